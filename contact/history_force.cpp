// SPDX-License-Identifier: BSD-3-Clause
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
    if (auto it = c.kernels.find(key); it != c.kernels.end()) return it->second;
  }
  // Built outside the lock: other threads keep running; two threads building the same key keep the first.
  const auto base = opt.modes > 0 ? inverse_sqrt_soe_modes(opt.min_lag, opt.horizon, opt.modes)
                                  : inverse_sqrt_soe(opt.min_lag, opt.horizon, opt.tolerance);
  auto k = std::make_shared<const SoeKernel>(HistoryKernel(opt.kernel, D, nu), base);
  const std::lock_guard<std::mutex> lock(c.mu);
  if (c.kernels.size() >= 256) c.kernels.clear();  // bounded: a long sweep of distinct scenes
  return c.kernels.emplace(key, std::move(k)).first->second;
}

SphereHistory::SphereHistory(const HistoryOptions& opt, double a, double mu, double rho_f, double U0)
    : kernel_(opt.kernel, 2 * a, mu / rho_f),
      evaluator_(opt.evaluator),
      impulsive_(opt.impulsive),
      initial_re_(opt.initial_re),
      c_(6 * pi * mu * a),
      D_(2 * a),
      nu_(mu / rho_f),
      U0_(U0),
      min_lag_(opt.min_lag),
      interpolate_(opt.interpolate_outputs),
      output_rtol_(opt.output_rtol),
      output_atol_(opt.output_atol) {
  if (direct()) {
    step_ = opt.direct_step;
    grid_u_.push_back(U0);  // U(0+)
    return;
  }
  soe_ = shared_soe_kernel(opt, 2 * a, mu / rho_f);
  w_.assign(soe_->modes(), 0.0);
  fixed_weights_ = kernel_.kind() == KernelKind::basset;  // Basset's weights and κ do not depend on Re
  if (fixed_weights_) soe_->weights(0.0, w_, kappa_);
  if (stepwise()) {
    z_.assign(soe_->modes(), impulsive_ ? U0 : 0.0);
    zs_.assign(soe_->modes(), 0.0);
    z_next_.assign(soe_->modes(), 0.0);
    for (double l : soe_->rates()) inv_rate_.push_back(1 / l);
    for (auto& c : cache_) {
      c.e.assign(soe_->modes(), 0.0);
      c.we.assign(soe_->modes(), 0.0);
      c.m.assign(kPoints * soe_->modes(), 0.0);
    }
    if (fixed_weights_) fast_ = SoeFastModes(soe_->rates(), w_);
  }
  lean_ = stepwise() && fixed_weights_ && !(impulsive_ && U0_ != 0);
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

SphereHistory::Term SphereHistory::evaluate_general(double t, double U, double K_H, std::span<const double> z) const {
  const bool jump = impulsive_ && U0_ != 0;
  const double Re = jump || !fixed_weights_ || direct() ? reynolds(U) : 0.0;  // Basset's weights do not depend on Re
  const double cK = c_ * K_H;
  Term term;
  if (soe_) {
    double kappa = kappa_;
    if (!fixed_weights_) soe_->weights(Re, w_, kappa);
    double sum = 0;
    if (stepwise()) {
      sum = memory_sum(t, U, w_);
    } else {
      for (std::size_t i = 0; i < w_.size(); ++i) sum += w_[i] * z[i];
    }
    term.force = -cK * (jump ? sum + jump_term(t, Re) : sum);
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

void SphereHistory::reset_memory(double t, std::span<const double> z) {
  window_ = left_ok_ = false;
  z_.assign(z.begin(), z.end());
  tn_ = t;
  np_ = 0;
  ++z_gen_;
}

namespace {
// M_top/Δ^(top+1) = Σ_k c_k (−x)^k, c_k = top!/(top+k+1)!, top = kPoints − 1 (the soe-step series, x ≤ 1/2).
constexpr int kTopTerms = 12;
constexpr std::array<double, kTopTerms> top_series(int top) {
  std::array<double, kTopTerms> c{};
  double v = 1.0 / (top + 1);
  for (int k = 0; k < kTopTerms; ++k) {
    c[k] = v;
    v /= top + k + 2;
  }
  return c;
}
}  // namespace

void SphereHistory::fill_step(StepCache& c, double dt, std::size_t from, std::size_t to) const {
  // M_0 = (1 − e^(−x))/λ, M_j = (Δ^j − j M_(j−1))/λ for x = λΔ ≥ 1/2; below, the top M by its series
  // M_j = Δ^(j+1) Σ_k j! (−x)^k/(j+k+1)! and the lower ones downward, M_(j−1) = (Δ^j − λ M_j)/j (stable for
  // small x), with e^(−x) = 1 − λ M_0: no exponential there.
  static constexpr std::array<double, kTopTerms> kTopSeries = top_series(kPoints - 1);
  static constexpr std::array<double, kPoints + 1> inv = [] {
    std::array<double, kPoints + 1> v{};
    for (int j = 1; j <= kPoints; ++j) v[j] = 1.0 / j;
    return v;
  }();
  constexpr int top = kPoints - 1;
  std::array<double, kPoints + 1> dp{1};  // Δ^j
  for (int j = 1; j <= kPoints; ++j) dp[j] = dp[j - 1] * dt;
  const auto& lam = soe_->rates();
  const std::size_t n = lam.size();
  // The rates ascend: the series below `split`, the exponentials from it (two branch-free loops).
  const auto split =
      std::clamp(static_cast<std::size_t>(std::lower_bound(lam.begin(), lam.end(), 0.5 / dt) - lam.begin()), from, to);
  for (std::size_t i = from; i < split; ++i) {
    const double x = lam[i] * dt;
    double sum = kTopSeries[kTopTerms - 1];  // Horner: truncation 1.2e-15 relative at x = 1/2
    for (int k = kTopTerms - 2; k >= 0; --k) sum = kTopSeries[k] - x * sum;
    std::array<double, kPoints> M;
    M[top] = dp[top + 1] * sum;
    for (int j = top; j > 0; --j) M[j - 1] = (dp[j] - lam[i] * M[j]) * inv[j];
    c.e[i] = 1 - lam[i] * M[0];
    for (int j = 0; j < kPoints; ++j) c.m[j * n + i] = M[j];
  }
  for (std::size_t i = split; i < to; ++i) {
    const double x = lam[i] * dt;
    const double e = x > SoeFastModes::kFast ? 0.0 : std::exp(-x), il = inv_rate_[i];  // e^(−40) z is below rounding
    c.e[i] = e;
    double M = (1 - e) * il;
    c.m[i] = M;
    for (int j = 1; j < kPoints; ++j) c.m[j * n + i] = M = (dp[j] - j * M) * il;
  }
}

void SphereHistory::share_steps_with(const SphereHistory* twin) {
  twin_ = twin && twin->stepwise() && twin->soe_ == soe_ ? twin : nullptr;
}

void SphereHistory::new_step(StepCache& c, double dt) const {
  const std::size_t n = soe_->modes();
  const StepCache* shared = nullptr;  // an equal sphere's values at the same Δ (the same kernel and weights)
  if (twin_)
    for (const auto& o : twin_->cache_)
      if (o.dt == dt) shared = &o;
  if (shared) {
    c.fast = shared->fast;
    c.full = shared->full;
    const std::size_t to = c.full ? n : c.fast;
    std::copy_n(shared->e.begin(), to, c.e.begin());
    std::copy_n(shared->we.begin(), c.fast, c.we.begin());
    for (std::size_t j = 0; j < kPoints; ++j) std::copy_n(shared->m.begin() + j * n, to, c.m.begin() + j * n);
    c.sums = shared->sums;
  } else if (fixed_weights_) {
    fill_basset(c, dt);
  } else {
    fill_step(c, dt, 0, n);
    c.fast = n;
    c.full = true;
  }
  c.dt = dt;
  c.z_gen = c.sum0_gen = -1;
}

void SphereHistory::fill_basset(StepCache& c, double dt) const {
  const std::size_t n = soe_->modes();
  c.fast = fast_.first(dt);
  c.full = c.fast == n;
  fill_step(c, dt, 0, c.fast);
  for (std::size_t i = 0; i < c.fast; ++i) c.we[i] = w_[i] * c.e[i];
  const auto outer = fast_.sums(dt, c.fast);
  for (std::size_t j = 0; j < kPoints; ++j) c.sums[j + 1] = dot(w_.data(), &c.m[j * n], c.fast) + outer[j];
}

void SphereHistory::fill_all_modes(StepCache& c) const {
  if (c.full) return;
  fill_step(c, c.dt, c.fast, soe_->modes());  // Basset's fast modes: e = 0, no exponential
  c.full = true;
}

int SphereHistory::slot_for(double dt) const {
  int lru = 0;
  for (int k = 0; k < kSlots; ++k) {
    if (cache_[k].dt == dt) return k;
    if (cache_[k].used < cache_[lru].used) lru = k;
  }
  return lru;
}

const SphereHistory::StepCache& SphereHistory::step_at(double dt) const {
  if (cache_[cur_].dt != dt) {
    cur_ = slot_for(dt);
    if (cache_[cur_].dt != dt) new_step(cache_[cur_], dt);
  }
  StepCache& c = cache_[cur_];
  c.used = ++uses_;
  if (c.z_gen != z_gen_) {
    c.q_at = horner(pq_.data(), np_ - 1, dt);
    c.w_at = horner(pw_.data(), np_, dt);
    if (fixed_weights_) {
      if (c.sum0_gen != z_gen_) c.sums[0] = dot(c.we.data(), z_.data(), c.fast);  // the fast modes' e^(−λΔ): 0
      c.sum0_gen = z_gen_;
      c.a = c.b = 0;
      for (int j = 0; j < np_; ++j) {
        if (j + 1 < np_) c.a += (j + 1) * pq_[j + 1] * c.sums[j + 1];
        c.b += (j + 1) * pw_[j + 1] * c.sums[j + 1];
      }
    }
    c.z_gen = z_gen_;
  }
  return c;
}

bool SphereHistory::in_step(double t, double U) const {
  const double dt = t - tn_;
  if (!(dt > 0) || np_ == 0) return false;
  // P = Q + ((U − Q(Δ))/ω(Δ)) ω: the step's own part Q and ω (step_polynomial) and the current (t, U).
  const StepCache& c = step_at(dt);
  c_now_ = (U - c.q_at) / c.w_at;
  return true;
}

namespace {
// Newton's divided differences through m points, expanded into monomials (m a constant: the loops unroll).
template <int m, std::size_t n>
std::array<double, n> newton_monomials(const double* s, const double* u) {
  static_assert(m >= 1 && m <= static_cast<int>(n));
  std::array<double, n> dd{}, c{};
  for (int k = 0; k < m; ++k) dd[k] = u[k];
  for (int k = 1; k < m; ++k)
    for (int i = m - 1; i >= k; --i) dd[i] = (dd[i] - dd[i - 1]) / (s[i] - s[i - k]);
  c[0] = dd[m - 1];
  for (int k = m - 2; k >= 0; --k) {
    for (int j = m - 1 - k; j >= 1; --j) c[j] = c[j - 1] - s[k] * c[j];
    c[0] = dd[k] - s[k] * c[0];
  }
  return c;
}

// Π_(k<m) (σ − s_k) in monomials of σ.
template <int m, std::size_t n>
std::array<double, n> node_polynomial(const double* s) {
  static_assert(m >= 0 && m < static_cast<int>(n));
  std::array<double, n> p{};
  p[0] = 1;
  for (int k = 0; k < m; ++k) {
    for (int j = k + 1; j >= 1; --j) p[j] = p[j - 1] - s[k] * p[j];
    p[0] = -s[k] * p[0];
  }
  return p;
}
}  // namespace

std::array<double, SphereHistory::kPoints> SphereHistory::monomials_through(const double* s, const double* u, int m) {
  static_assert(kPoints == 3);
  switch (m) {
    case 1: return newton_monomials<1, kPoints>(s, u);
    case 2: return newton_monomials<2, kPoints>(s, u);
    case 3: return newton_monomials<3, kPoints>(s, u);
    default: return {};
  }
}

void SphereHistory::step_polynomial() {
  // Q through the accepted points (s_k, U_k), s_k = t_k − t_n (s_1 = 0), in monomials; ω(σ) = Π_k (σ − s_k).
  // P' = Q' + c ω' with c = (U − Q(Δ))/ω(Δ) for the current (t, U).
  std::array<double, kPoints> sk{};
  for (int k = 0; k < np_; ++k) sk[k] = pt_[k] - tn_;
  pq_ = monomials_through(sk.data(), pu_.data(), np_);
  switch (np_) {
    case 1: pw_ = node_polynomial<1, kPoints + 1>(sk.data()); break;
    case 2: pw_ = node_polynomial<2, kPoints + 1>(sk.data()); break;
    case 3: pw_ = node_polynomial<3, kPoints + 1>(sk.data()); break;
    default: pw_ = node_polynomial<0, kPoints + 1>(sk.data());
  }
}

double SphereHistory::dot(const double* a, const double* b, std::size_t n) {
  double sum = 0;  // in order: a run's rounding does not depend on the vector unit
  for (std::size_t i = 0; i < n; ++i) sum += a[i] * b[i];
  return sum;
}

double SphereHistory::horner(const double* c, int degree, double x) {
  double v = degree >= 0 ? c[degree] : 0.0;
  for (int j = degree - 1; j >= 0; --j) v = v * x + c[j];
  return v;
}

double SphereHistory::in_step_slope(int j, double c) const {
  return (j + 1 < np_ ? (j + 1) * pq_[j + 1] : 0.0) + c * (j + 1) * pw_[j + 1];
}

double SphereHistory::memory_sum(double t, double U, std::span<const double> w) const {
  if (window_ && t < acc_t_ && t > tn_) return output_sum(t - tn_);  // an output inside the accepted step
  if (!in_step(t, U)) {
    double sum = 0;
    for (std::size_t i = 0; i < z_.size(); ++i) sum += w[i] * z_[i];
    return sum;
  }
  const StepCache& c = cache_[cur_];
  if (fixed_weights_) return c.sums[0] + c.a + c_now_ * c.b;  // Re-independent weights: the sums in_step cached
  modes_in_step(c, zs_);
  double sum = 0;
  for (std::size_t i = 0; i < z_.size(); ++i) sum += w[i] * zs_[i];
  return sum;
}

inline void SphereHistory::modes_at(const StepCache& c, double cf, std::span<double> out) const {
  // z_i = e^(−λ_i Δ) z_i + Σ_j d_j M_ij (d_j = 0 for j ≥ np_), out apart from z_ (a vector loop).
  static_assert(kPoints == 3);
  const std::size_t n = out.size();
  std::array<double, kPoints> d{};
  for (int j = 0; j < np_; ++j) d[j] = in_step_slope(j, cf);
  const double *__restrict e = c.e.data(), *__restrict M0 = c.m.data(), *__restrict M1 = M0 + n, *__restrict M2 = M1 + n,
               *__restrict z = z_.data();
  double* __restrict o = out.data();
  for (std::size_t i = 0; i < n; ++i) o[i] = e[i] * z[i] + (d[0] * M0[i] + d[1] * M1[i] + d[2] * M2[i]);
}

double SphereHistory::modes_in_step(const StepCache& c, std::span<double> out) const {
  // With Basset's weights also Σ w_i e^(−λ_i Δ) z_i(t) in order (as step_at's dot): CVODE often keeps h, and the next
  // step asks it.
  modes_at(c, c_now_, out);
  return fixed_weights_ ? dot(c.we.data(), out.data(), c.fast) : 0.0;
}

void SphereHistory::accept_step(double t, double U) {
  next_ok_ = false;
  if (!stepwise() || !fixed_weights_ || np_ == 0 || !(t > tn_)) return;
  window_ = true;
  acc_t_ = t;
  acc_u_ = U;
  outputs_.reset();
  outputs_built_ = false;
  step_end(t, U);
}

void SphereHistory::step_end(double t, double U) {
  // The modes at the end (advance_memory takes them) and their sum at this Δ; S, S' there for the interpolants.
  step_at(t - tn_);
  StepCache& c = cache_[cur_];
  out_cf_ = (U - c.q_at) / c.w_at;  // P through the accepted end
  fill_all_modes(c);
  modes_at(c, out_cf_, z_next_);
  if (interpolate_) outputs_end_ = end_of(c, out_cf_);
  next_ok_ = true;
  next_gen_ = z_gen_;
  next_sum0_ = dot(c.we.data(), z_next_.data(), c.fast);  // in order, as step_at's
}

StepOutputs::End SphereHistory::end_of(const StepCache& c, double cf) const {
  // S = Σ w e z + Σ_j P'_j Σ w M_j; S' = Σ w (P' − λ z) = −Σ w λ e z + P'_0 Σ w e + Σ_(j≥1) j P'_j Σ w M_(j−1),
  // with λ M_0 = 1 − e and λ M_j = Δ^j − j M_(j−1) (the weights' sum cancels).
  const auto& lam = soe_->rates();
  double wlez = 0, we = 0;
  for (std::size_t i = 0; i < c.fast; ++i) {
    wlez += c.we[i] * lam[i] * z_[i];
    we += c.we[i];
  }
  StepOutputs::End e;
  e.value = c.sums[0] + c.a + cf * c.b;
  e.slope = in_step_slope(0, cf) * we - wlez;
  for (int j = 1; j < np_; ++j) e.slope += j * in_step_slope(j, cf) * c.sums[j];
  return e;
}

double SphereHistory::check_lag(double h) const {
  double best = 0.5 * h;
  double dist = INFINITY;
  for (const auto& c : cache_)
    if (c.dt >= StepOutputs::kCheckFrom * h && c.dt <= (1 - StepOutputs::kCheckFrom) * h && std::abs(c.dt - 0.5 * h) < dist)
      best = c.dt, dist = std::abs(c.dt - 0.5 * h);
  return best;
}

void SphereHistory::build_outputs() const {
  outputs_built_ = true;
  const double h = acc_t_ - tn_;
  if (!interpolate_ || !left_ok_) return;
  const StepOutputs::End end = outputs_end_;  // step_end's
  const double dc = check_lag(h);
  const StepCache& cc = step_at(dc);
  const double sc = cc.sums[0] + cc.a + out_cf_ * cc.b;
  const double scale = std::max({std::abs(left_.value), std::abs(sc), std::abs(end.value)});
  const double tol = output_rtol_ * scale + output_atol_;
  // Beyond the solver's tolerance, the memory's own error in the step: its value at Δc with the polynomial one degree
  // lower (the oldest point left out). The interpolant adds no more than that.
  double own = 0;
  if (np_ >= 2 && StepOutputs::estimate(h, left_, end, dc, sc) > tol) {
    std::array<double, kPoints> sk{}, uk{};
    for (int k = 0; k + 1 < np_; ++k) sk[k] = pt_[k] - tn_, uk[k] = pu_[k];
    sk[np_ - 1] = h, uk[np_ - 1] = acc_u_;
    const auto c = monomials_through(sk.data(), uk.data(), np_);
    double low = cc.sums[0];  // + Σ_j P'_j Σ w M_j, P'_j = (j + 1) c_(j+1)
    for (int j = 0; j + 1 < np_; ++j) low += (j + 1) * c[j + 1] * cc.sums[j + 1];
    own = std::abs(sc - low);
  }
  outputs_.emplace(h, left_, end, dc, sc, std::max(tol, own));
}

double SphereHistory::output_sum(double dt) const {
  if (!outputs_built_) build_outputs();
  if (outputs_ && outputs_->accepted()) {
    ++interpolated_;
    return outputs_->value(dt);
  }
  ++exact_outputs_;
  const StepCache& c = step_at(dt);
  return c.sums[0] + c.a + out_cf_ * c.b;
}

void SphereHistory::advance_memory(double t, double U, bool restart) {
  if (!stepwise()) return;
  // The accepted step's end (step_end) when this is that time and velocity and the modes have not moved since.
  const bool at_end = window_ && next_ok_ && t == acc_t_ && U == acc_u_ && next_gen_ == z_gen_;
  window_ = next_ok_ = false;
  const bool moved = in_step(t, U);  // at_end: true (accept_step saw Δ > 0 and a polynomial)
  if (!moved && np_ > 0 && !restart) return;  // not a new time
  // The end's value and slope start the next step's interpolant (not across a restart: U' may jump there).
  left_ok_ = moved && !restart && fixed_weights_ && interpolate_;
  if (left_ok_) left_ = at_end ? outputs_end_ : end_of(cache_[cur_], c_now_);
  if (moved) {
    StepCache& c = cache_[cur_];
    double sum0 = 0;
    if (at_end) {
      z_.swap(z_next_);
      sum0 = next_sum0_;
    } else {
      fill_all_modes(c);
      sum0 = modes_in_step(c, zs_);
      z_.swap(zs_);
    }
    if (fixed_weights_) {
      c.sums[0] = sum0;
      c.sum0_gen = z_gen_ + 1;  // the generation these modes get below
    }
  }
  if (restart || np_ == 0) {
    np_ = 1;
  } else {
    for (int k = kPoints - 1; k > 0; --k) pt_[k] = pt_[k - 1], pu_[k] = pu_[k - 1];
    np_ = std::min(np_ + 1, kPoints);
  }
  pt_[0] = t;
  pu_[0] = U;
  tn_ = t;
  step_polynomial();
  ++z_gen_;  // e and M stay valid for their Δ
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
