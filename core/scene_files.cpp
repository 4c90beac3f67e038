// SPDX-License-Identifier: BSD-3-Clause
#include "core/scene_files.hpp"

#include <algorithm>
#include <filesystem>
#include <string_view>

#include "core/close_names.hpp"
#include "core/errors.hpp"
#include "core/materials.hpp"

namespace imcol {

namespace {

namespace fs = std::filesystem;

/// The file name a shipped scene's name stands for: ".toml" added if missing, a leading "data/scenes/" dropped.
std::string shipped_file(const std::string& arg) {
  constexpr std::string_view kReadmePrefix = "data/scenes/";
  const std::string name = arg.starts_with(kReadmePrefix) ? arg.substr(kReadmePrefix.size()) : arg;
  return name.ends_with(".toml") ? name : name + ".toml";
}

}  // namespace

std::vector<std::string> close_scene_names(const std::string& name) {
  std::vector<std::pair<std::size_t, std::string>> scored;
  const std::size_t allowed = std::max<std::size_t>(2, name.size() / 3);
  for (const auto& s : shipped_scene_names()) {
    const std::string last = s.substr(s.rfind('/') + 1);
    std::size_t d = std::min(edit_distance(name, s), edit_distance(name, last));
    if (name.size() >= 3 && s.find(name) != std::string::npos) d = std::min<std::size_t>(d, 1);
    if (d <= allowed) scored.push_back({d, s});
  }
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (std::size_t i = 0; i < scored.size() && i < 5; ++i) out.push_back(scored[i].second);
  return out;
}

std::string scenes_dir() { return (fs::path(data_dir()) / "scenes").string(); }

std::optional<std::string> locate_scene(const std::string& arg) {
  std::error_code ec;
  const std::string file = shipped_file(arg);
  const fs::path shipped = fs::path(scenes_dir()) / file;
  const bool is_shipped = !fs::path(file).is_absolute() && fs::is_regular_file(shipped, ec);
  // A folder is never a scene: `default` beside an output folder of that name is the shipped scene.
  if (!arg.empty() && fs::exists(arg, ec) && !(is_shipped && fs::is_directory(arg, ec))) return arg;
  if (is_shipped) return shipped.string();
  return std::nullopt;
}

std::string find_scene(const std::string& arg) {
  if (arg.empty()) throw InputError("command line", "scene", "empty scene argument (give a scene file or a shipped scene's name: imcol scenes lists them)");
  if (auto path = locate_scene(arg)) return *path;
  std::error_code ec;
  const std::string file = shipped_file(arg);
  std::string msg = "no scene '" + arg + "': no file " + (fs::absolute(arg, ec)).string() + " (relative to the current folder), and no " +
                    file + " in " + scenes_dir() + " (imcol scenes lists the shipped scenes)";
  const auto close = close_scene_names(file.substr(0, file.size() - 5));
  if (!close.empty()) {
    msg += "; close names:";
    for (std::size_t i = 0; i < close.size(); ++i) msg += (i ? ", " : " ") + close[i];
  }
  throw InputError("command line", "scene", msg);
}

std::vector<std::string> shipped_scene_names() {
  std::vector<std::string> out;
  std::error_code ec;
  const fs::path dir = scenes_dir();
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec) || it->path().extension() != ".toml") continue;
    std::string rel = it->path().lexically_relative(dir).generic_string();
    out.push_back(rel.substr(0, rel.size() - 5));
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace imcol
