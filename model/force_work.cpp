// SPDX-License-Identifier: BSD-3-Clause
#include "model/force_work.hpp"

namespace imcol::model {

const char* to_string(ForceKind k) {
  switch (k) {
    case ForceKind::drag: return "drag";
    case ForceKind::lubrication: return "lubrication";
    case ForceKind::added_mass: return "added_mass";
    case ForceKind::history: return "history";
    case ForceKind::contact: return "contact";
    case ForceKind::gravity: return "gravity";
    case ForceKind::simulated: return "simulated";
  }
  return "?";
}

double force_of(const SphereForces& f, ForceKind k) {
  switch (k) {
    case ForceKind::drag: return f.drag;
    case ForceKind::lubrication: return f.lubrication;
    case ForceKind::added_mass: return f.added_mass;
    case ForceKind::history: return f.history;
    case ForceKind::contact: return f.contact;
    case ForceKind::gravity: return f.gravity;
    case ForceKind::simulated: return f.simulated;
  }
  return 0;
}

std::array<double, kForceKinds> force_powers(const Evaluation& ev, std::size_t n) {
  std::array<double, kForceKinds> p{};
  for (std::size_t k = 0; k < kForceKinds; ++k)
    for (std::size_t m = 0; m < n; ++m) p[k] += force_of(ev.f[m], kAllForceKinds[k]) * ev.u[m];
  return p;
}

}  // namespace imcol::model
