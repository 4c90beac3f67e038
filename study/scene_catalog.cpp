// SPDX-License-Identifier: BSD-3-Clause
#include "study/scene_catalog.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/errors.hpp"
#include "core/scene.hpp"
#include "core/scene_files.hpp"
#include "flow/flow_scene.hpp"

namespace imcol::study {

namespace {

/// A collision scene's kind from its configuration; a flow scene (data/scenes/flow/) is "flow".
SceneEntry describe_entry(const std::string& name) {
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

std::string lower_case(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool matches_pattern(const SceneEntry& e, const std::string& pattern) {
  if (pattern.empty()) return true;
  if (pattern.find_first_of("*?[") != std::string::npos) return fnmatch(pattern.c_str(), e.name.c_str(), 0) == 0;
  const std::string p = lower_case(pattern);
  return lower_case(e.name).find(p) != std::string::npos || lower_case(e.description).find(p) != std::string::npos;
}

std::string scene_folder(const SceneEntry& e) {
  const auto slash = e.name.rfind('/');
  return slash == std::string::npos ? std::string() : e.name.substr(0, slash + 1);
}

}  // namespace

std::vector<SceneEntry> shipped_scenes(const std::string& pattern) {
  std::vector<SceneEntry> entries;
  for (const auto& name : shipped_scene_names()) {
    SceneEntry e = describe_entry(name);
    if (matches_pattern(e, pattern)) entries.push_back(e);
  }
  std::stable_sort(entries.begin(), entries.end(), [&](const SceneEntry& a, const SceneEntry& b) { return scene_folder(a) < scene_folder(b); });
  return entries;
}


std::vector<std::string> matching_scenes(const std::string& pattern) {
  std::vector<std::string> out;
  for (const auto& e : shipped_scenes(pattern)) out.push_back(e.name);
  return out;
}

}  // namespace imcol::study
