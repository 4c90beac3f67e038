// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The pair's geometry and the parameters every force term reads, derived once from the Scene (SI units):
// radii a_m, masses m_p,m and displaced fluid masses m_f,m, the reduced radius and mass a* = (1/a1 + 1/a2)⁻¹,
// m* (MODEL.md §1; a wall: a* = a1, m* = m_p,1), the effective modulus E* (Hertz, MODEL.md §2.4), the dry
// restitution e_dry (choice) and the contact zone δ_SS.
#include <array>
#include <cstddef>

#include "core/scene.hpp"

namespace imcol::model {

enum class Target { none, wall, sphere };

struct PairGeometry {
  explicit PairGeometry(const Scene& sc);

  Target target = Target::none;
  std::size_t n_spheres = 1;
  std::array<double, 2> a{}, mp{}, mf{};  // radius m, mass kg, displaced fluid mass kg
  double D = 0;                           // diameter of sphere 1, m: the length scale of the scene's ratios
  double a_star = 0, m_star = 0, E_star = 0, e_dry = 1;  // m, kg, Pa, -
  double mu = 0, rho_f = 0;                               // Pa s, kg/m³ (0 without a fluid)
  double initial_gap = 0;     // m; infinite without a target
  double delta_ss_m = 0;      // δ_SS, m: shortened to the initial gap on a start inside the contact zone
  bool start_inside = false;  // the run starts inside the contact zone (approaching, elastic)
  double u_ref = 0;           // largest initial speed (at least 1 mm/s), m/s
  double u_rel0 = 0;          // initial U1 − U2, m/s (> 0: approaching; 0 without a target)
  double gap_scale = 0;       // the gap's error scale: D, the lubrication cutoff or the Hertz indentation, m

  bool has_target() const { return target != Target::none; }
  bool pair() const { return target == Target::sphere; }
};

double sphere_volume(double a);  // m³

}  // namespace imcol::model
