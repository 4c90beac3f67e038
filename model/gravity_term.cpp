// SPDX-License-Identifier: BSD-3-Clause
#include "model/gravity_term.hpp"

namespace imcol::model {

namespace {
/// (m_p − m_f) g of each sphere, N; it has no `model` block lines.
class GravityTerm : public ForceTerm {
 public:
  GravityTerm(const Scene& sc, const PairGeometry& p) : n_spheres_(p.n_spheres) {
    for (std::size_t m = 0; m < n_spheres_; ++m) weight_[m] = (p.mp[m] - p.mf[m]) * sc.gravity;
  }
  TermSlot properties() const override { return {ForceKind::gravity, "f_grav"}; }
  void add(const TermInput&, Evaluation& ev) const override {
    for (std::size_t m = 0; m < n_spheres_; ++m) ev.f[m].term[slot()] = weight_[m];
  }

 private:
  std::size_t n_spheres_ = 1;
  std::array<double, 2> weight_{};  // N
};
}  // namespace

std::unique_ptr<ForceTerm> make_gravity_term(const Scene& sc, const PairGeometry& p) { return std::make_unique<GravityTerm>(sc, p); }

}  // namespace imcol::model
