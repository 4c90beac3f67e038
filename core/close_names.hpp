// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Close names for "did you mean" hints: the optimal-string-alignment distance (Damerau–Levenshtein without
// repeated edits of a substring: insertions, deletions, substitutions and swaps of two neighbours, one edit each).
#include <cstddef>
#include <string>
#include <vector>

namespace imcol {

/// The edits that turn `a` into `b`.
std::size_t edit_distance(const std::string& a, const std::string& b);

/// The edits a name of `size` characters may be off by and still be close: 1 up to 4 characters, else 2 (or a
/// third of the name, when more).
std::size_t allowed_edits(std::size_t size);

/// The candidates within allowed_edits(name) of `name`, closest first (ties in the candidates' order), at most `most`.
std::vector<std::string> close_names(const std::string& name, const std::vector<std::string>& candidates, std::size_t most = 3);

/// "; did you mean 'x'?" (or "'x' or 'y'") for the closest candidates, "" when none is close.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates);

}  // namespace imcol
