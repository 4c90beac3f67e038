// SPDX-License-Identifier: BSD-3-Clause
#include "core/report.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace imcol {

void write_file_atomic(const std::filesystem::path& path, const std::string& content) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
  if (ec) throw std::runtime_error("cannot create directory " + path.parent_path().string() + ": " + ec.message());
  fs::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string() + ": " + std::strerror(errno));
    errno = 0;
    out << content;
    out.flush();
    if (!out) {
      const int err = errno;
      fs::remove(tmp, ec);
      throw std::runtime_error("write failed for " + path.string() + (err ? std::string(": ") + std::strerror(err) : std::string()));
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot move " + tmp.string() + " to " + path.string());
  }
}

}  // namespace imcol
