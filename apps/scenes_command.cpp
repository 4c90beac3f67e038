// SPDX-License-Identifier: BSD-3-Clause
#include "apps/scenes_command.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <vector>

#include "core/errors.hpp"
#include "core/scene.hpp"
#include "core/scene_files.hpp"
#include "flow/flow_scene.hpp"

namespace imcol {

namespace {

struct Entry {
  std::string name, kind, description;
};

/// A collision scene's kind from its configuration; a flow scene (data/scenes/flow/) is "flow".
Entry describe(const std::string& name) {
  const std::string path = (std::filesystem::path(scenes_dir()) / (name + ".toml")).string();
  try {
    const Scene sc = load_scene(path);
    std::string kind = sc.wall ? "sphere-wall" : sc.two_spheres() ? "sphere-sphere" : "free sphere";
    if (sc.has(Effect::flow)) kind += ", coupled";
    return {name, kind, sc.description};
  } catch (const InputError& collision_error) {
    try {
      const flow::FlowScene fsc = flow::load_flow_scene(path);
      return {name, "flow", fsc.description};
    } catch (const InputError&) {
      return {name, "unreadable", collision_error.what()};
    }
  }
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool matches(const Entry& e, const std::string& pattern) {
  if (pattern.empty()) return true;
  if (pattern.find_first_of("*?[") != std::string::npos) return fnmatch(pattern.c_str(), e.name.c_str(), 0) == 0;
  const std::string p = lower(pattern);
  return lower(e.name).find(p) != std::string::npos || lower(e.description).find(p) != std::string::npos;
}

std::string folder_of(const Entry& e) {
  const auto slash = e.name.rfind('/');
  return slash == std::string::npos ? std::string() : e.name.substr(0, slash + 1);
}

/// The shipped scenes matching `pattern`, grouped by folder: the top level first, then each folder in order.
std::vector<Entry> matching(const std::string& pattern) {
  std::vector<Entry> entries;
  for (const auto& name : shipped_scene_names()) {
    Entry e = describe(name);
    if (matches(e, pattern)) entries.push_back(e);
  }
  std::stable_sort(entries.begin(), entries.end(), [&](const Entry& a, const Entry& b) { return folder_of(a) < folder_of(b); });
  return entries;
}

}  // namespace

std::vector<std::string> matching_scenes(const std::string& pattern) {
  std::vector<std::string> out;
  for (const auto& e : matching(pattern)) out.push_back(e.name);
  return out;
}

int cmd_scenes(const std::string& pattern) {
  const std::vector<Entry> entries = matching(pattern);
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
