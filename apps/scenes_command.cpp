// SPDX-License-Identifier: BSD-3-Clause
#include "apps/scenes_command.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <vector>

#include "core/scene_files.hpp"

namespace imcol {

namespace {

std::string folder_of(const study::SceneEntry& e) {
  const auto slash = e.name.rfind('/');
  return slash == std::string::npos ? std::string() : e.name.substr(0, slash + 1);
}

}  // namespace

int cmd_scenes(const std::string& pattern) {
  const std::vector<study::SceneEntry> entries = study::shipped_scenes(pattern);
  if (entries.empty()) {
    std::cout << "no shipped scene matches '" << pattern << "' (in " << scenes_dir() << ")\n";
    return 0;
  }
  std::size_t width = 0;
  for (const auto& e : entries) width = std::max(width, e.name.size());
  std::cout << "shipped scenes in " << scenes_dir() << " (imcol run NAME; a path to a file of your own works too)\n";
  std::string folder = "\x01";
  for (const auto& e : entries) {
    const std::string f = folder_of(e);
    if (f != folder) {
      folder = f;
      std::cout << "\n" << (f.empty() ? std::string("(top level)") : f) << "\n";
    }
    std::cout << "  " << std::left << std::setw(static_cast<int>(width)) << e.name << "  " << std::setw(22) << e.kind << "  "
              << e.description << "\n";
  }
  return 0;
}

}  // namespace imcol
