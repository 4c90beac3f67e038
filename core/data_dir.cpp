// SPDX-License-Identifier: BSD-3-Clause
#include "core/data_dir.hpp"

#include <cstdlib>
#include <mutex>

namespace imcol {

namespace {
std::mutex& data_dir_mutex() {
  static std::mutex m;
  return m;
}
std::string& data_dir_setting() {
  static std::string dir;
  return dir;
}
}  // namespace

std::string data_dir() {
  if (const char* d = std::getenv("IMCOL_DATA_DIR"); d && *d) return d;
  {
    std::lock_guard lock(data_dir_mutex());
    if (!data_dir_setting().empty()) return data_dir_setting();
  }
  return IMCOL_DATA_DIR;
}

void set_data_dir(const std::string& dir) {
  std::lock_guard lock(data_dir_mutex());
  data_dir_setting() = dir;
}

}  // namespace imcol
