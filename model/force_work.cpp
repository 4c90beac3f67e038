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

double force_of(const SphereForces& f, ForceKind k, const KindSlots& slots) {
  if (k == ForceKind::simulated) return f.simulated;
  const auto& s = slots[static_cast<std::size_t>(k)];
  if (s.empty()) return k == ForceKind::added_mass ? f.implicit_added_mass : 0.0;
  double sum = f.term[s[0]];
  for (std::size_t i = 1; i < s.size(); ++i) sum += f.term[s[i]];
  return sum;
}

std::array<double, kForceKinds> force_powers(const Evaluation& ev, std::size_t n, const KindSlots& slots) {
  std::array<double, kForceKinds> p{};
  for (std::size_t k = 0; k < kForceKinds; ++k)
    for (std::size_t m = 0; m < n; ++m) p[k] += force_of(ev.f[m], kAllForceKinds[k], slots) * ev.u[m];
  return p;
}

}  // namespace imcol::model
