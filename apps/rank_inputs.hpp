// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the ranks of an MPI job compare before they share out a command's runs (cluster::agree): each distributed
// command's resolved scene(s) and the options that decide its results. Options that change only where and how rank 0
// writes (--out, --no-plot, --export, progress) or a rank's own threads (--jobs: nodes may differ) are left out.
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "apps/calibrate.hpp"
#include "apps/cluster.hpp"
#include "apps/sweep.hpp"
#include "calibrate/measurement.hpp"
#include "apps/work_precision.hpp"
#include "apps/work_precision_flow.hpp"
#include "core/scene.hpp"
#include "core/scene_values.hpp"

namespace imcol {

namespace rank_inputs_detail {

inline std::string num(double v) { return scene_values_detail::num(v); }

template <class T>
std::string list(const std::vector<T>& v) {
  std::string t;
  for (const auto& x : v) {
    if (!t.empty()) t += ",";
    if constexpr (std::is_arithmetic_v<T>) t += num(static_cast<double>(x));
    else t += x;
  }
  return t;
}

}  // namespace rank_inputs_detail

/// A sweep: every point's scene (a digest line each), the varied quantity and its range.
inline cluster::Inputs sweep_inputs(const std::vector<Scene>& scenes, const SweepOptions& opt) {
  using rank_inputs_detail::num;
  cluster::Inputs in;
  for (const auto& sc : scenes) in.scene += std::to_string(cluster::digest(scene_values(sc))) + "\n";
  in.options = "sweep\nvary = " + opt.vary + "\nfrom = " + num(opt.from) + "\nto = " + num(opt.to) + "\npoints = " +
               std::to_string(opt.points) + "\nspacing = " + opt.spacing + "\n";
  return in;
}

/// work-precision of a collision scene: its scene (history added by --add-history included) and its ladders.
inline cluster::Inputs work_precision_inputs(const Scene& base, const WorkPrecisionOptions& opt) {
  using rank_inputs_detail::list;
  using rank_inputs_detail::num;
  cluster::Inputs in;
  in.scene = scene_values(base);
  in.options = "work-precision\nrtols = " + list(opt.rtols) + "\nintegrators = " + list(opt.integrators) + "\nevaluators = " +
               list(opt.evaluators) + "\ndirect_steps = " + list(opt.direct_steps) + "\ndirect_rtol = " + num(opt.direct_rtol) +
               "\nref_rtol = " + num(opt.ref_rtol) + "\nref_history_tol = " + num(opt.ref_history_tol) + "\nrepeat = " +
               std::to_string(opt.repeat) + "\nadd_history = " + (opt.add_history ? "true" : "false") + "\n";
  return in;
}

/// work-precision of a coupled scene: its scene and the grid and step ladders.
inline cluster::Inputs flow_ladder_inputs(const Scene& base, const FlowLadderOptions& opt) {
  using rank_inputs_detail::list;
  cluster::Inputs in;
  in.scene = scene_values(base);
  in.options = "work-precision (coupled)\ncells = " + list(opt.cells) + "\ncfls = " + list(opt.cfls) + "\n";
  return in;
}

/// A measurement's values (not its file name) as text.
inline std::string measurement_values(const calib::Measurement& m) {
  using rank_inputs_detail::list;
  std::string t;
  if (const auto* tr = std::get_if<calib::MeasuredTrajectory>(&m)) {
    t = "trajectory\nt = " + list(tr->t) + "\ncolumns = " + list(tr->columns) + "\n";
    for (const auto& z : tr->z) t += "z = " + list(z) + "\n";
  } else {
    const auto& tb = std::get<calib::MeasuredTable>(m);
    t = "table\nkeys = " + list(tb.keys) + "\ne = " + list(tb.e) + "\n";
    for (const auto& row : tb.values) t += "row = " + list(row) + "\n";
  }
  return t;
}

/// A calibration: its scene, the fitted keys and intervals, the measurements' values, the window and the search.
inline cluster::Inputs calibrate_inputs(const Scene& base, const calib::Measurement& data, const std::optional<calib::Measurement>& held_out,
                                        const CalibrateOptions& opt) {
  using rank_inputs_detail::list;
  using rank_inputs_detail::num;
  cluster::Inputs in;
  in.scene = scene_values(base);
  const auto& s = opt.search;
  in.options = "calibrate\nfit = " + list(opt.fits) + "\ndata = " + std::to_string(cluster::digest(measurement_values(data))) +
               "\nvalidate = " + (held_out ? std::to_string(cluster::digest(measurement_values(*held_out))) : std::string("none")) +
               "\nwindow = " + opt.window + "\noffset_max = " + (opt.offset_max ? num(*opt.offset_max) : std::string("none")) +
               "\nscan = " + std::to_string(s.scan) + "\nstarts = " + std::to_string(s.starts) + "\nmax_evals = " +
               std::to_string(s.max_evals) + "\nxtol = " + num(s.xtol) + "\nprofile_points = " + std::to_string(s.profile_points) +
               "\nfactor = " + (s.factor ? num(*s.factor) : std::string("none")) + "\nconfidence = " + num(s.confidence) +
               "\nrefine = " + std::to_string(s.refine) + "\nrefine_to = " + num(s.refine_to) + "\ncache = " +
               (opt.cache.empty() ? "none" : "yes") + "\n";
  return in;
}

}  // namespace imcol
