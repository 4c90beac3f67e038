// SPDX-License-Identifier: BSD-3-Clause
#include "model/wall_function.hpp"

#include "contact/formulas.hpp"

namespace imcol::model {

WallFunction::WallFunction(const Scene& sc, const PairGeometry& p) : a_star_(p.a_star) {
  dw_floor_ = sc.added_mass.dw_floor > 0 ? sc.added_mass.dw_floor : sc.contact.delta_ss * p.D / p.a_star;
  // The continuation below the floor, for every caller (added mass, K_H, the flow blend's estimate); built now, not
  // inside the first right-hand side. Without a target W is never evaluated.
  if (p.has_target()) {
    w_floor_ = contact::added_mass_W(dw_floor_);
    dw_slope_ = contact::added_mass_dW(dw_floor_);
  }
}

double WallFunction::W(double gap) const {
  const double d = gap / a_star_;
  if (d >= dw_floor_) return contact::added_mass_W(d);
  return w_floor_ + dw_slope_ * (d - dw_floor_);
}

double WallFunction::dW(double gap) const {
  const double d = gap / a_star_;
  return d >= dw_floor_ ? contact::added_mass_dW(d) : dw_slope_;
}

}  // namespace imcol::model
