// SPDX-License-Identifier: BSD-3-Clause
#include "contact/formulas.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "contact/table_data.hpp"
#include "contact/tables.hpp"

namespace imcol::contact {

double reduced(double x1, double x2) {
  if (std::isinf(x2)) return x1;
  return 1.0 / (1.0 / x1 + 1.0 / x2);
}

double effective_modulus(double E1, double nu1, double E2, double nu2) {
  return 1.0 / ((1 - nu1 * nu1) / E1 + (1 - nu2 * nu2) / E2);
}

double hertz_force(double E_star, double a_star, double eps) {
  return eps <= 0 ? 0.0 : (4.0 / 3.0) * E_star * std::sqrt(a_star) * eps * std::sqrt(eps);
}

double hertz_max_indentation(double m_star, double U, double E_star, double a_star) {
  return std::pow(15.0 * m_star * U * U / (16.0 * E_star * std::sqrt(a_star)), 0.4);
}

double hertz_peak_force(double m_star, double U, double E_star, double a_star) {
  return hertz_force(E_star, a_star, hertz_max_indentation(m_star, U, E_star, a_star));
}

double hertz_contact_time(double m_star, double U, double E_star, double a_star) {
  return 2.943 * hertz_max_indentation(m_star, U, E_star, a_star) / U;
}

double ramp_F(double x, double beta) {
  if (x >= 1.0) return 0.0;
  const double denom = -std::expm1(-beta);  // 1 − e^{−β}
  if (x >= 0.0) return std::exp(-beta * x) * (-std::expm1(-beta * (1.0 - x))) / denom;
  // x < 0: continue with the value and slope at 0 (finite, growing, C¹).
  const double slope0 = -beta / denom;  // F'(0)
  return 1.0 + slope0 * x;
}

double ramp_F_integral(double beta) { return 1.0 / beta - std::exp(-beta) / -std::expm1(-beta); }  // 1/(e^β − 1) without overflow

double energy_consistent_beta(double delta_ss, double eps_max) {
  // Solve δ_SS (1/β − 1/(e^β − 1)) = (2/5) ε_max for β by Newton from the large-β estimate.
  const double target = 0.4 * eps_max / delta_ss;
  if (!(target > 0) || target >= 0.5)
    throw std::domain_error("energy_consistent_beta: the Hertz indentation exceeds what the ramp can store (eps_max >= 1.25 delta_ss)");
  double b = 1.0 / target;
  for (int it = 0; it < 100; ++it) {
    const double q = std::exp(-b), one_m_q = -std::expm1(-b);  // e^b/(e^b − 1)² = q/(1 − q)², no overflow
    const double f = ramp_F_integral(b) - target;
    const double df = -1.0 / (b * b) + q / (one_m_q * one_m_q);
    const double step = f / df;
    b = std::max(b - step, 0.5 * b);
    if (std::abs(step) < 1e-15 * b) break;
  }
  return b;
}

double blend_H(double x) {
  const double t = std::clamp(0.5 * x, 0.0, 1.0);
  return 1.0 - t * t * (3.0 - 2.0 * t);
}

double terminal_speed(double D, double rho_p, double rho_f, double mu, double g, const std::function<double(double)>& phi) {
  const double u_stokes = std::abs(rho_p - rho_f) * std::abs(g) * D * D / (18 * mu);  // φ = 1
  if (!(u_stokes > 0)) return 0;
  double lo = 1e-12 * u_stokes, hi = u_stokes;  // φ ≥ 1: the Stokes speed bounds it
  for (int k = 0; k < 200 && hi / lo > 1 + 1e-12; ++k) {
    const double mid = std::sqrt(lo * hi);
    (mid * phi(rho_f * mid * D / mu) < u_stokes ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

double drag_factor(DragLaw law, double Re) {
  if (law == DragLaw::stokes) return 1.0;
  return 1.0 + 0.15 * std::pow(std::abs(Re), 0.687);
}

// ----- Brenner series -----
double brenner_lambda_series(double h_over_a) {
  if (!(h_over_a > 0)) throw std::domain_error("brenner_lambda_series: h/a must be > 0");
  const double alpha = std::acosh(1.0 + h_over_a);
  const double s1 = std::sinh(alpha), s2 = std::sinh(2 * alpha);
  double sum = 0.0;
  for (long n = 1; n < 100000000; ++n) {
    const double k = 2.0 * n + 1.0;
    const double E = std::exp(-k * alpha);
    const double one_m_E = -std::expm1(-k * alpha);
    const double den = one_m_E * one_m_E - k * k * s1 * s1 * E;
    const double ratio_m1 = E * (2 * one_m_E + k * s2 + k * k * s1 * s1) / den;
    const double term = double(n) * (n + 1) / ((2.0 * n - 1) * (2.0 * n + 3)) * ratio_m1;
    sum += term;
    if (k * alpha > 2.0 && std::abs(term) < 1e-17 * std::abs(sum)) break;
  }
  return (4.0 / 3.0) * s1 * sum;
}

namespace {
double brenner_dlambda_fd(double x) {
  const double h = 1e-5 * x;
  return (brenner_lambda_series(x + h) - brenner_lambda_series(x - h)) / (2 * h);
}
using table_data::brenner_min, table_data::brenner_max, table_data::w_min, table_data::w_max;
// Shipped nodes (contact/table_data.cpp, written by imcol_gen_tables from the series below; a test
// recomputes them): building them at start-up took 50–90 ms.
const LogTable& brenner_table() {
  static const LogTable t(table_data::brenner_nodes, brenner_min, brenner_max, table_data::brenner_n);
  return t;
}
double brenner_asymptote(double d) { return 1.0 / d + 0.2 * std::log(1.0 / d); }

const LogTable& w_table() {
  static const LogTable t(table_data::w_nodes, w_min, w_max, table_data::w_n);
  return t;
}
}  // namespace

std::array<double, 2> table_node(TableKind kind, int i) {
  const bool w = kind == TableKind::added_mass_W;
  const double x = w ? LogTable::node_x(w_min, w_max, table_data::w_n, i)
                     : LogTable::node_x(brenner_min, brenner_max, table_data::brenner_n, i);
  if (w) return {added_mass_W_series(x), x * added_mass_dW_series(x)};
  return {brenner_lambda_series(x), x * brenner_dlambda_fd(x)};
}

double brenner_lambda(double h_over_a) {
  if (!(h_over_a > 0)) throw std::domain_error("brenner_lambda: h/a must be > 0");
  if (h_over_a > brenner_max) return brenner_lambda_series(h_over_a);
  const auto& t = brenner_table();
  if (h_over_a >= brenner_min) return t.value(h_over_a);
  static const double offset = t.value(brenner_min) - brenner_asymptote(brenner_min);
  return brenner_asymptote(h_over_a) + offset;
}

double lubrication_log_coefficient(double a1, double a2) {
  if (std::isinf(a2)) return a1 / 5.0;
  const double s = a1 + a2;
  return a1 * a2 * (a1 * a1 + 7 * a1 * a2 + a2 * a2) / (5 * s * s * s);
}

double asymptotic_resistance(double h, double a_star, double c_log, double h_c) {
  if (h >= h_c) return 0.0;
  return a_star * a_star * (1.0 / h - 1.0 / h_c) + c_log * std::log(h_c / h);
}

double regularised_gap(double h, double h_min) {
  const double r = std::sqrt(h * h + 4 * h_min * h_min);
  return h >= 0 ? 0.5 * (h + r) : 2 * h_min * h_min / (r - h);  // same value, no cancellation for h < 0
}

GapResistance gap_resistance(LubricationModel model, const GapGeometry& g, double h) {
  switch (model) {
    case LubricationModel::brenner: {
      const double R = g.a1 * (brenner_lambda(h / g.a1) - 1.0);
      return {R, R};
    }
    case LubricationModel::asymptotic: {
      const double R = asymptotic_resistance(h, g.a_star, g.c_log, g.h_c);
      return {R, R};
    }
    case LubricationModel::seed: {
      const double gap_part = brenner_lambda(h / g.a_star) - 1.0;  // λ(δ**) − 1
      return {g.a1 * gap_part, std::isinf(g.a2) ? g.a1 * gap_part : g.a2 * gap_part};
    }
  }
  return {};
}

// ----- Added mass image series -----
namespace {
/// coth x − 1/x, accurate for small x
double coth_minus_inv(double x) {
  if (x < 1e-3) return x / 3.0 - x * x * x / 45.0;
  return 1.0 / std::tanh(x) - 1.0 / x;
}
template <bool Derivative>
double w_series(double delta) {
  if (!(delta > 0)) throw std::domain_error("added-mass series: delta must be > 0");
  const double sa = std::sqrt(delta * (2.0 + delta));  // sinh α
  const double alpha = std::log1p(delta + sa);         // acosh(1 + δ)
  const double ca = coth_minus_inv(alpha);
  double sum = 0.0;
  for (long n = 2; n < 100000000; ++n) {
    const double na = n * alpha;
    if (na > 700) break;
    const double r = sa / std::sinh(na);
    double term = r * r * r;
    if constexpr (Derivative) term *= 3.0 * (ca - n * coth_minus_inv(na)) / sa;
    sum += term;
    if (na > 2.0 && std::abs(term) < 1e-17 * std::abs(sum)) break;
  }
  return sum;
}
}  // namespace

double added_mass_W_series(double delta) { return w_series<false>(delta); }
double added_mass_dW_series(double delta) { return w_series<true>(delta); }

double added_mass_W(double delta) {
  if (delta > w_max) return added_mass_W_series(delta);
  if (delta >= w_min) return w_table().value(delta);
  static const double w_at_min = w_table().value(w_min);
  const double s = std::max(delta, 0.0) / w_min;
  return zeta3_minus_1 + s * (w_at_min - zeta3_minus_1);
}

double added_mass_dW(double delta) {
  if (delta > w_max) return added_mass_dW_series(delta);
  if (delta >= w_min) return w_table().derivative(delta);
  static const double slope = (w_table().value(w_min) - zeta3_minus_1) / w_min;
  return slope;
}

}  // namespace imcol::contact
