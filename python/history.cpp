// SPDX-License-Identifier: BSD-3-Clause
// imcol.history_compare: the history-force kernels and evaluators compared on one scene (study/history.hpp), or e against
// St per kernel over a sweep (study/history_sweep.hpp), as `imcol history` runs them, the GIL released while they
// run; history.csv's or history_sweep.csv's columns as an imcol.StudyTable.
#include <pybind11/stl.h>

#include <optional>

#include "core/errors.hpp"
#include "python/bindings.hpp"
#include "python/call.hpp"
#include "python/interrupt.hpp"
#include "python/convert.hpp"
#include "python/scene.hpp"
#include "python/table.hpp"
#include "study/history.hpp"
#include "study/history_sweep.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace history_impl {  // this file's helpers: named, as the module is one unity unit

using Names = std::optional<std::vector<std::string>>;

/// The scene alone: every kernel × evaluator and none.
PyTable history_of_scene(const Scene& base, const Names& kernels, const Names& evaluators, const py::object& progress) {
  study::HistoryResult r;
  call_interruptibly(
      [&] {
        r = study::compare_history(base, kernels.value_or(choice_names<KernelKind>()),
                                   evaluators.value_or(std::vector<std::string>{"soe-step", "soe", "direct"}), interruptible_hooks());
      },
      progress);
  py::dict info;
  info["collision"] = r.collision;
  info["cancelled"] = r.cancelled;
  return make_table("history", study::history_table(r), info);
}

/// A sweep: each point with none and every kernel × evaluator (the scene's evaluator unless given).
PyTable history_of_sweep(const study::SceneLoader& load, const std::vector<Override>& overrides, const Scene& base, const Names& kernels,
                         const Names& evaluators, const std::string& vary, const std::vector<double>& values, int jobs,
                         const py::object& progress) {
  const std::vector<std::string> ks = kernels.value_or(choice_names<KernelKind>());
  const std::vector<std::string> es = evaluators.value_or(std::vector<std::string>{});
  study::check_history_choices(ks, es);
  if (!base.has_target())
    throw InputError(base.path, "wall", "a free sphere has no collision, so no e to compare (add a [wall] or a second [[sphere]])");
  study::HistorySweepResult r;
  call_interruptibly(
      [&] {
        const std::vector<Scene> scenes = study::sweep_scenes(load, overrides, base, vary, values);
        r = study::history_sweep(scenes, vary, values, study::history_series(ks, es, base), study::threads(jobs), interruptible_hooks());
      },
      progress);
  py::dict info;
  info["vary"] = r.vary;
  info["column"] = r.column;
  info["cancelled"] = r.cancelled;
  return make_table("history_sweep", study::history_sweep_table(r), info);
}

PyTable history(const py::object& scene_arg, const Names& kernels, const Names& evaluators, const std::optional<std::string>& vary,
                const std::optional<std::vector<double>>& values, int jobs, const std::optional<py::object>& rtol,
                const std::optional<py::object>& atol, const std::optional<std::string>& integrator, const py::object& progress) {
  require_numpy("imcol.history_compare");
  check_progress_callable(progress, "imcol.history_compare");
  const PyScene scene = scene_argument(scene_arg, "imcol.history_compare").cast<PyScene>();
  if (vary) {
    study::check_sweep_quantity(*vary, "imcol.history_compare", "vary");
    if (!values) throw InputError("imcol.history_compare", "values", "missing: give the values of " + *vary + " (SI units)");
    study::check_sweep_values(*vary, *values, "imcol.history_compare", "values");
  } else if (values) {
    throw InputError("imcol.history_compare", "values", "needs vary: the quantity the values are of");
  }
  if (jobs < 0) throw InputError("imcol.history_compare", "jobs", "must be >= 0 (0 = all cores)");
  std::vector<Override> overrides = scene.overrides();
  for (auto& o : solver_overrides(rtol, atol, integrator)) overrides.push_back(o);
  const auto load = [&](const std::vector<Override>& ov) { return parse_scene(scene.text(), scene.path(), ov); };
  const Scene base = load(overrides);
  if (!base.fluid) throw InputError(base.path, "fluid", "the history force needs a [fluid] table");
  if (!vary) return history_of_scene(base, kernels, evaluators, progress);
  return history_of_sweep(load, overrides, base, kernels, evaluators, *vary, *values, jobs, progress);
}

}  // namespace history_impl

void bind_history(py::module_& m) {
  m.def("history_compare", in_call("imcol.history_compare", &history_impl::history), py::arg("scene"), py::arg("kernels") = py::none(), py::arg("evaluators") = py::none(),
        py::arg("vary") = py::none(), py::arg("values") = py::none(), py::arg("jobs") = 0, py::arg("rtol") = py::none(),
        py::arg("atol") = py::none(), py::arg("integrator") = py::none(), py::arg("progress") = py::none(),
        "Runs a scene (an imcol.Scene, a shipped scene's name or a scene file's path) without the history force and with each kernel (default all: "
        "imcol.history_kernels()) and evaluator (default soe-step, soe, direct) as `imcol history` does, one after the "
        "other; with `vary` and `values`, at each value of that quantity on `jobs` threads (0: all cores), the evaluator "
        "the scene's unless given. The GIL is released while they run; Ctrl-C stops the runs in flight within a step (KeyboardInterrupt). "
        "progress: None or progress(done, total, eta_s), runs finished of all. Returns an imcol.StudyTable: history.csv's "
        "columns, or history_sweep.csv's with `vary`.");
}

}  // namespace imcol::python
