// SPDX-License-Identifier: BSD-3-Clause
#include "run/flow_references.hpp"

#include <array>
#include <cmath>

#include "contact/formulas.hpp"

namespace imcol {

double impulsive_start_force(double mu, double nu, double a, double U, double t) {
  return 6 * M_PI * mu * a * U * (1 + a / std::sqrt(M_PI * nu * t));
}

OscillatingSphereForce::OscillatingSphereForce(double mu, double rho, double a, double amplitude, double frequency)
    : mu_(mu), rho_(rho), a_(a), amplitude_(amplitude), omega_(2 * M_PI * frequency), delta_(std::sqrt(2 * (mu / rho) / omega_)) {}

double OscillatingSphereForce::at(double t) const {
  const double om = omega_, U = amplitude_ * om * std::sin(om * t), dU = amplitude_ * om * om * std::cos(om * t);
  return -6 * M_PI * mu_ * a_ * (1 + a_ / delta_) * U - 3 * M_PI * a_ * a_ * std::sqrt(2 * mu_ * rho_ / om) * (1 + 2 * a_ / (9 * delta_)) * dU;
}

double brenner_wall_force(double mu, const flow::SphereState& b, double wall_z) {
  const double gap = b.z - b.radius - wall_z;
  return -contact::brenner_lambda(gap / b.radius) * 6 * M_PI * mu * b.radius * b.u;
}

Scene pair_force_scene(const flow::FlowScene& sc) {
  Scene s;
  s.path = sc.path + " (its f_THR)";
  s.name = sc.name;
  s.fluid = FluidSpec();
  s.fluid->density = sc.density;
  s.fluid->viscosity = sc.viscosity;
  for (const auto& b : sc.spheres) {
    SphereSpec p;
    p.density = 2 * sc.density;
    p.youngs_modulus = 1e9;
    p.poisson_ratio = 0.3;
    p.e_dry = 1.0;
    p.diameter = b.diameter;
    p.position = b.position;
    p.velocity = b.velocity;
    s.spheres.push_back(p);
  }
  for (Effect e : {Effect::drag, Effect::lubrication, Effect::added_mass, Effect::elastic}) s.effects.insert(e);
  s.drag.law = DragLaw::schiller_naumann;
  // what parse_scene fills in for a pair that leaves out [lubrication], [contact], [measure] and [output]
  s.lubrication.model = LubricationModel::asymptotic;
  s.contact.delta_ss = 0.024;
  s.measure.instant_gap = s.contact.delta_ss;
  s.output.dt = s.measure.window / 100.0;
  return s;
}

std::pair<double, double> AnalyticPairForce::at(const std::vector<flow::SphereState>& s) const {
  const double gap = s[1].z - s[0].z - s[0].radius - s[1].radius;
  const std::array<double, 4> y = {gap, s[0].u, s[1].z, s[1].u};
  const auto f = model_.analytic_fluid_force(0.0, y, {0.0, 0.0});
  return {f[0], f[1]};
}

}  // namespace imcol
