// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Writing result files completely or not at all: write to a temporary file beside the target, then rename.
#include <filesystem>
#include <string>

namespace imcol {

/// Atomically replaces `path` with `content` (creates parent directories). Throws std::runtime_error.
void write_file_atomic(const std::filesystem::path& path, const std::string& content);

}  // namespace imcol
