// SPDX-License-Identifier: BSD-3-Clause
#include "python/scene.hpp"

#include <algorithm>

#include "core/scene_files.hpp"
#include "core/toml_reader.hpp"
#include "python/bindings.hpp"
#include "python/call.hpp"
#include "python/convert.hpp"

namespace py = pybind11;

namespace imcol::python {

PyScene::PyScene(std::string path, std::string text)
    : path_(std::move(path)), text_(std::move(text)), scene_(std::make_shared<const Scene>(parse_scene(text_, path_))) {}

PyScene PyScene::load(const std::string& name_or_path) {
  const std::string path = find_scene(name_or_path);
  return PyScene(path, read_scene_file(path));
}

PyScene PyScene::from_toml(const std::string& text) { return PyScene("<string>", text); }

namespace scene_impl {  // this file's helpers: named, as the module is one unity unit

/// Whether `inner` names `outer` or a node inside it.
bool inside(const std::vector<std::string>& inner, const std::vector<std::string>& outer) {
  return !outer.empty() && inner.size() >= outer.size() && std::equal(outer.begin(), outer.end(), inner.begin());
}

/// "; did you mean 'a', 'b' or 'c'?" for the shipped scenes close to `name`, "" when none is.
std::string close_scenes_hint(const std::string& name) {
  const std::string stem = name.ends_with(".toml") ? name.substr(0, name.size() - 5) : name;
  const auto close = close_scene_names(stem);
  std::string s;
  for (std::size_t i = 0; i < close.size() && i < 3; ++i)
    s += (i == 0 ? "; did you mean '" : i + 1 == std::min<std::size_t>(close.size(), 3) ? " or '" : ", '") + close[i] + "'";
  return s.empty() ? s : s + "?";
}

/// The scene a name or path stands for, read; errors name `call`.
PyScene scene_from_name(const std::string& name, const std::string& call) {
  const auto path = locate_scene(name);
  if (!path)
    throw py::value_error(call + ": scene '" + name + "': no shipped scene or file of that name (imcol.scenes() lists the shipped scenes)" +
                          close_scenes_hint(name));
  try {
    return PyScene::load(*path);
  } catch (const InputError& e) {
    throw py::value_error(call_message(call, e));
  }
}

}  // namespace scene_impl

py::object scene_argument(const py::handle& scene, const std::string& call) {
  if (py::isinstance<PyScene>(scene)) return py::reinterpret_borrow<py::object>(scene);
  const py::object os = py::module_::import("os");
  if (py::isinstance<py::str>(scene) || py::isinstance(scene, os.attr("PathLike")))
    return py::cast(scene_impl::scene_from_name(os.attr("fspath")(scene).cast<std::string>(), call));
  throw py::type_error(call + ": scene must be an imcol.Scene, a shipped scene's name or the path of a scene file (got " +
                       py::str(py::type::of(scene).attr("__name__")).cast<std::string>() + ")");
}

void PyScene::set(const std::string& key, const std::string& value_text) {
  // Overrides apply in order, each replacing the node its key names, so an earlier override of this key, or of a
  // node inside it, is overwritten by this one whatever lies between: it is dropped, and the scene read is the one
  // --set would give with every override kept. The overrides stay one per key, and set's cost with them.
  Override ov = parse_override(key + "=" + value_text);
  const auto path = key_path(ov.key);
  std::vector<Override> trial;
  trial.reserve(overrides_.size() + 1);
  for (const auto& o : overrides_)
    if (!scene_impl::inside(key_path(o.key), path)) trial.push_back(o);
  trial.push_back(std::move(ov));
  scene_ = std::make_shared<const Scene>(parse_scene(text_, path_, trial));
  overrides_ = std::move(trial);
  last_.reset();  // made with the overrides before this one
}

std::shared_ptr<const Scene> PyScene::snapshot(const std::vector<Override>& extra) const {
  if (extra.empty()) return scene_;
  const auto same = [](const Override& a, const Override& b) { return a.key == b.key && a.value == b.value; };
  if (last_ && std::equal(extra.begin(), extra.end(), last_extra_.begin(), last_extra_.end(), same)) return last_;
  auto all = overrides_;
  all.insert(all.end(), extra.begin(), extra.end());
  auto sc = std::make_shared<const Scene>(parse_scene(text_, path_, all));
  last_extra_ = extra;
  last_ = sc;
  return sc;
}

void bind_scene(py::module_& m) {
  py::class_<PyScene>(m, "Scene", "A scene: a TOML file or text, with keys set on it as the command line's --set does.")
      .def_static(
          "load", [](const py::object& name_or_path) { return scene_argument(name_or_path, "Scene.load"); }, py::arg("name_or_path"),
          "A scene file (str or os.PathLike), or a shipped scene's name (\"default\", \"coupled/gg3462\"), as `imcol run` "
          "takes it; an imcol.Scene is returned as it is.")
      .def_static("from_toml", in_call("Scene.from_toml", &PyScene::from_toml), py::arg("text"), "A scene given as TOML text.")
      .def(
          "set",
          [](PyScene& s, const std::string& key, const py::handle& value) -> PyScene& {
            const std::string text = toml_value_text(value);
            try {
              s.set(key, text);
            } catch (const InputError& e) {
              throw py::value_error(call_message("Scene.set('" + key + "')", e));
            }
            return s;
          },
          py::arg("key"), py::arg("value"), py::return_value_policy::reference_internal,
          "Sets a dotted key as `--set key=value` does, with the same checks and messages (ValueError); returns the "
          "scene. A str is taken as --set takes its text (a bare word is a string); numbers, bools and lists as TOML; "
          "NumPy scalars and arrays by their kind (numpy.bool_ a bool, integers an int, floats a float, arrays lists). "
          "A later set of a key replaces the earlier one, and the keys set inside it (`overrides` keeps each key once).")
      .def_property_readonly("name", [](const PyScene& s) { return s.scene().name; })
      .def_property_readonly("path", &PyScene::path, "The file the scene was read from (`<string>` for from_toml).")
      .def_property_readonly("description", [](const PyScene& s) { return s.scene().description; })
      .def_property_readonly("toml", &PyScene::text, "The scene's TOML text, before the keys set on it.")
      .def_property_readonly(
          "overrides",
          [](const PyScene& s) {
            py::list out;
            for (const auto& o : s.overrides()) out.append(o.key + "=" + o.value);
            return out;
          },
          "The keys set, as --set options would give them: each key once, at its latest value, in the order set.")
      .def("__copy__", [](const PyScene& s) { return s; })
      .def("__deepcopy__", [](const PyScene& s, const py::dict&) { return s; }, py::arg("memo"))
      .def("__repr__", [](const PyScene& s) {
        std::string r = "imcol.Scene('" + s.scene().name + "', path='" + s.path() + "'";
        if (!s.overrides().empty()) r += ", " + std::to_string(s.overrides().size()) + " keys set";
        return r + ")";
      });
}

}  // namespace imcol::python
