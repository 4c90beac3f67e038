// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// imcol.Scene: a scene's TOML text and the overrides set on it, read and checked as the command line reads a scene
// file and its --set options (core/scene.hpp load_scene / parse_scene).
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace imcol::python {

class PyScene {
 public:
  /// A file, or a shipped scene's name (core/scene_files.hpp find_scene), as `imcol run NAME` takes it.
  static PyScene load(const std::string& name_or_path);
  /// A scene given as TOML text; messages name it `<string>`.
  static PyScene from_toml(const std::string& text);

  /// Sets one key as `--set key=value_text` does (the same checks and messages); the scene is unchanged on error.
  void set(const std::string& key, const std::string& value_text);

  /// The scene with `extra` overrides after the scene's own, shared and immutable: the scene itself (no copy) without
  /// extra overrides. A run holds it while the GIL is released, so a set() meanwhile (which makes a new one) cannot
  /// change it under the run. With extra overrides the last ones and their scene are kept: a loop of
  /// run(scene, rtol=…) parses the scene once, not per call. Called with the GIL held (it guards the kept scene).
  std::shared_ptr<const Scene> snapshot(const std::vector<Override>& extra) const;

  const Scene& scene() const { return *scene_; }
  const std::string& path() const { return path_; }
  const std::string& text() const { return text_; }
  const std::vector<Override>& overrides() const { return overrides_; }

 private:
  PyScene(std::string path, std::string text);
  std::string path_, text_;
  std::vector<Override> overrides_;
  std::shared_ptr<const Scene> scene_;
  mutable std::vector<Override> last_extra_;  // snapshot()'s last extra overrides and their scene (null: none yet)
  mutable std::shared_ptr<const Scene> last_;
};

/// The argument `scene` of every call that takes one (`call`: "imcol.run", "Scene.load"): an imcol.Scene (the
/// object itself), or a shipped scene's name ("default", "coupled/gg3462") or the path of a scene file (str or
/// os.PathLike), read as Scene.load reads it. Raises ValueError naming the call: no such scene (with the close names
/// of shipped scenes), or the file's first bad line; TypeError for any other type.
pybind11::object scene_argument(const pybind11::handle& scene, const std::string& call);

}  // namespace imcol::python
