// SPDX-License-Identifier: BSD-3-Clause
#include "study/dem_replay_fit.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "calibrate/local_search.hpp"

namespace imcol::study {

std::vector<double> replayed_restitution(const HookeContact& c, const ViscousRule& rule, const std::vector<double>& St, const ReplayStep& step) {
  std::vector<double> e;
  e.reserve(St.size());
  for (const double s : St) e.push_back(replay_viscous(c, rule, impact_speed_for_stokes(c, rule.fluid_viscosity, s), step).e);
  return e;
}

std::size_t min_replay_samples(bool e_max_free) { return e_max_free ? 3 : 2; }

namespace {

constexpr double kEmaxLow = 0.01;

/// The search's unit square mapped onto (St_c, e_max).
struct ReplayBox {
  double St_lo, St_hi;
  std::optional<double> e_max_fixed;
  ViscousRule rule(double mu, const std::vector<double>& u) const {
    ViscousRule r;
    r.fluid_viscosity = mu;
    r.critical_stokes = St_lo * std::pow(St_hi / St_lo, u[0]);
    r.maximum_restitution = e_max_fixed ? *e_max_fixed : kEmaxLow + (1 - kEmaxLow) * u[1];
    return r;
  }
};

double sum_of_squares(const std::vector<double>& model, const std::vector<ReplaySample>& s) {
  double ss = 0;
  for (std::size_t i = 0; i < s.size(); ++i) ss += (model[i] - s[i].e) * (model[i] - s[i].e);
  return ss;
}

/// The grid's best point, the start of the local search.
std::vector<double> grid_start(const std::function<double(const std::vector<double>&)>& f, std::size_t dims) {
  constexpr int kGrid = 11;
  std::vector<double> best(dims, 0.5), u(dims);
  double best_f = INFINITY;
  for (int a = 0; a < kGrid; ++a)
    for (int b = 0; b < (dims > 1 ? kGrid : 1); ++b) {
      u[0] = a / (kGrid - 1.0);
      if (dims > 1) u[1] = b / (kGrid - 1.0);
      if (const double v = f(u); v < best_f) best_f = v, best = u;
    }
  return best;
}

void check_samples(const std::vector<ReplaySample>& samples, bool e_max_free) {
  if (samples.size() < min_replay_samples(e_max_free))
    throw std::invalid_argument("a fit through the replay needs at least " + std::to_string(min_replay_samples(e_max_free)) +
                                " points with e > 0; there are " + std::to_string(samples.size()));
  for (const auto& s : samples)
    if (!(s.St > 0 && std::isfinite(s.St) && s.e > 0 && std::isfinite(s.e)))
      throw std::invalid_argument("a sample with St = " + std::to_string(s.St) + ", e = " + std::to_string(s.e) + ": both must be positive");
}

}  // namespace

ReplayFit fit_viscous_rule(const std::vector<ReplaySample>& samples, const HookeContact& c, double mu, std::optional<double> e_max_fixed,
                           const ReplayStep& step) {
  check_samples(samples, !e_max_fixed);
  std::vector<double> St;
  for (const auto& s : samples) St.push_back(s.St);
  const auto [lo, hi] = std::minmax_element(St.begin(), St.end());
  const ReplayBox box{1e-3 * *lo, 2 * *hi, e_max_fixed};
  ReplayFit fit;
  fit.e_max_free = !e_max_fixed;
  double best_f = INFINITY;
  std::vector<double> best_u;
  const auto f = [&](const std::vector<double>& u) {
    ++fit.evaluations;
    const double v = sum_of_squares(replayed_restitution(c, box.rule(mu, u), St, step), samples);
    if (v < best_f) best_f = v, best_u = u;
    return v;
  };
  const std::size_t dims = e_max_fixed ? 1 : 2;
  calib::local_search(grid_start(f, dims), 400, 1e-9, 0.05, f);
  fit.rule = box.rule(mu, best_u);
  fit.e_replay = replayed_restitution(c, fit.rule, St, step);
  double ss = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double r = fit.e_replay[i] - samples[i].e;
    ss += r * r;
    if (std::abs(r) > fit.max_residual) fit.max_residual = std::abs(r), fit.max_residual_St = samples[i].St;
  }
  fit.rms_residual = std::sqrt(ss / static_cast<double>(samples.size()));
  return fit;
}

}  // namespace imcol::study
