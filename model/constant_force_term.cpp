// SPDX-License-Identifier: BSD-3-Clause
// A constant external force F along z on each sphere, N (a demonstration of a term).
#include "model/force_term.hpp"
#include "model/pair.hpp"

namespace imcol::model {

namespace {
class ConstantForceTerm : public ForceTerm {
 public:
  ConstantForceTerm(double F, std::size_t n_spheres) : F_(F), n_spheres_(n_spheres) {
    choices_ = {{"constant_force.F_N", choice_number(F_)}};
  }
  TermSlot properties() const override { return {ForceKind::gravity, "f_const"}; }  // a body force in the budget
  void add(const TermInput&, Evaluation& ev) const override {
    for (std::size_t m = 0; m < n_spheres_; ++m) ev.f[m].term[slot()] = F_;
  }

 private:
  double F_;
  std::size_t n_spheres_;
};
}  // namespace

std::unique_ptr<ForceTerm> make_constant_force_term(const Scene&, const PairGeometry& p) {
  return std::make_unique<ConstantForceTerm>(1e-3, p.n_spheres);
}

}  // namespace imcol::model
