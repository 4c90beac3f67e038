// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading a whole input text file with a bound: what is not a regular file (a directory, a device such as /dev/zero,
// a FIFO) is refused before it is opened, and so is a file larger than the bound; the read itself stops at the bound.
// The one reader of imcol's input texts: scenes (core/toml_reader.hpp), measurements and calibration caches.
#include <cstdint>
#include <string>

namespace imcol {

/// "1 MiB", "64 MiB", "1000 bytes": a byte count as the messages write a bound.
std::string byte_count_text(std::uintmax_t bytes);

/// The whole text of `path`, a regular file of at most `max_bytes`. InputError(path, key, problem) otherwise, the
/// file named as "the WHAT file" (e.g. what = "scene": "is a directory, not a scene file"; "the scene file has N bytes,
/// more than the 1 MiB a scene may have"); `format` (e.g. "TOML") says what it should be: "a scene is a TOML text file".
std::string read_text_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes,
                           const std::string& format = "", const std::string& key = "");

}  // namespace imcol
