// SPDX-License-Identifier: BSD-3-Clause
#include "model/approach.hpp"

#include "core/errors.hpp"

namespace imcol::model {

std::optional<std::string> never_approaching(const Scene& sc) {
  if (!sc.has_target() || sc.spheres.empty()) return std::nullopt;  // a free sphere: the trajectory is the result
  const auto& s1 = sc.spheres[0];
  const double rho_f = sc.fluid ? sc.fluid->density : 0.0;
  const bool gravity = sc.has(Effect::gravity) && sc.gravity != 0;
  if (sc.wall) {
    const double u1 = s1.velocity;
    if (u1 > 0) return std::nullopt;
    const double weight_to_wall = gravity ? (s1.density - rho_f) * sc.gravity : 0.0;  // per unit volume, N/m³, along +z
    if (weight_to_wall > 0) return std::nullopt;
    std::string why = "never approaching: the sphere ";
    why += u1 < 0 ? "moves away from the wall (U(0) = " + fmt_number(u1) + " m/s)" : "starts at rest";
    why += !gravity ? " with no gravity"
                    : (weight_to_wall == 0 ? " and buoyancy balances its weight" : " and its net weight points away from the wall");
    why += ": no force can bring it to the wall, so no t_end gives a collision and there is no e to measure";
    return why;
  }
  const auto& s2 = sc.spheres[1];
  const double u1 = s1.velocity, u2 = s2.velocity;
  if (gravity || u1 > 0 || u2 < 0) return std::nullopt;
  const bool identical = s1.diameter == s2.diameter && s1.density == s2.density;
  const bool coupled = sc.has(Effect::lubrication) || sc.has(Effect::added_mass) || sc.has(Effect::flow);
  if (coupled && !identical) return std::nullopt;
  std::string why = "never approaching: ";
  why += (u1 == 0 && u2 == 0) ? "the spheres start at rest" : "the spheres move apart (U_rel(0) = " + fmt_number(u1 - u2) + " m/s, neither toward the other)";
  why += " with no gravity: no force can bring them together, so no t_end gives a collision and there is no e to measure";
  return why;
}

}  // namespace imcol::model
