// SPDX-License-Identifier: BSD-3-Clause
#include "model/drag_term.hpp"

#include <cmath>

#include "contact/formulas.hpp"

namespace imcol::model {

namespace {
class DragTerm : public ForceTerm {
 public:
  DragTerm(const Scene& sc, const PairGeometry& p)
      : law_(sc.drag.law), a_(p.a), n_spheres_(p.n_spheres), mu_(p.mu), rho_f_(p.rho_f), six_pi_mu_(6 * contact::pi * p.mu) {
    choices_ = {{"drag.law", to_string(law_)}};
  }

  TermSlot properties() const override { return {ForceKind::drag, "f_drag", true}; }

  void add(const TermInput&, Evaluation& ev) const override {
    for (std::size_t m = 0; m < n_spheres_; ++m) {
      const double Re = rho_f_ * 2 * a_[m] * std::abs(ev.u[m]) / mu_;
      ev.f[m].term[slot()] = -six_pi_mu_ * a_[m] * ev.u[m] * contact::drag_factor(law_, Re);
    }
  }

 private:
  DragLaw law_;
  std::array<double, 2> a_{};  // m
  std::size_t n_spheres_ = 1;
  double mu_ = 0, rho_f_ = 0, six_pi_mu_ = 0;
};
}  // namespace

std::unique_ptr<ForceTerm> make_drag_term(const Scene& sc, const PairGeometry& p) { return std::make_unique<DragTerm>(sc, p); }

}  // namespace imcol::model
