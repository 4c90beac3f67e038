// SPDX-License-Identifier: BSD-3-Clause
#include "coupling/step_rule.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace imcol::coupling {

namespace {
constexpr double kP0 = 5600;  // Re·N below which cfl 0.5 (docs/coupling.md "The flow step")

FlowStep make_step(const Scene& sc, double h, const ReferenceSpeed& ref) {
  FlowStep s;
  const double D = sc.spheres[0].diameter, nu = sc.fluid->viscosity / sc.fluid->density;
  s.u_ref = ref.u;
  s.re = ref.u * D / nu;
  s.tau_p = relaxation_time(sc, 0);
  for (std::size_t m = 1; m < sc.spheres.size(); ++m) s.tau_p = std::min(s.tau_p, relaxation_time(sc, m));
  std::ostringstream os;
  os.precision(3);
  if (sc.flow.dt > 0) {
    s.dt = sc.flow.dt;
    s.limit = StepLimit::given;
    s.cfl = 0;
    os << "flow.dt = " << s.dt << " s";
    s.rule = os.str();
    return s;
  }
  const double cfl = sc.flow.cfl > 0 ? sc.flow.cfl : default_cfl(s.re, sc.flow.cells_per_diameter);
  const double dt_flow = ref.u > 0 ? cfl * h / ref.u : cfl * h * h / nu;  // at rest: a viscous step
  const double dt_tau = sc.flow.tau_p_fraction * s.tau_p;
  std::ostringstream courant;
  courant.precision(3);
  courant << "flow.cfl = " << cfl;
  if (!(sc.flow.cfl > 0)) courant << " (the default at Re = " << s.re << ", U_ref = " << ref.u << " m/s: " << ref.source << ")";
  else courant << " (U_ref = " << ref.u << " m/s: " << ref.source << ")";
  if (ref.u <= 0) courant << ", viscous step cfl h^2/nu";
  if (dt_tau < dt_flow) {
    s.dt = dt_tau;
    s.limit = StepLimit::relaxation;
    os << "dt = " << s.dt << " s = flow.tau_p_fraction " << sc.flow.tau_p_fraction << " x tau_p " << s.tau_p
       << " s, shorter than the Courant step " << dt_flow << " s of " << courant.str();
  } else {
    s.dt = dt_flow;
    s.limit = ref.u > 0 ? StepLimit::courant : StepLimit::viscous;
    os << courant.str() << ", dt = " << s.dt << " s";
  }
  s.cfl = ref.u > 0 ? s.dt * ref.u / h : 0;
  s.rule = os.str();
  return s;
}
}  // namespace

double default_cfl(double re, int cells) { return 0.5 * std::min(1.0, std::sqrt(kP0 / std::max(re * cells, 1e-300))); }

double relaxation_time(const Scene& sc, std::size_t m) {
  const auto& s = sc.spheres[m];
  const double a = 0.5 * s.diameter, V = 4.0 / 3.0 * std::numbers::pi * a * a * a;
  return (s.density + 0.5 * sc.fluid->density) * V / (6 * std::numbers::pi * sc.fluid->viscosity * a);
}

FlowStep flow_step(const Scene& sc, double h) { return make_step(sc, h, reference_speed(sc)); }

FlowStep flow_step(const Scene& sc, double h, double u_ref) {
  return make_step(sc, h, {u_ref, "the largest initial sphere speed"});
}

std::string step_advice(const FlowStep& s) {
  switch (s.limit) {
    case StepLimit::relaxation:
      return "the flow kernel's step is too long for the spheres' response to the fluid's force (" + s.rule +
             "): lower flow.tau_p_fraction or set a smaller flow.dt";
    case StepLimit::given:
      return "the flow kernel's step may be too long (" + s.rule + "): set a smaller flow.dt, or remove it for the default rule";
    case StepLimit::courant:
    case StepLimit::viscous:
      break;
  }
  return "the flow kernel's step is too long for the fluid's speed (" + s.rule + "): lower flow.cfl or set a smaller flow.dt";
}

}  // namespace imcol::coupling
