// SPDX-License-Identifier: BSD-3-Clause
// imcol.sweep and imcol.SweepResult: e against St over values of one quantity, as `imcol sweep` runs it: the points'
// scenes from study/sweep_points.hpp sweep_scenes (all checked before anything runs), the points run by
// study/sweep.hpp run_sweep on this process's threads, the GIL released for both, and sweep.csv's columns
// (sweep_columns) as NumPy arrays.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>

#include "study/sweep.hpp"
#include "study/sweep_columns.hpp"
#include "core/errors.hpp"
#include "python/bindings.hpp"
#include "python/call.hpp"
#include "python/interrupt.hpp"
#include "python/convert.hpp"
#include "python/scene.hpp"
#include "python/sweep.hpp"
#include "python/table.hpp"

namespace py = pybind11;

namespace imcol::python {

using study::SweepPoint;

namespace sweep_impl {  // this file's helpers: named, as the module is one unity unit

py::array_t<double> number_array(const std::vector<SweepPoint>& pts, std::optional<double> (*get)(const SweepPoint&)) {
  py::array_t<double> a(static_cast<py::ssize_t>(pts.size()));
  auto v = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < pts.size(); ++i) v(static_cast<py::ssize_t>(i)) = get(pts[i]).value_or(NAN);
  return a;
}

py::object word_array(const std::vector<SweepPoint>& pts, std::string (*get)(const SweepPoint&)) {
  py::list words;
  for (const auto& p : pts) words.append(get(p));
  return py::module_::import("numpy").attr("array")(words, py::arg("dtype") = "str");
}

PySweepResult make_result(const std::string& vary, const std::vector<SweepPoint>& pts) {
  PySweepResult r;
  r.vary = vary;
  r.column = study::sweep_column(vary);
  auto put = [&](const std::string& name, py::object a) {
    r.columns.append(name);
    r.table[py::str(name)] = std::move(a);
  };
  py::array_t<long long> point(static_cast<py::ssize_t>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i) point.mutable_at(static_cast<py::ssize_t>(i)) = static_cast<long long>(i);
  put("point", point);
  put(r.column, number_array(pts, [](const SweepPoint& p) { return std::optional<double>(p.value); }));
  for (const auto& c : study::sweep_columns()) put(c.name, c.number ? py::object(number_array(pts, c.number)) : word_array(pts, c.word));
  return r;
}

std::vector<double> values_from(const py::handle& values) {
  py::array_t<double, py::array::c_style | py::array::forcecast> a = py::module_::import("numpy").attr("asarray")(values, "float64");
  if (a.ndim() != 1)
    throw InputError("imcol.sweep", "values", "must be one-dimensional (" + std::to_string(a.ndim()) + " dimensions given)");
  return std::vector<double>(a.data(), a.data() + a.size());
}

PySweepResult sweep(const py::object& scene_arg, const std::string& vary, const py::object& values_arg, int jobs,
                    const std::optional<py::object>& rtol, const std::optional<py::object>& atol,
                    const std::optional<std::string>& integrator, const py::object& progress) {
  require_numpy("imcol.sweep");  // before anything runs: its values and its result are arrays
  check_progress_callable(progress, "imcol.sweep");
  const PyScene scene = scene_argument(scene_arg, "imcol.sweep").cast<PyScene>();
  study::check_sweep_quantity(vary, "imcol.sweep", "vary");
  if (values_arg.is_none()) throw InputError("imcol.sweep", "values", "None: give the values of " + vary + " (SI units)");
  const std::vector<double> values = values_from(values_arg);
  study::check_sweep_values(vary, values, "imcol.sweep", "values");
  if (jobs < 0) throw InputError("imcol.sweep", "jobs", "must be >= 0 (0 = all cores)");

  // The scene's keys, then the solver's as given here (as --set, then --rtol/--atol/--integrator), then the point's.
  std::vector<Override> overrides = scene.overrides();
  for (auto& o : solver_overrides(rtol, atol, integrator)) overrides.push_back(o);
  const auto load = [&](const std::vector<Override>& ov) { return parse_scene(scene.text(), scene.path(), ov); };

  study::SweepResult run;
  bool liquid = false, pair = false;
  Scene base_scene;
  // Reading the points' scenes and running them touch no Python object.
  call_interruptibly(
      [&] {
        const Scene base = load(overrides);
        liquid = base.fluid.has_value();
        pair = base.spheres.size() == 2;
        base_scene = base;
        const std::vector<Scene> scenes = study::sweep_scenes(load, overrides, base, vary, values);
        run = study::run_sweep(scenes, vary, values, study::threads(jobs), interruptible_hooks());
      },
      progress);
  PySweepResult r = make_result(vary, run.points);
  r.result = std::move(run);
  r.liquid = liquid;
  r.pair = pair;
  r.base = std::move(base_scene);
  return r;
}

py::object column(const PySweepResult& r, const std::string& name) { return r.table[py::str(name)]; }

}  // namespace sweep_impl

void bind_sweep(py::module_& m) {
  using namespace sweep_impl;
  py::class_<PySweepResult>(m, "SweepResult",
                            "A sweep's points as NumPy arrays, one per column of sweep.csv (`columns`, `table[name]`); "
                            "every column is also an attribute: r.St_B_eq_6_2, r.steps, …")
      .def_readonly("vary", &PySweepResult::vary, "The varied quantity.")
      .def_readonly("column", &PySweepResult::column, "sweep.csv's column of the varied quantity (\"velocity_m_s\").")
      .def_property_readonly("values", [](const PySweepResult& r) { return column(r, r.column); }, "The varied quantity's values (SI units).")
      .def_property_readonly("St", [](const PySweepResult& r) { return column(r, "St"); }, "Stokes number at impact (NaN where a point failed).")
      .def_property_readonly("e", [](const PySweepResult& r) { return column(r, "e"); }, "Restitution coefficient (NaN where not measured).")
      .def_property_readonly("status", [](const PySweepResult& r) { return column(r, "status"); }, "\"ok\" or \"failed\" per point.")
      .def_property_readonly("messages", [](const PySweepResult& r) { return column(r, "message"); },
                             "Per point: why e is missing, which measures disagree, the t_end it took, or why the point failed; \"\" if none.")
      .def_property_readonly("columns", [](const PySweepResult& r) { return r.columns.attr("copy")(); }, "The columns, in sweep.csv's order.")
      .def_readonly("table", &PySweepResult::table, "Column name -> NumPy array.")
      .def("to_dict", [](const PySweepResult& r) { return py::module_::import("copy").attr("deepcopy")(r.table); },
           "The columns as a dict of NumPy arrays (copies), in sweep.csv's order: pandas.DataFrame(r.to_dict()).")
      .def("__len__", [](const PySweepResult& r) { return py::len(column(r, "point")); })
      .def("__getattr__",
           [](const PySweepResult& r, const std::string& name) -> py::object {
             if (r.table.contains(name)) return r.table[py::str(name)];
             throw py::attribute_error("imcol.SweepResult has no attribute '" + name + "'");
           })
      .def("__dir__", [](const py::object& self) { return dir_with_columns(self, self.cast<const PySweepResult&>().columns); })
      .def("__repr__", [](const PySweepResult& r) {
        const auto n = py::len(column(r, "point"));
        py::ssize_t failed = 0;
        for (const auto& s : column(r, "status"))
          if (s.cast<std::string>() != "ok") ++failed;
        return "imcol.SweepResult(vary='" + r.vary + "', points=" + std::to_string(n) + ", failed=" + std::to_string(failed) + ")";
      });

  m.def("sweep", in_call("imcol.sweep", &sweep), py::arg("scene"), py::arg("vary") = "velocity", py::kw_only(), py::arg("values"), py::arg("jobs") = 0,
        py::arg("rtol") = py::none(), py::arg("atol") = py::none(), py::arg("integrator") = py::none(), py::arg("progress") = py::none(),
        "Runs a scene (an imcol.Scene, a shipped scene's name or a scene file's path) at each of `values` (required, by keyword) of `vary` (imcol.sweep_quantities()) as "
        "`imcol sweep` does, on `jobs` threads (0: all cores), the GIL released. rtol, atol, integrator: as --rtol, "
        "--atol, --integrator. Bad input raises ValueError naming the point before anything runs; a point that fails "
        "is reported in `status` and `messages`, never raised. Ctrl-C stops the points in flight within a step "
        "(KeyboardInterrupt). progress: None or progress(done, total, eta_s), points finished of all. Returns an imcol.SweepResult.");
}

}  // namespace imcol::python
