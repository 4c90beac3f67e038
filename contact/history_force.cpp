#include "contact/history_force.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "contact/formulas.hpp"

namespace imcol::contact {

namespace {
struct SoeCache {
  using Key = std::tuple<int, double, double, double, double, double, int>;
  std::mutex mu;
  std::map<Key, std::shared_ptr<const SoeKernel>> kernels;
  SoeCacheStats stats;
};
SoeCache& soe_cache() {
  static SoeCache c;
  return c;
}
}  // namespace

std::shared_ptr<const SoeKernel> shared_soe_kernel(const HistoryOptions& opt, double D, double nu) {
  const SoeCache::Key key{static_cast<int>(opt.kernel), D, nu, opt.min_lag, opt.horizon, opt.modes > 0 ? 0.0 : opt.tolerance,
                          opt.modes > 0 ? opt.modes : 0};
  auto& c = soe_cache();
  {
    const std::lock_guard<std::mutex> lock(c.mu);
    if (auto it = c.kernels.find(key); it != c.kernels.end()) {
      ++c.stats.reused;
      return it->second;
    }
  }
  // Built outside the lock: other threads keep running; two threads building the same key keep the first.
  const auto base = opt.modes > 0 ? inverse_sqrt_soe_modes(opt.min_lag, opt.horizon, opt.modes)
                                  : inverse_sqrt_soe(opt.min_lag, opt.horizon, opt.tolerance);
  auto k = std::make_shared<const SoeKernel>(HistoryKernel(opt.kernel, D, nu), base);
  const std::lock_guard<std::mutex> lock(c.mu);
  ++c.stats.built;
  if (c.kernels.size() >= 256) c.kernels.clear();  // bounded: a long sweep of distinct scenes
  return c.kernels.emplace(key, std::move(k)).first->second;
}

SoeCacheStats soe_cache_stats() {
  auto& c = soe_cache();
  const std::lock_guard<std::mutex> lock(c.mu);
  return c.stats;
}

SphereHistory::SphereHistory(const HistoryOptions& opt, double a, double mu, double rho_f, double U0)
    : kernel_(opt.kernel, 2 * a, mu / rho_f),
      direct_(opt.direct),
      impulsive_(opt.impulsive),
      initial_re_(opt.initial_re),
      c_(6 * pi * mu * a),
      D_(2 * a),
      nu_(mu / rho_f),
      U0_(U0),
      min_lag_(opt.min_lag) {
  if (direct_) {
    step_ = opt.direct_step;
    grid_u_.push_back(U0);  // U(0+)
    return;
  }
  soe_ = shared_soe_kernel(opt, 2 * a, mu / rho_f);
  w_.assign(soe_->modes(), 0.0);
}

double SphereHistory::reynolds(double U) const { return std::abs(initial_re_ ? U0_ : U) * D_ / nu_; }

const std::vector<double>& SphereHistory::rates() const {
  static const std::vector<double> none;
  return soe_ ? soe_->rates() : none;
}

void SphereHistory::initial_states(std::span<double> z) const {
  std::fill(z.begin(), z.end(), impulsive_ ? U0_ : 0.0);
}

std::vector<double> SphereHistory::absolute_tolerances(double u_floor) const {
  // Mode i adds c w_i z_i to the force; errors u_floor/(√n w_i) in the modes add up (randomly) to
  // the drag error c u_floor of a velocity error u_floor.
  std::vector<double> t(states());
  if (t.empty()) return t;
  std::vector<double> w(t.size());
  double kappa = 0;
  soe_->weights(0.0, w, kappa);  // Basset weights
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = u_floor / (std::sqrt(static_cast<double>(t.size())) * std::max(w[i], 1e-300));
  return t;
}

double SphereHistory::start_floor() const { return 1e-3 * min_lag_; }

double SphereHistory::jump_term(double t, double Re) const {
  if (!impulsive_ || U0_ == 0) return 0.0;
  const double te = std::max(t, start_floor());
  double k = kernel_.K(te, Re);
  if (soe_) {
    const auto& lam = soe_->rates();
    for (std::size_t i = 0; i < lam.size(); ++i) k -= w_[i] * std::exp(-lam[i] * te);
  }
  return U0_ * k;
}

double SphereHistory::apply_start(double K_H, double m_eff, std::span<double> z) const {
  // Below the floor t_f the start-up force is held at its value at t_f; the momentum it misses,
  // c K_H U(0) ∫_0^t_f (K(s) − K(t_f)) ds, is given to the sphere at t = 0 instead.
  if (!impulsive_ || U0_ == 0) return 0.0;
  const double tf = start_floor(), Re = reynolds(U0_);
  const double dU = K_H * c_ * U0_ * (kernel_.integral(tf, Re) - tf * kernel_.K(tf, Re)) / m_eff;
  for (auto& v : z) v -= dU;  // direct: no states; its grid keeps U(0) and sees the drop as memory
  return dU;
}

SphereHistory::Term SphereHistory::evaluate(double t, double U, double K_H, std::span<const double> z) const {
  const double Re = reynolds(U);
  const double cK = c_ * K_H;
  Term term;
  if (soe_) {
    double kappa = 0;
    soe_->weights(Re, w_, kappa);
    double sum = 0;
    for (std::size_t i = 0; i < w_.size(); ++i) sum += w_[i] * z[i];
    term.force = -cK * (sum + jump_term(t, Re));
    term.mass = cK * kappa;
    return term;
  }
  // Direct product integration of U piecewise linear through the grid values and the current U:
  // Σ_k (s_k − s_{k−1}) I(t − t_k), s_j the slope on [t_j, t_{j+1}], the last one the secant
  // (U(t) − U_n)/(t − t_n) of the partial segment, so that the force is continuous at grid points.
  const std::size_t n = grid_u_.size() - 1;
  const double tn = static_cast<double>(n) * step_;
  const double part = t - tn;
  double sum = 0, s_prev = 0;
  for (std::size_t k = 0; k <= n; ++k) {
    double s = 0;
    if (k < n) s = (grid_u_[k + 1] - grid_u_[k]) / step_;
    else if (part > 1e-12 * step_) s = (U - grid_u_[n]) / part;
    const double ds = s - s_prev;
    if (ds != 0) sum += ds * kernel_.integral(std::max(t - static_cast<double>(k) * step_, 0.0), Re);
    s_prev = s;
  }
  term.force = -cK * (sum + jump_term(t, Re));
  return term;
}

void SphereHistory::state_rhs(double accel, std::span<const double> z, std::span<double> dz) const {
  const auto& lam = soe_->rates();
  for (std::size_t i = 0; i < lam.size(); ++i) dz[i] = accel - lam[i] * z[i];
}

void SphereHistory::gains(double U, double K_H, std::span<double> g) const {
  double kappa = 0;
  soe_->weights(reynolds(U), g, kappa);
  for (auto& v : g) v *= c_ * K_H;
}

void SphereHistory::record(double t, double U) {
  const double tk = static_cast<double>(grid_u_.size()) * step_;
  if (std::abs(t - tk) > 1e-6 * step_)
    throw std::logic_error("direct history evaluator: grid point missed (t = " + std::to_string(t) +
                           " s, expected " + std::to_string(tk) + " s)");
  grid_u_.push_back(U);
}

}  // namespace imcol::contact
