// SPDX-License-Identifier: BSD-3-Clause
#include "contact/history_kernel.hpp"

#include <cerf.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "contact/formulas.hpp"

namespace imcol::contact {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
using cplx = std::complex<double>;

// ---------- Universal shape φ(x) = (1 + x^p)^(−c1), p = 3/(2 c1) ----------

// ln(1 + e^a) without overflow.
double softplus(double a) { return a > 30 ? a + std::log1p(std::exp(-a)) : std::log1p(std::exp(a)); }

// ln φ(x) for x ≥ 0.
double log_phi(double x, double c1, double p) {
  if (x <= 0) return 0.0;
  return -c1 * softplus(p * std::log(x));
}

// Gauss–Legendre nodes/weights on [−1, 1] (Newton on P_n).
template <int N>
struct GaussLegendre {
  std::array<double, N> x{}, w{};
  GaussLegendre() {
    for (int i = 0; i < N; ++i) {
      double z = std::cos(pi * (i + 0.75) / (N + 0.5)), dp = 1;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = z;
        for (int k = 2; k <= N; ++k) {
          const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = N * (z * p1 - p0) / (z * z - 1);
        const double dz = p1 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x[i] = z;
      w[i] = 2 / ((1 - z * z) * dp * dp);
    }
  }
};

// Cubic Hermite basis on [0, 1] (values h00, h10, h01, h11).
std::array<double, 4> hermite(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {2 * t3 - 3 * t2 + 1, t3 - 2 * t2 + t, -2 * t3 + 3 * t2, t3 - t2};
}

// G(y) = ∫_0^y x^(−1/2) φ(x) dx for one c1. Stored as lg = ln(G/(2√y)) on a uniform grid in
// t = ln y over [1e-12, 1e12], with its exact first and second derivatives; lg is flat below and
// linear above, and quintic Hermite interpolation is accurate to ~1e-14. Series outside the grid.
class GTable {
 public:
  explicit GTable(double c1) : c1_(c1), p_(1.5 / c1) {
    constexpr int n = 2800;
    t0_ = std::log(1e-12);
    dt_ = (std::log(1e12) - t0_) / n;
    lg_.resize(n + 1);
    dlg_.resize(n + 1);
    d2lg_.resize(n + 1);
    const GaussLegendre<8> gl;
    // dG/dt = A(t) = √y φ(y); dA/dt = A (1/2 − c1 p y^p/(1 + y^p))
    const auto A = [&](double t) { return std::exp(0.5 * t + log_phi(std::exp(t), c1_, p_)); };
    double G = small(std::exp(t0_));
    for (int k = 0; k <= n; ++k) {
      const double t = t0_ + k * dt_;
      if (k > 0) {
        const double a = t - dt_, half = 0.5 * dt_;
        double inc = 0;
        for (int i = 0; i < 8; ++i) inc += gl.w[i] * A(a + half * (1 + gl.x[i]));
        G += half * inc;
      }
      const double r = A(t) / G, dA_over_A = 0.5 - c1_ * p_ / (1 + std::exp(-p_ * t));
      lg_[k] = std::log(G) - std::log(2.0) - 0.5 * t;
      dlg_[k] = r - 0.5;
      d2lg_[k] = r * dA_over_A - r * r;
    }
    y_hi_ = std::exp(t0_ + n * dt_);
    G_inf_ = G + tail(y_hi_);
  }
  double operator()(double y) const {
    if (y <= 0) return 0.0;
    const double t = std::log(y);
    const double u = (t - t0_) / dt_;
    if (u <= 0) return small(y);
    if (y >= y_hi_) return G_inf_ - tail(y);
    const auto k = std::min(static_cast<std::size_t>(u), lg_.size() - 2);
    const double x = u - static_cast<double>(k), x2 = x * x, x3 = x2 * x, x4 = x3 * x, x5 = x4 * x;
    const double h2 = dt_ * dt_;  // quintic Hermite basis
    const double lg = (1 - 10 * x3 + 15 * x4 - 6 * x5) * lg_[k] + (10 * x3 - 15 * x4 + 6 * x5) * lg_[k + 1] +
                      dt_ * ((x - 6 * x3 + 8 * x4 - 3 * x5) * dlg_[k] + (-4 * x3 + 7 * x4 - 3 * x5) * dlg_[k + 1]) +
                      0.5 * h2 * ((x2 - 3 * x3 + 3 * x4 - x5) * d2lg_[k] + (x3 - 2 * x4 + x5) * d2lg_[k + 1]);
    return 2 * std::sqrt(y) * std::exp(lg);
  }

 private:
  // φ ≈ 1 − c1 x^p + c1(c1+1)/2 x^2p − …, integrated term by term (y ≤ 1e-12: error O(y^4p) < 1e-28).
  double small(double y) const {
    const double q = std::pow(y, p_), c = c1_;
    return 2 * std::sqrt(y) *
           (1 - c * q / (2 * p_ + 1) + c * (c + 1) / 2 * q * q / (4 * p_ + 1) -
            c * (c + 1) * (c + 2) / 6 * q * q * q / (6 * p_ + 1));
  }
  // ∫_y^∞ x^(−1/2) φ dx with φ = x^(−3/2)(1 + x^(−p))^(−c1), expanded in x^(−p) (y ≥ 1e12).
  double tail(double y) const {
    const double q = std::pow(y, -p_), c = c1_;
    return (1 - c * q / (1 + p_) + c * (c + 1) / 2 * q * q / (1 + 2 * p_)) / y;
  }
  double c1_, p_, t0_ = 0, dt_ = 0, y_hi_ = 0, G_inf_ = 0;
  std::vector<double> lg_, dlg_, d2lg_;
};

const GTable& g_table(double c1) {
  if (c1 == 2.0) {
    static const GTable t(2.0);
    return t;
  }
  if (c1 == 2.5) {
    static const GTable t(2.5);
    return t;
  }
  throw std::logic_error("history kernel: no G table for this c1");
}

// ---------- Sum of exponentials for s^(−1/2) ----------

struct Term {
  double rate, weight;
};

// n-th McLean/Beylkin–Monzón term (T = horizon).
Term soe_term(int n, double h, double T) {
  const double u = n * h, e = std::exp(-u), x = u - e;
  return {std::exp(x) / T, h * (1 + e) * std::exp(0.5 * x) / std::sqrt(pi * T)};
}

// Largest relative contribution w √s e^(−λ s) of one term on [δ, T].
double term_size(const Term& t, double delta, double T) {
  const double s = std::clamp(0.5 / t.rate, delta, T);
  return t.weight * std::sqrt(s) * std::exp(-t.rate * s);
}

// Terms kept for step h: every term whose largest relative contribution on [δ, T] is at least
// tol/10 with tol = 7 e^(−π²/h) (the tails decay faster than geometrically, so the first
// dropped term bounds the truncation error).
std::vector<Term> soe_terms(double delta, double T, double h) {
  const double cut = 0.7 * std::exp(-pi * pi / h);
  std::vector<Term> lo, hi;
  constexpr int n_max = 100000;
  for (int n = 0; n > -n_max; --n) {
    const Term t = soe_term(n, h, T);
    if (!(t.weight > 0) || term_size(t, delta, T) < cut) break;
    lo.push_back(t);
  }
  for (int n = 1; n < n_max; ++n) {
    const Term t = soe_term(n, h, T);
    if (term_size(t, delta, T) < cut) break;
    hi.push_back(t);
  }
  std::reverse(lo.begin(), lo.end());
  lo.insert(lo.end(), hi.begin(), hi.end());
  return lo;
}

// Log grid on [a, b] with at least `per_decade` points per decade.
std::vector<double> log_grid(double a, double b, double per_decade) {
  const int n = std::max(2, static_cast<int>(std::ceil(per_decade * std::log10(b / a))) + 1);
  std::vector<double> s(n);
  const double d = std::log(b / a) / (n - 1);
  for (int i = 0; i < n; ++i) s[i] = a * std::exp(i * d);
  s.back() = b;
  return s;
}

// Error grid density: ≥ 200 per decade and ≥ 20 points per period h of the trapezoid error in ln s.
double error_grid_density(double h) { return std::max(200.0, 20 * std::log(10.0) / h); }

// Rates ascending: the terms with λs > 50 (each below 1e-20 of the sum, under half an ulp) are skipped.
double soe_sum(const std::vector<double>& rate, const double* w, double s) {
  double y = 0;
  for (std::size_t i = 0; i < rate.size() && rate[i] * s <= 50; ++i) y += w[i] * std::exp(-rate[i] * s);
  return y;
}

SumOfExponentials build_soe(double delta, double T, double h) {
  SumOfExponentials r;
  r.min_lag = delta;
  r.horizon = T;
  r.step = h;
  for (const Term& t : soe_terms(delta, T, h)) {
    r.rate.push_back(t.rate);
    r.weight.push_back(t.weight);
  }
  r.kappa = 2 * std::sqrt(delta);
  for (std::size_t i = 0; i < r.rate.size(); ++i)
    r.kappa += r.weight[i] * std::expm1(-r.rate[i] * delta) / r.rate[i];
  for (double s : log_grid(delta, T, error_grid_density(h))) {
    const double e = std::abs(soe_sum(r.rate, r.weight.data(), s) * std::sqrt(s) - 1);
    r.max_rel_error = std::max(r.max_rel_error, e);
  }
  return r;
}

void check_interval(double min_lag, double horizon) {
  if (!(min_lag > 0) || !std::isfinite(min_lag))
    throw std::invalid_argument("inverse_sqrt_soe: min_lag must be positive and finite");
  if (!(horizon > min_lag) || !std::isfinite(horizon))
    throw std::invalid_argument("inverse_sqrt_soe: horizon must be finite and larger than min_lag");
}

// ---------- Faddeeva function and the exact Basset solutions ----------

cplx faddeeva(cplx z) { return {re_w_of_z(z.real(), z.imag()), im_w_of_z(z.real(), z.imag())}; }

// F^(n)(σ), n = 0..5, of F(σ) = w(−iσ√t): w' = −2zw + 2i/√π, w^(n+1) = −2z w^(n) − 2n w^(n−1).
std::array<cplx, 6> F_derivatives(cplx sigma, double t) {
  const cplx a(0, -std::sqrt(t)), z = a * sigma;
  std::array<cplx, 6> w{};
  w[0] = faddeeva(z);
  w[1] = -2.0 * z * w[0] + cplx(0, 2 / std::sqrt(pi));
  for (int n = 1; n < 5; ++n) w[n + 1] = -2.0 * z * w[n] - 2.0 * n * w[n - 1];
  cplx an = 1;
  for (auto& v : w) {
    v *= an;
    an *= a;
  }
  return w;
}

// Large |z| = |σ|√t (Im z ≥ 0): w(z) ~ (i/(√π z)) Σ_k (2k−1)!!/(2z²)^k, error ~e^(−|z|²), so
//   σF(σ) ~ −(1/√(πt)) Σ_k c_k σ^(−2k),  F/σ ~ −(1/√(πt)) Σ_k c_k σ^(−2k−2),
//   c_k = (−1)^k (2k−1)!!/(2t)^k,
// and the divided differences D_n of σ^(−n) follow D_n = D_(n−1)/σ+ + D_1 σ−^(−(n−1)),
// D_1 = −1/(σ+σ−): no cancellation, unlike the closed form at large t.
cplx divided_difference_asymptotic(cplx sp, cplx sm, double t, bool over_sigma) {
  const cplx D1 = -1.0 / (sp * sm);
  cplx Dn = D1, sm_pow = 1;  // D_n, σ−^(−(n−1))
  int n = 1;
  const auto advance_to = [&](int target) {
    while (n < target) {
      sm_pow /= sm;
      Dn = Dn / sp + D1 * sm_pow;
      ++n;
    }
  };
  // |D_n| oscillates for complex roots: truncate on the envelope |c_k| n r^(n+1), r = 1/min|σ±|,
  // with |c_k| r^n (= scaled) updated by ratios, so that nothing overflows.
  const double r = 1 / std::min(std::abs(sp), std::abs(sm));
  cplx sum = 0;
  double c = 1, scaled = over_sigma ? r * r : 1, prev = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 500; ++k) {
    if (k > 0) {
      c *= -(2 * k - 1) / (2 * t);
      scaled *= (2 * k - 1) / (2 * t) * r * r;
    }
    const int power = over_sigma ? 2 * k + 2 : 2 * k;
    if (power == 0) continue;  // constant: no divided difference
    const double envelope = scaled * power * r;
    if (envelope >= prev) break;  // asymptotic series: stop at the smallest term
    advance_to(power);
    sum += c * Dn;
    prev = envelope;
    if (envelope < 1e-18 * std::abs(sum)) break;
  }
  return -sum / std::sqrt(pi * t);
}

// Divided difference [g(σ+) − g(σ−)]/(σ+ − σ−) for g = σF (relaxation) or g = F/σ (settling).
// Both |σ±|²t ≥ 40: the asymptotic series above (error ~e^(−40); the closed form would lose ~|σ|²t
// digits to cancellation). Close roots (|d|√t < 1e-2, and |d| < 1e-2|m| for F/σ): Taylor series about
// the midpoint m, g'(m) + g'''(m) (d/2)²/6 + g⁽⁵⁾(m) (d/2)⁴/120, the double-root limit at d = 0.
// Otherwise the closed form. Measured against 80-digit values: ≲ 1e-13 relative, up to 3e-12 for
// nearly double roots just below |σ|²t = 40.
cplx divided_difference(cplx sp, cplx sm, double t, bool over_sigma) {
  if (std::norm(sp) * t >= 40 && std::norm(sm) * t >= 40)
    return divided_difference_asymptotic(sp, sm, t, over_sigma);
  const cplx d = sp - sm, m = 0.5 * (sp + sm);
  const bool close = std::abs(d) * std::sqrt(t) < 1e-2 && (!over_sigma || std::abs(d) < 1e-2 * std::abs(m));
  const auto g = [&](cplx s) {
    const cplx F = faddeeva(cplx(0, -std::sqrt(t)) * s);
    return over_sigma ? F / s : s * F;
  };
  if (!close) return (g(sp) - g(sm)) / d;
  const auto F = F_derivatives(m, t);
  std::array<cplx, 6> gd{};
  for (int n = 1; n <= 5; n += 2) {
    if (!over_sigma) {
      gd[n] = m * F[n] + double(n) * F[n - 1];
    } else {  // Leibniz: (F σ^(−1))^(n) = Σ C(n,k) F^(n−k) (−1)^k k! σ^(−k−1)
      cplx sum = 0, mk = 1.0 / m;
      double binom = 1, fact = 1;
      for (int k = 0; k <= n; ++k) {
        sum += binom * fact * (k % 2 ? -1.0 : 1.0) * F[n - k] * mk;
        mk /= m;
        binom = binom * (n - k) / (k + 1);
        fact *= k + 1;
      }
      gd[n] = sum;
    }
  }
  const cplx e = 0.25 * d * d;
  return gd[1] + gd[3] * e / 6.0 + gd[5] * e * e / 120.0;
}

void check_basset_args(double alpha, double gamma, double t) {
  if (!(alpha > 0) || !std::isfinite(alpha))
    throw std::invalid_argument("basset solution: alpha must be positive and finite");
  if (!(gamma >= 0) || !std::isfinite(gamma))
    throw std::invalid_argument("basset solution: gamma must be non-negative and finite");
  if (!(t >= 0) || !std::isfinite(t)) throw std::invalid_argument("basset solution: t must be non-negative");
}

// Roots σ± of σ² + γσ + α = 0.
std::pair<cplx, cplx> basset_roots(double alpha, double gamma) {
  const cplx r = std::sqrt(cplx(gamma * gamma - 4 * alpha, 0));
  return {0.5 * (-gamma + r), 0.5 * (-gamma - r)};
}

}  // namespace

// ---------- HistoryKernel ----------

HistoryKernel::HistoryKernel(KernelKind kind, double D, double nu) : kind_(kind), D_(D), nu_(nu) {
  if (!(D > 0) || !std::isfinite(D)) throw std::invalid_argument("HistoryKernel: diameter must be positive");
  if (!(nu > 0) || !std::isfinite(nu))
    throw std::invalid_argument("HistoryKernel: viscosity must be positive");
  switch (kind) {
    case KernelKind::basset: break;
    case KernelKind::mei_adrian: c1_ = 2.0, c2_ = 0.105; break;
    case KernelKind::kim: c1_ = 2.5, c2_ = 0.126; break;
    case KernelKind::dorgan_loth: c1_ = 2.5, c2_ = 0.2; break;
  }
}

double HistoryKernel::crossover_time(double Re) const {
  if (kind_ == KernelKind::basset || !(Re > 0)) return inf;
  const double f = 0.75 / Re + c2_;
  return std::cbrt(4 / pi) * D_ * D_ / nu_ * f * f;  // (2/√π)^(2/3) = (4/π)^(1/3)
}

double HistoryKernel::K(double s, double Re) const {
  const double KB = D_ / (2 * std::sqrt(pi * nu_ * s));
  const double sc = crossover_time(Re);
  if (std::isinf(sc)) return KB;
  return KB * std::exp(log_phi(s / sc, c1_, 1.5 / c1_));
}

double HistoryKernel::integral(double s, double Re) const {
  if (!(s > 0)) return 0.0;
  const double C = D_ / (2 * std::sqrt(pi * nu_));
  const double sc = crossover_time(Re);
  if (std::isinf(sc)) return 2 * C * std::sqrt(s);
  return C * std::sqrt(sc) * g_table(c1_)(s / sc);
}

// ---------- Sum of exponentials ----------

SumOfExponentials inverse_sqrt_soe(double min_lag, double horizon, double tol) {
  check_interval(min_lag, horizon);
  if (!(tol > 1e-15 && tol < 0.1))
    throw std::invalid_argument("inverse_sqrt_soe: tol must lie in (1e-15, 0.1)");
  return build_soe(min_lag, horizon, pi * pi / std::log(7 / tol));
}

// The term count falls (roughly monotonically) with h. Bisect for the plateau of h giving
// `modes` terms, then take the h on it with the smallest measured error. If the count jumps
// over `modes`, the nearest achievable count is returned (ties: the larger one).
SumOfExponentials inverse_sqrt_soe_modes(double min_lag, double horizon, int modes) {
  check_interval(min_lag, horizon);
  if (modes < 2 || modes > 400)
    throw std::invalid_argument("inverse_sqrt_soe_modes: modes must lie in [2, 400]");
  const auto count = [&](double h) { return static_cast<int>(soe_terms(min_lag, horizon, h).size()); };
  const double h_min = pi * pi / std::log(7 / 1e-300), h_max = 50;
  if (count(h_min) < modes) return build_soe(min_lag, horizon, h_min);
  // Smallest h with count ≤ target, by bisection (count(lo) > target ≥ count(hi)).
  const auto first_at_most = [&](int target) {
    double lo = h_min, hi = h_max;
    for (int it = 0; it < 80 && hi - lo > 1e-14 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (count(mid) > target ? lo : hi) = mid;
    }
    return std::pair{lo, hi};
  };
  auto [below, a] = first_at_most(modes);
  const int n_a = count(a);
  if (n_a != modes) {
    const int n_below = count(below);
    return build_soe(min_lag, horizon, (n_below - modes <= modes - n_a) ? below : a);
  }
  const double b = first_at_most(modes - 1).first;  // end of the plateau
  SumOfExponentials best;
  bool have = false;
  constexpr int samples = 8;
  for (int i = 0; i <= samples; ++i) {
    const double h = a + (b - a) * i / samples;
    if (count(h) != modes) continue;
    SumOfExponentials r = build_soe(min_lag, horizon, h);
    if (!have || r.max_rel_error < best.max_rel_error) best = std::move(r), have = true;
  }
  return have ? best : build_soe(min_lag, horizon, a);
}

std::complex<double> inverse_sqrt_transfer(double omega) {
  return std::sqrt(pi) * std::sqrt(cplx(0, -omega));  // principal branch
}

std::complex<double> soe_transfer(const SumOfExponentials& soe, double omega) {
  const cplx iw(0, omega);
  cplx sum = soe.kappa;
  for (std::size_t i = 0; i < soe.rate.size(); ++i) sum += soe.weight[i] / (soe.rate[i] - iw);
  return -iw * sum;
}

// ---------- SoeKernel ----------

namespace {
constexpr double samples_per_decade = 20;  // fit samples on [min_lag, horizon]
constexpr double tikhonov = 1e-9;         // μ relative to ‖M‖_F

/// The least-squares fit's operator on n_s samples s_j log-spaced by ds on [min_lag, horizon].
struct SoeFit {
  int n_s = 0;
  double ds = 0;
  Eigen::VectorXd rho;  // ρ_j = Σ_i M_ji
  Eigen::MatrixXd P;    // the Tikhonov pseudo-inverse of M, m × n_s
};

// Fit in relative variables w_i = w_B,i (1 + c_i) with rows scaled by 1/K_B(s_j):
//   M_ji = w_base,i √s_j e^(−λ_i s_j),  target b_j = (φ(s_j/s_c) − 1) ρ_j,  ρ_j = Σ_i M_ji,
// i.e. the fit is to φ × (Basset SoE), so the Basset SoE's own error is not amplified by 1/φ in
// the tail, and b = 0 (w = w_B) at Re = 0. c = P b, P the Tikhonov pseudo-inverse (QR of [M; μI]).
SoeFit soe_fit(const SumOfExponentials& base, const std::vector<double>& rate) {
  const std::size_t m = rate.size();
  const double delta = base.min_lag, T = base.horizon;
  SoeFit f;
  f.n_s = std::max(static_cast<int>(std::ceil(samples_per_decade * std::log10(T / delta))) + 1, static_cast<int>(m));
  const int n_s = f.n_s;
  f.ds = std::log(T / delta) / (n_s - 1);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n_s + m, m);
  f.rho.resize(n_s);
  for (int j = 0; j < n_s; ++j) {
    const double s = delta * std::exp(j * f.ds);
    for (std::size_t i = 0; i < m; ++i)
      A(j, i) = base.weight[i] * std::sqrt(s) * std::exp(-rate[i] * s);
    f.rho[j] = A.row(j).sum();
  }
  const double mu = tikhonov * A.topRows(n_s).norm();
  for (std::size_t i = 0; i < m; ++i) A(n_s + i, i) = mu;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::MatrixXd Q1 = (qr.householderQ() * Eigen::MatrixXd::Identity(n_s + m, m)).topRows(n_s);
  f.P = qr.matrixQR().topLeftCorner(m, m).triangularView<Eigen::Upper>().solve(Q1.transpose());
  return f;
}
}  // namespace

SoeKernel::SoeKernel(const HistoryKernel& kernel, const SumOfExponentials& base)
    : kernel_(kernel), base_(base), rate_(base.rate) {
  const std::size_t m = rate_.size();
  if (m == 0 || base.weight.size() != m || !(base.min_lag > 0) || !(base.horizon > base.min_lag))
    throw std::invalid_argument("SoeKernel: malformed sum of exponentials");
  const double C = kernel.diameter() / (2 * std::sqrt(pi * kernel.nu()));
  const double delta = base.min_lag, T = base.horizon;
  w_basset_.resize(m);
  decay_.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    w_basset_[i] = C * base.weight[i];
    decay_[i] = -std::expm1(-rate_[i] * delta) / rate_[i];
  }
  kappa_basset_ = C * base.kappa;
  if (kernel.kind() == KernelKind::basset) return;

  const SoeFit fit = soe_fit(base, rate_);
  const int n_s = fit.n_s;
  const double ds = fit.ds;
  const Eigen::VectorXd& rho = fit.rho;
  const Eigen::MatrixXd& P = fit.P;

  // Nodes τ_k = ln s_c with spacing ds (a finer one changes nothing measurable), from s_c(Re = ∞)
  // up to where 1 − φ(T/s_c) ≈ c1 (T/s_c)^p < 1e-3 max_rel_error; the top node is Basset itself
  // (zero slope), so the blend is C¹. Weights in between: cubic Hermite with the exact slopes.
  const double c1 = kernel.c1(), p = 1.5 / c1;
  tau0_ = std::log(kernel.crossover_time(inf));
  dtau_ = ds;
  const double eps = 1e-3 * std::max(base.max_rel_error, 1e-16);
  const double tau_top = std::log(T) + std::log(c1 / eps) / p;
  const int n_nodes = std::max(2, static_cast<int>(std::ceil((tau_top - tau0_) / dtau_)) + 1);
  // φ − 1 and dφ/dτ = c1 p x^p/(1 + x^p) φ on one grid: ln(s_j/s_c,k) = ln δ − τ0 + (j − k) dτ.
  const int off = n_nodes - 1, n_g = n_s - 1 + n_nodes;
  std::vector<double> phi_m1(n_g), dphi(n_g);
  for (int g = 0; g < n_g; ++g) {
    const double a = p * (std::log(delta) - tau0_ + (g - off) * dtau_), lp = -c1 * softplus(a);
    phi_m1[g] = std::expm1(lp);
    dphi[g] = c1 * p / (1 + std::exp(-a)) * std::exp(lp);
  }
  Eigen::MatrixXd B(n_s, 2 * off);
  for (int k = 0; k < off; ++k)
    for (int j = 0; j < n_s; ++j) {
      B(j, 2 * k) = rho[j] * phi_m1[j - k + off];
      B(j, 2 * k + 1) = rho[j] * dphi[j - k + off];
    }
  const Eigen::MatrixXd Cm = P * B;
  w_table_.assign(n_nodes, w_basset_);
  dw_table_.assign(n_nodes, std::vector<double>(m, 0.0));
  for (int k = 0; k < off; ++k)
    for (std::size_t i = 0; i < m; ++i) {
      w_table_[k][i] = w_basset_[i] * (1 + Cm(i, 2 * k));
      dw_table_[k][i] = w_basset_[i] * Cm(i, 2 * k + 1);
    }
  ln_sc_.resize(n_nodes);
  for (int k = 0; k < n_nodes; ++k) ln_sc_[k] = tau0_ + k * dtau_;
}

void SoeKernel::weights(double Re, std::span<double> w, double& kappa) const {
  const std::size_t m = rate_.size();
  if (w.size() != m)
    throw std::invalid_argument("SoeKernel::weights: span size differs from the mode count");
  const double sc = kernel_.crossover_time(Re);
  const double u = ln_sc_.empty() || std::isinf(sc) ? inf : (std::log(sc) - tau0_) / dtau_;
  if (!(u < static_cast<double>(ln_sc_.size() - 1))) {
    std::copy(w_basset_.begin(), w_basset_.end(), w.begin());
    kappa = kappa_basset_;
    return;
  }
  const double uc = std::max(u, 0.0);
  const auto k = static_cast<std::size_t>(uc);
  const auto b = hermite(uc - static_cast<double>(k));
  const auto &w0 = w_table_[k], &w1 = w_table_[k + 1], &d0 = dw_table_[k], &d1 = dw_table_[k + 1];
  kappa = kernel_.integral(base_.min_lag, Re);
  for (std::size_t i = 0; i < m; ++i) {
    w[i] = b[0] * w0[i] + b[1] * dtau_ * d0[i] + b[2] * w1[i] + b[3] * dtau_ * d1[i];
    kappa -= w[i] * decay_[i];
  }
}

double SoeKernel::max_rel_error(double Re) const {
  std::vector<double> w(rate_.size());
  double kappa = 0;
  weights(Re, w, kappa);
  double err = 0;
  const double density = error_grid_density(base_.step > 0 ? base_.step : 1.0);
  for (double s : log_grid(base_.min_lag, base_.horizon, density))
    err = std::max(err, std::abs(soe_sum(rate_, w.data(), s) / kernel_.K(s, Re) - 1));
  return err;
}

// ---------- Exact solutions (Basset kernel) ----------

double basset_relaxation(double alpha, double gamma, double t) {
  check_basset_args(alpha, gamma, t);
  const auto [sp, sm] = basset_roots(alpha, gamma);
  return divided_difference(sp, sm, t, false).real();
}

double basset_settling(double alpha, double gamma, double t) {
  check_basset_args(alpha, gamma, t);
  // (σ−F+ − σ+F−)/(σ+ − σ−) = α·DD[F/σ] since σ+σ− = α.
  const auto [sp, sm] = basset_roots(alpha, gamma);
  return 1 / alpha + divided_difference(sp, sm, t, true).real();
}

}  // namespace imcol::contact
