// SPDX-License-Identifier: BSD-3-Clause
// imcol.run and imcol.Result: one run of a scene (run/simulate.hpp, the code path of `imcol run`) and what it
// measured, read from its RunResult: e, St and the named measures, the summary (summary.json as a dict), the
// trajectory as NumPy arrays by column name, the warnings and the solver's statistics.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>

#include "core/errors.hpp"
#include "python/bindings.hpp"
#include "python/call.hpp"
#include "python/interrupt.hpp"
#include "python/convert.hpp"
#include "python/scene.hpp"
#include "run/simulate.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace result_impl {  // this file's helpers: named, as the module is one unity unit

py::dict columns_as_arrays(const RunResult& r);

/// The run and its Python views, made on first use (a caller reading only e and St pays for neither).
struct PyResult {
  RunResult run;
  const py::object& summary() {  // summary.json as a dict
    if (!summary_) summary_ = to_python(run.summary_json);
    return summary_;
  }
  const py::object& view() {  // the summary as typed attributes (imcol._summary.Summary)
    if (!view_) view_ = py::module_::import("imcol._summary").attr("Summary")(summary());
    return view_;
  }
  const py::object& trajectory() {  // a dict: column name -> 1-D float64 array
    if (!trajectory_) {
      require_numpy("imcol.Result.trajectory");
      trajectory_ = columns_as_arrays(run);
    }
    return trajectory_;
  }

 private:
  py::object summary_, view_, trajectory_;  // null until first use
};

py::dict columns_as_arrays(const RunResult& r) {
  py::dict out;
  const std::size_t n = r.rows.size();
  for (std::size_t c = 0; c < r.columns.size(); ++c) {
    py::array_t<double> a(static_cast<py::ssize_t>(n));
    auto v = a.mutable_unchecked<1>();
    for (std::size_t i = 0; i < n; ++i) v(static_cast<py::ssize_t>(i)) = c < r.rows[i].size() ? r.rows[i][c] : NAN;
    out[py::str(r.columns[c])] = std::move(a);
  }
  return out;
}

Recording recording_from(const std::string& record) {
  if (record == "full") return Recording::full;
  if (record == "kinematics") return Recording::kinematics;
  throw InputError("imcol.run", "record", "must be full or kinematics (got '" + record + "')");
}

std::shared_ptr<PyResult> run(const py::object& scene_arg, const std::optional<py::object>& rtol,
                              const std::optional<py::object>& atol, const std::optional<std::string>& integrator,
                              const std::string& record, const py::object& progress) {
  const Recording rec = recording_from(record);
  check_progress_callable(progress, "imcol.run");
  const py::object scene = scene_argument(scene_arg, "imcol.run");  // a given Scene itself: its snapshot kept
  const auto sc = scene.cast<const PyScene&>().snapshot(solver_overrides(rtol, atol, integrator));  // no copy without options
  auto out = std::make_shared<PyResult>();
  // No sink: a coupled run computes no flow fields (nothing would keep them).
  call_interruptibly([&] { out->run = simulate(*sc, false, rec); }, progress);
  return out;
}

py::object opt(const std::optional<double>& v) { return v ? py::object(py::float_(*v)) : py::object(py::none()); }

/// The summary's view (imcol.Summary) on a result: to_dict, its names as the result's attributes, dir and repr.
void add_summary_view(py::class_<PyResult, std::shared_ptr<PyResult>>& c) {
  c.def("to_dict", [](PyResult& r) { return py::module_::import("copy").attr("deepcopy")(r.summary()); },
           "The summary as summary.json writes it, as a dict.")
      .def("__getattr__",
           [](PyResult& r, const std::string& name) -> py::object {
             // The summary's names: result.solver.steps, result.contact.law, result.flow (None without the flow kernel).
             if (py::hasattr(r.view(), name.c_str())) return r.view().attr(name.c_str());
             throw py::attribute_error("imcol.Result has no attribute '" + name + "'");
           })
      .def("__dir__",
           [](py::object self) {
             py::set names(py::module_::import("builtins").attr("object").attr("__dir__")(self));
             for (const auto& n : py::module_::import("builtins").attr("dir")(self.cast<PyResult&>().view())) names.add(n);
             py::list out(names);
             out.attr("sort")();
             return out;
           })
      .def("__repr__", [](const PyResult& r) {
        const auto& s = r.run.summary;
        auto num = [](const std::optional<double>& v) { return v ? fmt_number(*v) : std::string("None"); };
        return "imcol.Result(scene='" + s.scene + "', e=" + num(s.e) + ", St=" + num(s.St) + ")";
      });
}

}  // namespace result_impl

void bind_run(py::module_& m) {
  using namespace result_impl;
  py::class_<PyResult, std::shared_ptr<PyResult>> result(m, "Result",
                                                  "What a run measured. The summary's names are attributes with their "
                                                  "types: result.Re, result.solver.steps, result.contact.law, result.flow "
                                                  "(None where the run has no such block).");
  result.def_property_readonly("e", [](const PyResult& r) { return opt(r.run.summary.e); },
                             "Restitution coefficient by the measure `e_is` names; None without one (see e_missing).")
      .def_property_readonly("St", [](const PyResult& r) { return opt(r.run.summary.St); }, "Stokes number at impact.")
      // Read from the typed summary: timing a loop of runs does not build the summary's Python view.
      .def_property_readonly("wall_time_s", [](const PyResult& r) { return r.run.summary.wall_time_s; },
                             "The integration's wall time (s), as summary.json's wall_time_s.")
      .def_property_readonly("setup_time_s", [](const PyResult& r) { return r.run.summary.setup_time_s; },
                             "The model's set-up time (s), as summary.json's setup_time_s.")
      .def_property_readonly(
          "measures",
          [](const PyResult& r) {
            py::dict d;
            for (const auto& [m, e] : r.run.summary.e_measures) d[py::str(to_string(m))] = opt(e);
            return d;
          },
          "The first contact's named measures of e, name -> e (None where not measured).")
      .def_property_readonly("warnings", [](const PyResult& r) { return r.run.summary.warnings; })
      .def_property_readonly(
          "stats",
          [](const PyResult& r) {
            const auto& s = r.run.summary.solver.stats;
            py::dict d;
            for (const auto& [k, v] : s.as_map()) d[py::str(k)] = v;
            d["linear_solver"] = s.linear_solver;
            d["state_size"] = s.state_size;
            return d;
          },
          "The solver's statistics (steps, rhs_evals, …).")
      .def_property_readonly("bounces", [](PyResult& r) { return r.view().attr("bounces"); },
                             "The contacts (summary.json `bounces`), one imcol.Bounce each.")
      .def_property_readonly("columns", [](const PyResult& r) { return r.run.columns; }, "The trajectory's columns.")
      .def_property_readonly("trajectory", [](PyResult& r) { return r.trajectory(); },
                             "The trajectory samples: column name -> NumPy array (result.trajectory[\"u1\"]).")
      .def_property_readonly("summary", [](PyResult& r) { return r.view(); },
                             "The summary as typed attributes (imcol.Summary); its blocks are also the result's.");
  add_summary_view(result);

  m.def("run", in_call("imcol.run", &run), py::arg("scene"), py::arg("rtol") = py::none(), py::arg("atol") = py::none(),
        py::arg("integrator") = py::none(), py::arg("record") = "full", py::arg("progress") = py::none(),
        "Runs a scene (an imcol.Scene, a shipped scene's name or a scene file's path) as `imcol run` does (rtol, atol, integrator: as --rtol, --atol, --integrator). record: \"full\" "
        "(forces in the trajectory) or \"kinematics\" (positions, velocities and events only, faster). The GIL is "
        "released while it runs; Ctrl-C stops it within a step (KeyboardInterrupt). progress: None or "
        "progress(done, total, eta_s), simulated s of t_end. Raises ValueError (bad input) or imcol.SolverError.");
}

}  // namespace imcol::python
