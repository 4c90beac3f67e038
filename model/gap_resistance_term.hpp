// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Gap (lubrication) resistance (MODEL.md §2.1): on sphere 1 −6πμ R1(h) U_rel, on sphere 2 +6πμ R2(h) U_rel, N,
// with the resistance lengths R_m of lubrication.model (contact/formulas.hpp gap_resistance) at the gap
// regularised below lubrication.cutoff. The `asymptotic` law vanishes beyond h_c (its edge is a root of the model).
#include "contact/formulas.hpp"
#include "core/scene.hpp"
#include "model/force_term.hpp"
#include "model/pair.hpp"

namespace imcol::model {

class GapResistanceTerm : public ForceTerm {
 public:
  GapResistanceTerm(const Scene& sc, const PairGeometry& p);
  // What the model's lubrication-edge root reads:
  LubricationModel model() const { return model_; }
  double cutoff_m() const { return h_min_; }  // lubrication.cutoff × D, m
  double h_c_m() const { return h_c_; }       // lubrication.h_c × a*, m

  TermSlot properties() const override { return {ForceKind::lubrication, "f_lub", true}; }
  void add(const TermInput& in, Evaluation& ev) const override;

 private:
  LubricationModel model_;
  contact::GapGeometry geo_;  // the gap law's radii, a*, c_log, h_c
  double h_min_ = 0, h_c_ = 0, six_pi_mu_ = 0;
  bool pair_ = false;
  bool rough_ = false;  // lubrication.limit = roughness: no force in contact (below the roughness height δ_SS)
};

std::unique_ptr<ForceTerm> make_gap_resistance_term(const Scene& sc, const PairGeometry& p);

}  // namespace imcol::model
