// SPDX-License-Identifier: BSD-3-Clause
// imcol.calibrate and imcol.CalibrationResult: a calibration (study/calibrate.hpp) as `imcol calibrate` runs it, on
// this process's threads with the GIL released; calibration.csv's columns as NumPy arrays, the fitted values, their
// intervals and profiles, the validation. progress(done, total, eta_s) after each evaluation; Ctrl-C ends the
// running evaluations at their next step and raises KeyboardInterrupt (python/interrupt.hpp).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

#include "core/errors.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/call.hpp"
#include "python/interrupt.hpp"
#include "python/scene.hpp"
#include "study/calibrate.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace calibrate_impl {  // this file's helpers: named, as the module is one unity unit

/// A calibration's result as Python values, made once under the GIL.
struct PyCalibration {
  std::string kind;  // "trajectory" or "table"
  py::list keys;
  py::dict values, start, intervals, profiles, evaluations, stage_wall_s, factor_rule;
  py::object objective, rms, tau_s, validation;
  bool ok = false, cancelled = false;
  std::size_t count = 0;
  int failed = 0, jobs = 1;
  double wall_time_s = 0;
};

py::object number(double v) { return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none()); }
py::object number(const std::optional<double>& v) { return v ? number(*v) : py::object(py::none()); }

/// The scene's file: the calibration reads it again for every evaluation.
std::string scene_file(const py::object& scene_arg, std::vector<Override>& overrides) {
  const PyScene scene = scene_argument(scene_arg, "imcol.calibrate").cast<PyScene>();
  if (scene.path() == "<string>")
    throw InputError("imcol.calibrate", "scene", "needs a scene file or a shipped scene's name (a scene from TOML text has no file)");
  overrides = scene.overrides();
  return scene.path();
}

/// `fit` as --fit texts: "KEY=LO:HI[:log]", a list of them, or {key: (lo, hi) or (lo, hi, "log")}.
std::vector<std::string> fit_texts(const py::object& fit) {
  std::vector<std::string> out;
  if (py::isinstance<py::str>(fit)) return {fit.cast<std::string>()};
  if (!py::isinstance<py::dict>(fit)) return fit.cast<std::vector<std::string>>();
  for (const auto& [key, range] : fit.cast<py::dict>()) {
    const auto r = range.cast<py::sequence>();
    if (r.size() != 2 && r.size() != 3)
      throw InputError("imcol.calibrate", "fit", "each key's range is (lo, hi) or (lo, hi, \"log\")");
    std::string text = key.cast<std::string>() + "=" + py::repr(py::float_(r[0].cast<double>())).cast<std::string>() + ":" +
                       py::repr(py::float_(r[1].cast<double>())).cast<std::string>();
    if (r.size() == 3) text += ":" + r[2].cast<std::string>();
    out.push_back(text);
  }
  return out;
}

/// `window` as --window's text: "A:B" or (A, B).
std::string window_text(const py::object& window) {
  if (window.is_none() || py::isinstance<py::str>(window)) return window.is_none() ? "" : window.cast<std::string>();
  const auto w = window.cast<std::pair<double, double>>();
  return py::repr(py::float_(w.first)).cast<std::string>() + ":" + py::repr(py::float_(w.second)).cast<std::string>();
}

/// The evaluations as calibration.csv's columns: numbers float64 (NaN where the CSV's cell is empty), words str.
py::dict evaluation_columns(const study::CalibrationInputs& in, const calib::SearchResult& s) {
  const auto n = static_cast<py::ssize_t>(s.evaluations.size());
  auto numbers = [&](const std::function<double(const calib::EvaluationRecord&)>& f) {
    py::array_t<double> a(n);
    for (py::ssize_t i = 0; i < n; ++i) {
      const double v = f(s.evaluations[static_cast<std::size_t>(i)]);
      a.mutable_at(i) = std::isfinite(v) ? v : NAN;
    }
    return py::object(a);
  };
  auto words = [&](const std::function<std::string(const calib::EvaluationRecord&)>& f) {
    py::list w;
    for (const auto& e : s.evaluations) w.append(f(e));
    return py::module_::import("numpy").attr("array")(w, py::arg("dtype") = "str");
  };
  using R = calib::EvaluationRecord;
  py::dict t;
  py::array_t<long long> index(n), item(n), rank(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    index.mutable_at(i) = i;
    item.mutable_at(i) = s.evaluations[static_cast<std::size_t>(i)].item;
    rank.mutable_at(i) = s.evaluations[static_cast<std::size_t>(i)].rank;
  }
  t["index"] = index;
  t["stage"] = words([](const R& e) { return std::string(calib::stage_name(e.stage)); });
  t["item"] = item;
  for (std::size_t k = 0; k < in.params.size(); ++k) t[py::str(in.params[k].key)] = numbers([k](const R& e) { return e.values[k]; });
  t["objective"] = numbers([](const R& e) { return e.eval.objective; });
  t["rms"] = numbers([](const R& e) { return e.eval.rms; });
  t["tau_s"] = numbers([](const R& e) { return e.eval.tau.value_or(NAN); });
  t["status"] = words([](const R& e) { return std::string(e.eval.ok ? "ok" : "failed"); });
  t["message"] = words([](const R& e) { return e.eval.message; });
  t["wall_ms"] = numbers([](const R& e) { return 1e3 * e.eval.wall_s; });
  t["rank"] = rank;
  return t;
}

/// Each parameter's profile (values, objective, interval) and its interval as (lo, hi), None where it is open.
void add_profiles(PyCalibration& p, const study::CalibrationInputs& in, const calib::SearchResult& s) {
  for (std::size_t k = 0; k < s.profiles.size() && k < in.params.size(); ++k) {
    const auto& pr = s.profiles[k];
    const py::tuple interval = py::make_tuple(number(pr.lo), number(pr.hi));
    py::dict d;
    d["values"] = py::array_t<double>(static_cast<py::ssize_t>(pr.values.size()), pr.values.data());
    d["objective"] = py::array_t<double>(static_cast<py::ssize_t>(pr.objective.size()), pr.objective.data());
    d["interval"] = interval;
    d["resolved"] = pr.resolved;
    p.intervals[py::str(in.params[k].key)] = interval;
    p.profiles[py::str(in.params[k].key)] = d;
  }
  if (s.profiles.empty()) return;
  const auto& rule = s.rule;
  p.factor_rule["kind"] = rule.given ? "given" : "confidence";
  p.factor_rule["factor"] = number(rule.factor);
  p.factor_rule["threshold"] = number(rule.threshold);
  if (rule.given) return;
  p.factor_rule["confidence"] = rule.confidence;
  p.factor_rule["q"] = rule.q;
  p.factor_rule["n"] = rule.n;
  p.factor_rule["p"] = rule.p;
}

/// The held-out measurement under the fitted values: ok, objective, rms, tau_s, message, e_sim (a table's rows).
py::object validation_of(const std::optional<calib::Evaluation>& v) {
  if (!v) return py::none();
  py::dict d;
  d["ok"] = v->ok;
  d["objective"] = v->ok ? number(v->objective) : py::object(py::none());
  d["rms"] = v->ok ? number(v->rms) : py::object(py::none());
  d["tau_s"] = number(v->tau);
  d["message"] = v->message;
  d["e_sim"] = v->e_sim;
  return d;
}

PyCalibration make_result(const study::CalibrationInputs& in, const study::CalibrationResult& r) {
  PyCalibration p;
  const calib::SearchResult& s = r.search;
  p.kind = in.trajectory() ? "trajectory" : "table";
  for (std::size_t k = 0; k < in.params.size(); ++k) {
    const py::str key(in.params[k].key);
    p.keys.append(key);
    p.start[key] = in.start[k].value;
    if (k < s.best.size()) p.values[key] = s.best[k];
  }
  p.ok = s.best_eval.ok;
  p.objective = p.ok ? number(s.best_eval.objective) : py::object(py::none());
  p.rms = p.ok ? number(s.best_eval.rms) : py::object(py::none());
  p.tau_s = number(s.best_eval.tau);
  p.evaluations = evaluation_columns(in, s);
  p.count = s.evaluations.size();
  p.failed = s.failed;
  for (const auto stage : {calib::Stage::start, calib::Stage::scan, calib::Stage::local, calib::Stage::profile, calib::Stage::edge})
    if (std::isfinite(r.stage_times.end[static_cast<std::size_t>(stage)])) p.stage_wall_s[calib::stage_name(stage)] = r.stage_times.wall(stage);
  add_profiles(p, in, s);
  p.validation = validation_of(r.validation);
  p.cancelled = r.cancelled;
  p.wall_time_s = r.wall_s;
  p.jobs = r.jobs;
  return p;
}

/// The options as `imcol calibrate` takes them (its checks and messages), --factor and --confidence exclusive.
study::CalibrationOptions options(const py::object& data, const py::object& fit, const py::object& window, std::optional<double> offset_max,
                                  std::optional<int> scan, int starts, int max_evals, int profile_points, std::optional<double> factor,
                                  std::optional<double> confidence, int refine, double refine_to, const py::object& validate) {
  study::CalibrationOptions o;
  o.data = py::str(data).cast<std::string>();
  o.fits = fit_texts(fit);
  o.window = window_text(window);
  o.offset_max = offset_max;
  if (factor && confidence)
    throw InputError("imcol.calibrate", "confidence", "give either confidence (the interval at a probability) or factor (the factor itself), not both");
  if (scan) o.search.scan = *scan;
  o.search.starts = starts;
  o.search.max_evals = max_evals;
  o.search.profile_points = profile_points;
  o.search.factor = factor;
  if (confidence) o.search.confidence = *confidence;
  o.search.refine = refine;
  o.search.refine_to = refine_to;
  if (!validate.is_none()) o.validate = py::str(validate).cast<std::string>();
  return o;
}

PyCalibration calibrate(const py::object& scene_arg, const py::object& data, const py::object& fit, const py::object& window,
                        std::optional<double> offset_max, std::optional<int> scan, int starts, int max_evals, int profile_points,
                        std::optional<double> factor, std::optional<double> confidence, int refine, double refine_to,
                        const py::object& validate, int jobs, const py::object& progress) {
  require_numpy("imcol.calibrate");
  if (jobs < 0) throw InputError("imcol.calibrate", "jobs", "must be >= 0 (0 = all cores)");
  std::vector<Override> overrides;
  const std::string path = scene_file(scene_arg, overrides);
  const study::CalibrationOptions opt =
      options(data, fit, window, offset_max, scan, starts, max_evals, profile_points, factor, confidence, refine, refine_to, validate);
  study::CalibrationInputs in;
  {
    py::gil_scoped_release free;
    in = study::read_calibration_inputs(path, overrides, opt);
  }
  check_progress_callable(progress, "imcol.calibrate");
  study::CalibrationResult r;
  call_interruptibly([&] { r = study::run_calibration(in, study::threads(jobs), interruptible_hooks()); }, progress);
  return make_result(in, r);
}

/// The attributes, as to_dict() gives them and repr() sums them up.
py::dict as_dict(const PyCalibration& p) {
  py::dict d;
  d["kind"] = p.kind;
  d["keys"] = p.keys;
  d["values"] = p.values;
  d["start"] = p.start;
  d["intervals"] = p.intervals;
  d["ok"] = p.ok;
  d["objective"] = p.objective;
  d["rms"] = p.rms;
  d["tau_s"] = p.tau_s;
  d["evaluations"] = p.evaluations;
  d["count"] = p.count;
  d["failed"] = p.failed;
  d["profiles"] = p.profiles;
  d["factor_rule"] = p.factor_rule;
  d["validation"] = p.validation;
  d["stage_wall_s"] = p.stage_wall_s;
  d["wall_time_s"] = p.wall_time_s;
  d["jobs"] = p.jobs;
  d["cancelled"] = p.cancelled;
  return py::module_::import("copy").attr("deepcopy")(d);
}

std::string repr(const PyCalibration& p) {
  return "imcol.CalibrationResult(values=" + py::repr(p.values).cast<std::string>() + ", rms=" + py::repr(p.rms).cast<std::string>() +
         ", evaluations=" + std::to_string(p.count) + ", failed=" + std::to_string(p.failed) + (p.cancelled ? ", cancelled=True" : "") + ")";
}

}  // namespace calibrate_impl

void bind_calibrate(py::module_& m) {
  using namespace calibrate_impl;
  using P = PyCalibration;
  py::class_<P>(m, "CalibrationResult", "A calibration's outcome, as calibration.json and calibration.csv of `imcol calibrate` hold it.")
      .def_readonly("kind", &P::kind, "\"trajectory\" or \"table\": the measurement's kind.")
      .def_readonly("keys", &P::keys, "The fitted keys, in order.")
      .def_readonly("values", &P::values, "Fitted key -> its best value.")
      .def_readonly("start", &P::start, "Fitted key -> where the search started.")
      .def_readonly("intervals", &P::intervals, "Fitted key -> (lo, hi) where the objective stays within the factor of the best; None: open at the bound.")
      .def_readonly("ok", &P::ok, "Some evaluation succeeded (else values is empty).")
      .def_readonly("objective", &P::objective, "The best objective (m^2, or 1 for an e table); None without one.")
      .def_readonly("rms", &P::rms, "Its square root (m, or 1).")
      .def_readonly("tau_s", &P::tau_s, "A trajectory's fitted time offset (s, the measurement's clock minus the simulation's).")
      .def_readonly("evaluations", &P::evaluations, "calibration.csv's columns: name -> NumPy array, one entry per evaluation.")
      .def_readonly("count", &P::count, "Evaluations made.")
      .def_readonly("failed", &P::failed, "Evaluations that failed.")
      .def_readonly("profiles", &P::profiles, "Fitted key -> {values, objective, interval, resolved}.")
      .def_readonly("factor_rule", &P::factor_rule, "The interval's rule: kind, factor, threshold (and confidence, q, n, p).")
      .def_readonly("validation", &P::validation, "The held-out measurement under the fitted values (a dict), or None.")
      .def_readonly("stage_wall_s", &P::stage_wall_s, "Stage -> its wall time (s).")
      .def_readonly("wall_time_s", &P::wall_time_s, "The search's wall time (s).")
      .def_readonly("jobs", &P::jobs, "Threads used.")
      .def_readonly("cancelled", &P::cancelled, "The search stopped early: the result holds what finished.")
      .def("to_dict", &as_dict, "The attributes as a dict (copies).")
      .def("__repr__", &repr);

  m.def("calibrate", in_call("imcol.calibrate", &calibrate), py::arg("scene"), py::arg("data"), py::arg("fit"), py::kw_only(), py::arg("window") = py::none(),
        py::arg("offset_max") = py::none(), py::arg("scan") = py::none(), py::arg("starts") = 2, py::arg("max_evals") = 40,
        py::arg("profile_points") = 15, py::arg("factor") = py::none(), py::arg("confidence") = py::none(), py::arg("refine") = 16,
        py::arg("refine_to") = 1.0 / 64, py::arg("validate") = py::none(), py::arg("jobs") = 0, py::arg("progress") = py::none(),
        "Fits numeric scene keys to a measurement as `imcol calibrate` does (docs/calibration.md), on `jobs` threads "
        "(0: all cores), the GIL released. scene: an imcol.Scene from a file, a shipped scene's name or a scene file's path; data: the "
        "measurement's CSV (a trajectory or an e table); fit: \"KEY=LO:HI[:log]\", a list of them, or {key: (lo, hi[, "
        "\"log\"])}. The other options are the command's (--window as \"A:B\" or (A, B), --offset-max, --scan, ...). "
        "progress(done, total, eta_s) after each evaluation; Ctrl-C stops the search and raises KeyboardInterrupt. "
        "Returns an imcol.CalibrationResult.");
}

}  // namespace imcol::python
