// SPDX-License-Identifier: BSD-3-Clause
// imcol.work_precision and imcol.validate_seed: the ladders of study/work_precision.hpp and the seed's Table 6.1 of
// study/validate.hpp, run as `imcol work-precision` and `imcol validate seed` run them (the GIL released), their
// tables (work_precision.csv's, validate_seed.csv's columns) as NumPy arrays.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>

#include "core/errors.hpp"
#include "python/bindings.hpp"
#include "python/call.hpp"
#include "python/interrupt.hpp"
#include "python/convert.hpp"
#include "python/scene.hpp"
#include "python/table.hpp"
#include "run/summary_json.hpp"
#include "study//validate.hpp"
#include "study/work_precision.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace studies_precision_impl {  // this file's helpers: named, as the module is one unity unit

/// A study's table: its column names in the CSV's order and name -> 1-D array (numbers float64 with NaN where
/// missing, integers int64, words str).
struct PyTable {
  py::list columns;
  py::dict table;
};

template <class Row, class Cell>
PyTable make_table(const std::vector<study::RowColumn<Cell>>& columns, const std::vector<Row>& rows,
                   const std::function<Cell(const Row&)>& cell) {
  PyTable t;
  const auto n = static_cast<py::ssize_t>(rows.size());
  for (const auto& c : columns) {
    py::object a;
    if (c.kind == study::RowColumn<Cell>::word) {
      py::list words;
      for (const auto& r : rows) words.append(c.text(cell(r)));
      a = py::module_::import("numpy").attr("array")(words, py::arg("dtype") = "str");
    } else if (c.kind == study::RowColumn<Cell>::integer) {
      py::array_t<long long> v(n);
      for (py::ssize_t i = 0; i < n; ++i) v.mutable_at(i) = static_cast<long long>(c.value(cell(rows[static_cast<std::size_t>(i)])));
      a = v;
    } else {
      py::array_t<double> v(n);
      for (py::ssize_t i = 0; i < n; ++i) v.mutable_at(i) = c.value(cell(rows[static_cast<std::size_t>(i)]));
      a = v;
    }
    t.columns.append(c.name);
    t.table[py::str(c.name)] = a;
  }
  return t;
}

struct PyWorkPrecision : PyTable {
  study::WorkPrecisionResult result;
  py::dict reference, observed_order, cheapest;
};

struct PyValidate : PyTable {
  study::ValidateResult result;
  py::list agreement;
};

py::object optional_number(const std::optional<double>& v) { return v ? py::object(py::float_(*v)) : py::object(py::none()); }

/// The reference, the observed orders and the cheapest settings as dicts (the keys of work_precision.json).
void add_work_precision_blocks(PyWorkPrecision& r) {
  const auto& res = r.result;
  r.reference["integrator"] = res.reference.integrator_name();
  r.reference["evaluator"] = res.reference.evaluator_name();
  r.reference["rtol"] = res.ref_rtol;
  r.reference["history_tolerance"] = res.history ? py::object(py::float_(res.ref_history_tol)) : py::object(py::none());
  r.reference["value"] = res.value;
  r.reference["uncertainty"] = res.uncertainty;
  r.reference["wall_time_s"] = res.wall_time_s;
  r.reference["solver"] = to_python(run::Json(res.solver));
  for (const auto& o : res.orders)
    r.observed_order[py::str(o.config)] = py::dict(py::arg("vs") = o.vs, py::arg("exponent") = optional_number(o.exponent),
                                                   py::arg("order_in_steps") = optional_number(o.order_in_steps), py::arg("points") = o.points);
  for (const auto& c : res.cheapest) {
    py::object best = py::none();
    if (c.row) {
      const auto& p = res.rows[*c.row];
      best = py::dict(py::arg("config") = p.cfg.label(), py::arg("rtol") = p.rtol,
                      py::arg("direct_step_s") = std::isnan(p.direct_step) ? py::object(py::none()) : py::object(py::float_(p.direct_step)),
                      py::arg("median_ms") = p.ms, py::arg("error") = p.err_e);
    }
    r.cheapest[py::float_(c.target)] = best;
  }
}

std::vector<double> doubles_or(const std::optional<std::vector<double>>& v, const std::vector<double>& fallback) { return v ? *v : fallback; }

PyWorkPrecision work_precision(const py::object& scene_arg, const std::optional<std::vector<double>>& rtols,
                               const std::optional<std::vector<std::string>>& integrators, const std::optional<std::vector<std::string>>& evaluators,
                               int repeat, const std::optional<std::vector<double>>& direct_steps, double direct_rtol, double ref_rtol,
                               double ref_history_tolerance, bool add_history, int jobs, const py::object& progress) {
  require_numpy("imcol.work_precision");
  check_progress_callable(progress, "imcol.work_precision");
  const PyScene scene = scene_argument(scene_arg, "imcol.work_precision").cast<PyScene>();
  if (scene.scene().has(Effect::flow))
    throw InputError("imcol.work_precision", "scene", "a coupled scene: its ladders are the grid and the flow step (imcol work-precision)");
  if (jobs < 0) throw InputError("imcol.work_precision", "jobs", "must be >= 0 (0 = all cores)");
  study::WorkPrecisionOptions opt;
  opt.rtols = doubles_or(rtols, opt.rtols);
  if (integrators) opt.integrators = *integrators;
  if (evaluators) opt.evaluators = *evaluators;
  opt.direct_steps = doubles_or(direct_steps, opt.direct_steps);
  opt.direct_rtol = direct_rtol, opt.ref_rtol = ref_rtol, opt.ref_history_tol = ref_history_tolerance;
  opt.repeat = repeat, opt.add_history = add_history;
  PyWorkPrecision r;
  call_interruptibly(  // the runs touch no Python object
      [&] {
        const study::WorkPrecisionPlan plan = study::plan_work_precision(scene.scene(), opt);
        r.result = study::work_precision(plan, study::threads(jobs), interruptible_hooks());
      },
      progress);
  static_cast<PyTable&>(r) = make_table<study::WorkPrecisionRow, study::WorkPrecisionRow>(
      study::work_precision_columns(r.result.metric), r.result.rows, [](const study::WorkPrecisionRow& row) { return row; });
  add_work_precision_blocks(r);
  return r;
}

PyValidate validate_seed(const std::optional<std::vector<std::string>>& models, bool flow, double tolerance, int jobs,
                         const std::optional<py::object>& rtol, const std::optional<py::object>& atol,
                         const std::optional<std::string>& integrator, const py::object& progress) {
  require_numpy("imcol.validate_seed");
  check_progress_callable(progress, "imcol.validate_seed");
  if (jobs < 0) throw InputError("imcol.validate_seed", "jobs", "must be >= 0 (0 = all cores)");
  study::ValidateOptions opt;
  opt.flow = flow, opt.tolerance = tolerance;
  if (models) opt.models = *models;
  const std::vector<Override> overrides = solver_overrides(rtol, atol, integrator);
  PyValidate r;
  call_interruptibly([&] { r.result = study::validate_seed(opt, overrides, study::threads(jobs), interruptible_hooks()); },
                     progress);  // the runs touch no Python object
  const study::ValidateResult& res = r.result;
  static_cast<PyTable&>(r) = make_table<study::ValidateRow, study::ValidateCell>(
      study::validate_columns(res.flow), res.rows, [&res](const study::ValidateRow& row) { return study::ValidateCell{res, row}; });
  for (std::size_t set = 0; set < 2; ++set)
    for (std::size_t k = 0; k < res.models.size(); ++k)
      for (bool reduced : {false, true}) {
        if (reduced && !res.flow) continue;
        const auto& a = (reduced ? res.agreement_reduced : res.agreement)[set * res.models.size() + k];
        r.agreement.append(py::dict(py::arg("speed_set") = study::to_string(static_cast<study::SpeedSet>(set)),
                                    py::arg("model") = res.models[k].name, py::arg("run") = reduced || !res.flow ? "reduced-order" : "coupled",
                                    py::arg("within") = a.within, py::arg("runs") = a.runs, py::arg("largest") = a.worst,
                                    py::arg("largest_run") = a.worst_run));
      }
  return r;
}

/// The table's members of a result class: columns, table, to_dict, len, and each column as an attribute (and in dir()).
template <class T>
void bind_table(py::class_<T>& c, const char* name) {
  c.def_property_readonly("columns", [](const T& r) { return r.columns.attr("copy")(); }, "The columns, in the CSV file's order.")
      .def_readonly("table", &T::table, "Column name -> NumPy array.")
      .def("to_dict", [](const T& r) { return py::module_::import("copy").attr("deepcopy")(r.table); },
           "The columns as a dict of NumPy arrays (copies), in the CSV file's order: pandas.DataFrame(r.to_dict()).")
      .def("__len__", [](const T& r) { return r.columns.empty() ? 0 : py::len(r.table[r.columns[0]]); })
      .def("__getattr__", [name](const T& r, const std::string& key) -> py::object {
        if (r.table.contains(key)) return r.table[py::str(key)];
        throw py::attribute_error(std::string(name) + " has no attribute '" + key + "'");
      })
      .def("__dir__", [](const py::object& self) { return dir_with_columns(self, self.cast<const T&>().columns); });
}

}  // namespace studies_precision_impl

void bind_studies_precision(py::module_& m) {
  using namespace studies_precision_impl;
  py::class_<PyWorkPrecision> wp(m, "WorkPrecisionResult",
                                 "A work-precision ladder: its rungs as NumPy arrays, one per column of work_precision.csv "
                                 "(`columns`, `table[name]`, attributes); the reference, observed orders and cheapest settings.");
  bind_table(wp, "imcol.WorkPrecisionResult");
  wp.def_property_readonly("scene", [](const PyWorkPrecision& r) { return r.result.scene; })
      .def_property_readonly("metric", [](const PyWorkPrecision& r) { return r.result.metric; }, "\"e\", or \"u_end\" without a collision.")
      .def_readonly("reference", &PyWorkPrecision::reference, "The reference run: settings, value, uncertainty, solver block.")
      .def_property_readonly("skipped", [](const PyWorkPrecision& r) { return r.result.skipped; }, "Combinations skipped, with the reason.")
      .def_readonly("observed_order", &PyWorkPrecision::observed_order, "Per configuration: exponent vs rtol (or direct step), order in steps.")
      .def_readonly("cheapest", &PyWorkPrecision::cheapest, "Per target error (1e-3, 1e-6, 1e-9): the fastest setting that keeps it, or None.")
      .def("__repr__", [](const PyWorkPrecision& r) {
        return "imcol.WorkPrecisionResult(scene='" + r.result.scene + "', rungs=" + std::to_string(r.result.rows.size()) + ")";
      });
  m.def("work_precision", in_call("imcol.work_precision", &work_precision), py::arg("scene"), py::arg("rtols") = py::none(), py::arg("integrators") = py::none(),
        py::arg("evaluators") = py::none(), py::arg("repeat") = 3, py::arg("direct_steps") = py::none(), py::arg("direct_rtol") = 1e-10,
        py::arg("ref_rtol") = 1e-13, py::arg("ref_history_tolerance") = 1e-11, py::arg("add_history") = false, py::arg("jobs") = 1,
        py::arg("progress") = py::none(),
        "What accuracy costs, as `imcol work-precision` measures it on a collision scene (an imcol.Scene, a shipped scene's name or a scene file's path): an rtol "
        "ladder per integrator and history evaluator (the direct evaluator: a ladder of its step) against a reference at the "
        "tightest settings, `repeat` runs per rung (median wall time), on `jobs` threads (1: wall times not shared), the GIL "
        "released; Ctrl-C stops the runs in flight within a step (KeyboardInterrupt). progress: None or progress(done, total, "
        "eta_s), runs finished of all. Returns an imcol.WorkPrecisionResult.");

  py::class_<PyValidate> val(m, "ValidateResult",
                             "The seed's Table 6.1 against imcol: one row per run, model and speed set, as NumPy arrays, one per "
                             "column of validate_seed.csv (`columns`, `table[name]`, attributes); each model's agreement.");
  bind_table(val, "imcol.ValidateResult");
  val.def_property_readonly("flow", [](const PyValidate& r) { return r.result.flow; })
      .def_property_readonly("tolerance", [](const PyValidate& r) { return r.result.tolerance; })
      .def_readonly("agreement", &PyValidate::agreement, "Per speed set, model (and run): |e - e_seed| <= tolerance in `within` of `runs`.")
      .def("__repr__", [](const PyValidate& r) {
        return "imcol.ValidateResult(rows=" + std::to_string(r.result.rows.size()) + ", flow=" + (r.result.flow ? "True" : "False") + ")";
      });
  m.def("validate_seed", in_call("imcol.validate_seed", &validate_seed), py::arg("models") = py::none(), py::arg("flow") = false, py::arg("tolerance") = 0.05,
        py::arg("jobs") = 0, py::arg("rtol") = py::none(), py::arg("atol") = py::none(), py::arg("integrator") = py::none(),
        py::arg("progress") = py::none(),
        "The seed's Table 6.1 run as `imcol validate seed` runs it: each run with each model (\"seed\", \"asymptotic\"; None: "
        "both), reduced-order and with flow=True also coupled, at V_Io and at the speed that gives the printed St_B; on `jobs` "
        "threads (0: all cores), the GIL released; Ctrl-C stops the runs in flight within a step (KeyboardInterrupt). rtol, "
        "atol, integrator: as --rtol, --atol, --integrator. progress: None or progress(done, total, eta_s), runs finished "
        "of all. Returns an imcol.ValidateResult.");
}

}  // namespace imcol::python
