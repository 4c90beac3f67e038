// SPDX-License-Identifier: BSD-3-Clause
#include "model/added_mass_term.hpp"

#include "contact/formulas.hpp"

namespace imcol::model {

AddedMassForm::AddedMassForm(const Scene& sc, const PairGeometry& p)
    : wall(sc, p), mf(p.mf), a_star(p.a_star), n_spheres(p.n_spheres), has_target(p.has_target()) {
  lagrangian_pair = sc.added_mass.model == AddedMassModel::lagrangian && p.pair();
  mf_star = p.pair() ? contact::reduced(p.mf[0], p.mf[1]) : p.mf[0];
}

AddedMassMatrix AddedMassForm::matrix(double gap) const {
  const double W = has_target ? wall.W(gap) : 0.0;
  AddedMassMatrix M;
  if (lagrangian_pair) {
    const double A = 1.5 * mf_star * W;
    M.m11 = 0.5 * mf[0] + A;
    M.m22 = 0.5 * mf[1] + A;
    M.m12 = -A;
  } else {
    M.m11 = 0.5 * mf[0] * (1 + 3 * W);
    if (n_spheres == 2) M.m22 = 0.5 * mf[1] * (1 + 3 * W);
  }
  return M;
}

namespace {
/// Fills its mass (and m_pair, m_couple for the lagrangian pair) and the velocity part of f_AM.
class AddedMassTerm : public ForceTerm {
 public:
  AddedMassTerm(const Scene& sc, const PairGeometry& p) : f_(sc, p) {
    choices_ = {{"added_mass.model", to_string(sc.added_mass.model)}, {"added_mass.dw_floor", choice_number(f_.wall.dw_floor())}};
  }

  TermSlot properties() const override { return {ForceKind::added_mass, "f_am", true, TermMass::implicit}; }

  void add(const TermInput&, Evaluation& ev) const override {
    double W = 0, dW = 0;
    if (f_.has_target) {
      W = f_.wall.W(ev.gap);
      dW = f_.wall.dW(ev.gap);
    }
    for (std::size_t m = 0; m < f_.n_spheres; ++m) {
      if (f_.lagrangian_pair) {
        ev.f[m].mass[slot()] = 0.5 * f_.mf[m];  // free-space part; the gap part A is m_pair
      } else {
        ev.f[m].mass[slot()] = 0.5 * f_.mf[m] * (1 + 3 * W);
        if (f_.has_target) ev.f[m].term[slot()] = 0.75 * f_.mf[m] * ev.u[m] * (ev.u_rel / f_.a_star) * dW;  // velocity part (6.8)
      }
    }
    if (f_.lagrangian_pair) {
      const double A = 1.5 * f_.mf_star * W, dA = 1.5 * f_.mf_star * dW;
      ev.m_pair = A;
      ev.m_couple = -A;
      const double force = 0.5 * dA * ev.u_rel * ev.u_rel / f_.a_star;
      ev.f[0].term[slot()] = force;
      ev.f[1].term[slot()] = -force;
    }
  }

 private:
  AddedMassForm f_;
};
}  // namespace

std::unique_ptr<ForceTerm> make_added_mass_term(const Scene& sc, const PairGeometry& p) { return std::make_unique<AddedMassTerm>(sc, p); }

}  // namespace imcol::model
