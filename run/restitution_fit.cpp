// SPDX-License-Identifier: BSD-3-Clause
#include "run/restitution_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/NonLinearOptimization>

namespace imcol::run {

const char* to_string(RestitutionForm f) { return f == RestitutionForm::exponential ? "exp" : "linear"; }

const char* formula(RestitutionForm f) {
  return f == RestitutionForm::exponential ? "e = e_dry exp(-St_c/St)" : "e = e_dry max(0, 1 - St_c/St)";
}

double restitution_model(RestitutionForm form, double St_c, double e_dry, double St) {
  if (!(St > 0)) return 0;
  if (form == RestitutionForm::exponential) return e_dry * std::exp(-St_c / St);
  return e_dry * std::max(0.0, 1 - St_c / St);
}

std::size_t min_restitution_samples(bool e_dry_free) { return e_dry_free ? 3 : 2; }

namespace {

/// The residuals r_i = e_dry f(St_c/St_i) − e_i and their Jacobian, in Eigen's MINPACK functor shape.
/// Parameters: (St_c, e_dry) with e_dry free, (St_c) with it fixed.
struct Residuals {
  using Scalar = double;
  enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };
  using InputType = Eigen::VectorXd;
  using ValueType = Eigen::VectorXd;
  using JacobianType = Eigen::MatrixXd;

  RestitutionForm form;
  std::optional<double> e_dry_fixed;
  const std::vector<double>& St;
  const std::vector<double>& e;

  int inputs() const { return e_dry_fixed ? 1 : 2; }
  int values() const { return static_cast<int>(St.size()); }
  double e_dry(const Eigen::VectorXd& x) const { return e_dry_fixed ? *e_dry_fixed : x(1); }

  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& r) const {
    for (int i = 0; i < values(); ++i) r(i) = restitution_model(form, x(0), e_dry(x), St[i]) - e[i];
    return 0;
  }
  int df(const Eigen::VectorXd& x, Eigen::MatrixXd& J) const {
    const double ed = e_dry(x);
    for (int i = 0; i < values(); ++i) {
      double d_stc = 0, d_edry = 0;
      if (form == RestitutionForm::exponential) {
        d_edry = std::exp(-x(0) / St[i]);
        d_stc = -ed * d_edry / St[i];
      } else if (const double g = 1 - x(0) / St[i]; g > 0) {  // beyond the kink at St = St_c the model is 0
        d_edry = g;
        d_stc = -ed / St[i];
      }
      J(i, 0) = d_stc;
      if (!e_dry_fixed) J(i, 1) = d_edry;
    }
    return 0;
  }
};

/// The start: the form made linear in x = 1/St (ln e = ln e_dry − St_c x, or e = e_dry − e_dry St_c x), least squares.
Eigen::VectorXd linearised_fit(RestitutionForm form, std::optional<double> e_dry, const std::vector<double>& St,
                               const std::vector<double>& e) {
  const bool expo = form == RestitutionForm::exponential;
  const int n = static_cast<int>(St.size());
  Eigen::VectorXd x(n), y(n);
  for (int i = 0; i < n; ++i) {
    x(i) = 1 / St[i];
    y(i) = expo ? std::log(e[i]) : e[i];
  }
  if (e_dry) {  // y = c − k x with c known: one parameter through the origin of (x, c − y)
    const double c = expo ? std::log(*e_dry) : *e_dry;
    const double k = x.dot((Eigen::VectorXd::Constant(n, c) - y)) / x.squaredNorm();
    Eigen::VectorXd p(1);
    p << (expo ? k : k / *e_dry);
    return p;
  }
  Eigen::MatrixXd A(n, 2);
  A.col(0).setOnes();
  A.col(1) = x;
  const Eigen::Vector2d ab = A.colPivHouseholderQr().solve(y);  // y = a + b x
  const double ed = expo ? std::exp(ab(0)) : ab(0);
  Eigen::VectorXd p(2);
  p << (expo ? -ab(1) : -ab(1) / ab(0)), ed;
  return p;
}

}  // namespace

RestitutionFit fit_restitution(const std::vector<RestitutionSample>& samples, RestitutionForm form, std::optional<double> e_dry) {
  RestitutionFit fit;
  fit.form = form;
  fit.e_dry_free = !e_dry;
  if (e_dry && !(*e_dry > 0 && *e_dry <= 1)) throw std::invalid_argument("e_dry = " + std::to_string(*e_dry) + " is not in (0, 1]");
  std::vector<double> St, e;
  for (const auto& s : samples) {
    if (!s.e) {
      ++fit.without_e;
      continue;
    }
    if (!(std::isfinite(s.St) && s.St > 0) || !std::isfinite(*s.e) || *s.e < 0)
      throw std::invalid_argument("a sample with St = " + std::to_string(s.St) + ", e = " + std::to_string(*s.e) +
                                  ": St must be positive and e a number >= 0");
    if (*s.e == 0) {
      ++fit.no_rebound;
      fit.St_no_rebound_max = std::max(fit.St_no_rebound_max.value_or(0.0), s.St);
      continue;
    }
    St.push_back(s.St);
    e.push_back(*s.e);
  }
  fit.used = St.size();
  if (fit.used < min_restitution_samples(fit.e_dry_free))
    throw std::invalid_argument(std::string("a fit of ") + formula(form) + (e_dry ? " (e_dry fixed)" : " with e_dry free") + " needs at least " +
                                std::to_string(min_restitution_samples(fit.e_dry_free)) + " points with e > 0; there are " +
                                std::to_string(fit.used) + " (" + std::to_string(fit.no_rebound) + " with e = 0, " +
                                std::to_string(fit.without_e) + " failed or without e)");
  fit.St_min = *std::min_element(St.begin(), St.end());
  fit.St_max = *std::max_element(St.begin(), St.end());

  Residuals f{form, e_dry, St, e};
  Eigen::VectorXd x = linearised_fit(form, e_dry, St, e);
  Eigen::LevenbergMarquardt<Residuals, double> lm(f);
  lm.parameters.ftol = lm.parameters.xtol = 1e-12;
  lm.parameters.maxfev = 2000;
  lm.minimize(x);
  fit.iterations = static_cast<int>(lm.iter);
  if (!x.allFinite()) throw std::runtime_error(std::string("the fit of ") + formula(form) + " did not converge");
  fit.St_c = x(0);
  fit.e_dry = e_dry ? *e_dry : x(1);

  Eigen::VectorXd r(fit.used);
  f(x, r);
  fit.rms_residual = std::sqrt(r.squaredNorm() / static_cast<double>(fit.used));
  fit.max_residual = r.cwiseAbs().maxCoeff();
  // Standard errors: s² (JᵀJ)⁻¹ with s² the residual variance (n − p degrees of freedom).
  Eigen::MatrixXd J(fit.used, f.inputs());
  f.df(x, J);
  const double s2 = r.squaredNorm() / static_cast<double>(static_cast<int>(fit.used) - f.inputs());
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  if (std::abs(JtJ.determinant()) > 0) {
    const Eigen::MatrixXd cov = s2 * JtJ.inverse();
    fit.St_c_std_error = std::sqrt(cov(0, 0));
    if (!e_dry) fit.e_dry_std_error = std::sqrt(cov(1, 1));
  }
  return fit;
}

}  // namespace imcol::run
