// SPDX-License-Identifier: BSD-3-Clause
#include "study/sweep_points.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "run/measured_run.hpp"
#include "run/simulate.hpp"

namespace imcol::study {

namespace {

struct Quantity {
  const char* name;
  const char* column;  // CSV column of the varied value
};

const Quantity kQuantities[] = {{"velocity", "velocity_m_s"}, {"viscosity", "viscosity_Pa_s"}, {"diameter", "diameter_m"}, {"density", "density_kg_m3"}};

const Quantity* quantity(const std::string& vary) {
  for (const auto& x : kQuantities)
    if (vary == x.name) return &x;
  return nullptr;
}

/// A point's message: why e is missing (with the hint to raise solver.t_end only where the retries with a longer t_end
/// showed that it helps: then they were kept), or which named measures disagree with e, or the t_end it took.
std::string point_message(const RunSummary& s, double t_end_scene, double t_end_run) {
  std::ostringstream os;
  os << std::setprecision(4);
  const bool extended = t_end_run != t_end_scene;
  if (!s.e) return e_missing_message(s, t_end_scene, t_end_run);
  if (extended) os << "t_end extended to " << t_end_run << " s";
  if (e_status(s) == "measures_disagree") {
    os << (extended ? "; " : "") << "measures disagree with e (" << to_string(s.e_is) << ") by more than "
       << "measure.disagreement:";
    for (const auto& [k, v] : s.measures_disagree) os << " " << k << " = " << v;
  }
  return os.str();
}

}  // namespace

std::string e_status(const RunSummary& s) {
  if (!s.e) return "not_measured";
  return s.measures_disagree.empty() ? "measured" : "measures_disagree";
}

std::string point_name(std::size_t i, const std::string& vary, double value) {
  std::ostringstream os;
  os << std::setprecision(6) << "sweep point " << i << " (" << vary << " = " << value << ")";
  return os.str();
}

const char* sweep_column(const std::string& vary) {
  const Quantity* q = quantity(vary);
  return q ? q->column : nullptr;
}

std::vector<std::string> sweep_quantities() {
  std::vector<std::string> out;
  for (const auto& q : kQuantities) out.emplace_back(q.name);
  return out;
}

void check_sweep_quantity(const std::string& vary, const std::string& where, const std::string& key) {
  if (quantity(vary)) return;
  std::string list;
  for (const auto& q : kQuantities) list += (list.empty() ? "" : ", ") + std::string(q.name);
  throw InputError(where, key, "unknown value '" + vary + "' (expected " + list + ")");
}

void check_sweep_values(const std::string& vary, const std::vector<double>& values, const std::string& where, const std::string& key) {
  if (values.empty() || values.size() > 100000)
    throw InputError(where, key, "must hold 1 to 100000 values (" + std::to_string(values.size()) + " given)");
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!(values[i] > 0 && std::isfinite(values[i]))) throw InputError(where, key, point_name(i, vary, values[i]) + ": must be a positive number");
}

SweepPoint run_sweep_point(const Scene& scene, double value) {
  SweepPoint r;
  r.value = value;
  try {
    // A point whose collision or rebound window did not fit in t_end is rerun with t_end doubled (twice at most).
    RunResult run = simulate_for_e(scene);
    r.summary = std::move(run.summary);
    r.ok = true;
    r.message = point_message(r.summary, scene.solver.t_end, run.scene.solver.t_end);
  } catch (const std::exception& e) {
    r.message = e.what();  // a solver failure (or anything else) ends this point only
  }
  return r;
}

std::vector<double> sweep_values(const SweepRange& opt) {
  std::vector<double> v;
  for (int i = 0; i < opt.points; ++i) {
    const double f = opt.points == 1 ? 0.0 : static_cast<double>(i) / (opt.points - 1);
    v.push_back(opt.spacing == "log" ? opt.from * std::pow(opt.to / opt.from, f) : opt.from + f * (opt.to - opt.from));
  }
  return v;
}

std::vector<Override> sweep_overrides(const Scene& base, const std::string& vary, double value) {
  std::vector<Override> ov;
  const std::size_t n = base.spheres.size();
  const double t_end = base.solver.t_end;
  if (vary == "velocity") {
    const double v0 = base.spheres[0].velocity;
    ov.push_back({"sphere[0].velocity", toml_float(v0 < 0 ? -value : value)});
    // A slower approach takes longer: t_end grows with the time to cross the initial gap.
    if (v0 != 0 && value < std::abs(v0)) ov.push_back({"solver.t_end", toml_float(t_end * std::abs(v0) / value)});
  } else if (vary == "viscosity") {
    ov.push_back({"fluid.viscosity", toml_float(value)});
  } else if (vary == "density") {
    // Every sphere's density by the same factor: the impactor's becomes `value`, ratios are kept.
    const double s = value / base.spheres[0].density;
    for (std::size_t k = 0; k < n; ++k) ov.push_back({"sphere[" + std::to_string(k) + "].density", toml_float(base.spheres[k].density * s)});
  } else if (vary == "diameter") {
    // Every sphere scaled by the same factor (the impactor's diameter becomes `value`); the initial
    // gap keeps its size in diameters, the target (or wall) stays where it is.
    const double s = value / base.spheres[0].diameter;
    for (std::size_t k = 0; k < n; ++k)
      ov.push_back({"sphere[" + std::to_string(k) + "].diameter", toml_float(base.spheres[k].diameter * s)});
    if (base.has_target()) {
      const double a0 = base.spheres[0].diameter / 2, x0 = base.spheres[0].position;
      const double face = n == 2 ? base.spheres[1].position - base.spheres[1].diameter / 2 : base.wall->position;
      const double face_new = n == 2 ? base.spheres[1].position - s * base.spheres[1].diameter / 2 : base.wall->position;
      const double gap = face - (x0 + a0);
      ov.push_back({"sphere[0].position", toml_float(face_new - s * (gap + a0))});
    }
    if (s > 1) ov.push_back({"solver.t_end", toml_float(t_end * s)});
  } else {
    throw InputError("--vary", vary, "unknown quantity (expected velocity, viscosity, diameter, density)");
  }
  return ov;
}

std::vector<Scene> sweep_scenes(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base,
                                const std::string& vary, const std::vector<double>& values) {
  return sweep_scenes([&](const std::vector<Override>& ov) { return load_scene(scene_path, ov); }, overrides, base, vary, values);
}

std::vector<Scene> sweep_scenes(const SceneLoader& load, const std::vector<Override>& overrides,
                                const Scene& base, const std::string& vary, const std::vector<double>& values) {
  if (vary == "viscosity" && !base.fluid) throw InputError(base.path, "fluid", "a viscosity sweep needs a [fluid] table");
  std::vector<Scene> scenes;
  for (std::size_t i = 0; i < values.size(); ++i) {
    auto ov = overrides;
    for (auto& o : sweep_overrides(base, vary, values[i])) ov.push_back(o);
    try {
      scenes.push_back(load(ov));
    } catch (const InputError& e) {
      // The same place and key, the point named before the problem.
      throw InputError(e.where(), e.key(), point_name(i, vary, values[i]) + ": " + e.problem());
    }
  }
  return scenes;
}

}  // namespace imcol::study
