// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The added mass's wall function W(δ**), δ** = h/a* (MODEL.md §2.2, seed (6.8)), and its slope dW/dδ**.
// dW/dδ diverges like ln δ at contact: below dw_floor, W is continued linearly with the slope it has there. dW/dδ
// is then bounded and still the derivative of the W used in the mass, so the added-mass forces stay conservative
// (½ m_a(δ) U² is conserved in an ideal fluid; bounding dW/dδ alone would create energy on approach).
#include "core/scene.hpp"
#include "model/pair.hpp"

namespace imcol::model {

class WallFunction {
 public:
  /// dw_floor: added_mass.dw_floor, else δ_SS/a*.
  WallFunction(const Scene& sc, const PairGeometry& p);
  double W(double gap) const;   // gap in m
  double dW(double gap) const;  // dW/dδ** (per unit δ**)
  double dw_floor() const { return dw_floor_; }

 private:
  double a_star_ = 0, dw_floor_ = 0;
  double w_floor_ = 0, dw_slope_ = 0;  // W and dW/dδ at dw_floor
};

}  // namespace imcol::model
