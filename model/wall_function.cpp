// SPDX-License-Identifier: BSD-3-Clause
#include "model/wall_function.hpp"

#include "contact/formulas.hpp"

namespace imcol::model {

WallFunction::WallFunction(const Scene& sc, const PairGeometry& p) : a_star_(p.a_star) {
  dw_floor_ = sc.added_mass.dw_floor > 0 ? sc.added_mass.dw_floor : sc.contact.delta_ss * p.D / p.a_star;
  const bool added_mass = sc.has(Effect::added_mass) && p.has_target();
  const bool history_K_H = sc.has(Effect::history) && sc.history.wall_correction == WallCorrection::added_mass && p.has_target();
  const bool flow_estimate = sc.has(Effect::flow) && sc.flow.added_mass_estimate && p.has_target();  // FlowBlend's M_A
  // Build the lookup tables now, not inside the first right-hand side.
  if (added_mass || history_K_H || flow_estimate) {
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
