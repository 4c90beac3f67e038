// SPDX-License-Identifier: BSD-3-Clause
#include "model/gap_resistance_term.hpp"

#include <algorithm>
#include <limits>

namespace imcol::model {

using namespace contact;

GapResistanceTerm::GapResistanceTerm(const Scene& sc, const PairGeometry& p)
    : model_(sc.lubrication.model), h_min_(sc.lubrication.cutoff * p.D), h_c_(sc.lubrication.h_c * p.a_star),
      six_pi_mu_(6 * pi * p.mu), pair_(p.pair()), rough_(sc.lubrication.limit == LubricationLimit::roughness) {
  const double a2 = pair_ ? p.a[1] : std::numeric_limits<double>::infinity();
  geo_ = {p.a[0], a2, p.a_star, lubrication_log_coefficient(p.a[0], a2), h_c_};
  if (model_ != LubricationModel::asymptotic) brenner_lambda(1.0);  // build the lookup table now
  auto& c = choices_;
  c.push_back({"lubrication.model", to_string(model_)});
  c.push_back({"lubrication.law", model_ == LubricationModel::asymptotic
                                      ? "two-sphere asymptote, exact as h -> 0: 6 pi mu [a*^2/h + c_log ln(a*/h)] U_rel (Jeffrey & Onishi), shifted to vanish at h_c"
                                      : model_ == LubricationModel::brenner
                                            ? "exact sphere-wall series: 6 pi mu a (lambda(h/a) - 1) U (Brenner 1961)"
                                            : "the seed's gap law as read from its 6.2.1: 6 pi mu a_m (lambda(h/a*) - 1) U_rel on sphere m (Brenner's wall series at h/a*)"});
  c.push_back({"lubrication.cutoff_m", choice_number(h_min_)});
  c.push_back({"lubrication.limit", rough_ ? "roughness: acts down to the roughness height " + choice_number(sc.lubrication.roughness) +
                                                   " m, where the solids touch; none in contact (Joseph et al. 2001; Kempe & Froehlich 2012)"
                                             : std::string("cutoff: acts on the gap bounded smoothly by the cut-off, also in contact")});
  if (model_ == LubricationModel::asymptotic) c.push_back({"lubrication.h_c_m", choice_number(h_c_)});
  if (model_ == LubricationModel::seed && pair_)
    c.push_back({"lubrication.pair_forces", p.a[0] == p.a[1] ? std::string("equal and opposite (equal radii)")
                                                             : "differ: |f_lub2/f_lub1| = a2/a1 = " + choice_number(p.a[1] / p.a[0]) +
                                                                   " (the seed's law does not conserve the pair's momentum)"});
}

void GapResistanceTerm::add(const TermInput& in, Evaluation& ev) const {
  if (rough_ && in.in_contact) return;  // the load goes through the touching asperities, not a film
  // Per sphere: equal and opposite for brenner and asymptotic, in the ratio a2/a1 for the seed's law.
  const GapResistance R = gap_resistance(model_, geo_, regularised_gap(ev.gap, h_min_));
  ev.f[0].term[slot()] = -six_pi_mu_ * R.on1 * ev.u_rel;
  if (pair_) ev.f[1].term[slot()] = six_pi_mu_ * R.on2 * ev.u_rel;
}

std::unique_ptr<ForceTerm> make_gap_resistance_term(const Scene& sc, const PairGeometry& p) {
  return std::make_unique<GapResistanceTerm>(sc, p);
}

}  // namespace imcol::model
