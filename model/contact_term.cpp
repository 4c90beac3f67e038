// SPDX-License-Identifier: BSD-3-Clause
#include "model/contact_term.hpp"

namespace imcol::model {

ContactTerm::ContactTerm(const Scene& sc, const PairGeometry& p)
    : law_(contact::make_contact_law(sc.contact.law, {p.m_star, p.E_star, p.a_star, p.e_dry, p.delta_ss_m, p.D, sc.contact.delta_ss,
                                                      sc.contact.beta, sc.path})),
      pair_(p.pair()) {
  choices_ = {{"contact.law", to_string(law_->kind())}};
  for (auto& kv : law_->choices()) choices_.push_back(std::move(kv));
  choices_.push_back({"contact.e_dry", choice_number(p.e_dry)});
  choices_.push_back({"contact.delta_ss_m", choice_number(p.delta_ss_m)});
}

void ContactTerm::add(const TermInput& in, Evaluation& ev) const {
  const double f = in.contact_begun ? law_->force(ev.gap, ev.u_rel) : 0.0;  // magnitude, pushes the pair apart
  ev.f[0].term[slot()] = -f;
  if (pair_) ev.f[1].term[slot()] = f;
}

std::unique_ptr<ForceTerm> make_contact_term(const Scene& sc, const PairGeometry& p) { return std::make_unique<ContactTerm>(sc, p); }

}  // namespace imcol::model
