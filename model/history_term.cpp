// SPDX-License-Identifier: BSD-3-Clause
#include "model/history_term.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "contact/formulas.hpp"
#include "core/errors.hpp"
#include "model/impact_speed.hpp"

namespace imcol::model {

using namespace contact;

HistoryTerm::HistoryTerm(const Scene& sc, const PairGeometry& p) : wall_(sc, p), n_spheres_(p.n_spheres) {
  const auto& h = sc.history;
  auto& o = opt_;
  o.kernel = h.kernel;
  o.evaluator = h.evaluator;
  o.tolerance = h.tolerance;
  o.modes = static_cast<int>(h.modes);
  o.impulsive = h.start == HistoryStart::impulsive;
  o.initial_re = h.reynolds == HistoryReynolds::initial;
  // Outputs inside a step are interpolated to the solver's own accuracy (rtol of the memory sum, and the memory's
  // velocity floor of CollisionModel::absolute_tolerances) or to the memory's own error in that step, if larger.
  o.interpolate_outputs = h.interpolate_outputs;
  o.output_rtol = sc.solver.rtol;
  o.output_atol = std::max(sc.solver.atol, sc.solver.rtol) * p.u_ref;
  kh_added_mass_ = h.wall_correction == WallCorrection::added_mass && p.has_target();
  const double t_fast = fastest_time(sc, p);
  o.horizon = h.horizon > 0 ? h.horizon : sc.solver.t_end;
  o.min_lag = h.min_lag > 0 ? h.min_lag : 1e-3 * t_fast;
  if (o.horizon < 10 * o.min_lag)
    throw InputError(sc.path, h.horizon > 0 ? "history.horizon" : "history.min_lag",
                     "the memory horizon " + fmt_number(o.horizon) + " s must be at least 10 × min_lag (" +
                         fmt_number(o.min_lag) + " s)");
  // Direct evaluator: 10 steps per fastest time scale, but at most 50000 steps up to t_end.
  o.direct_step = h.direct_step > 0 ? h.direct_step : std::max(0.1 * t_fast, sc.solver.t_end / 50000);
  make_spheres(sc, p);
  set_choices(h);
}

// The viscous and particle relaxation times of each sphere and, with a target, the time to cross the contact zone
// and the Hertz contact time at the larger of the initial speed and the impact speed's bound (a sphere released
// from rest meets its target at the speed gravity gave it).
double HistoryTerm::fastest_time(const Scene& sc, const PairGeometry& p) {
  double t_fast = std::numeric_limits<double>::infinity();
  const double nu = p.mu / p.rho_f;
  for (std::size_t m = 0; m < p.n_spheres; ++m) {
    t_fast = std::min(t_fast, p.a[m] * p.a[m] / nu);
    t_fast = std::min(t_fast, (p.mp[m] + 0.5 * p.mf[m]) / (6 * pi * p.mu * p.a[m]));
  }
  if (!p.has_target()) return t_fast;
  const double u_impact = std::max(p.u_rel0, impact_speed_bound(sc, p));
  t_fast = std::min(t_fast, p.delta_ss_m / std::max(p.u_ref, u_impact));
  if (sc.has(Effect::elastic) && u_impact > 0) {
    // t_c ∝ U^(-1/5) through U² in the indentation: a speed whose square underflows gives t_c = 0 (the reader's
    // bound |U| >= 1e-30 keeps it positive).
    const double t_c = hertz_contact_time(p.m_star, u_impact, p.E_star, p.a_star);
    if (!(t_c > 0))
      throw InputError(sc.path, "sphere[0].velocity",
                       "an approach speed of " + fmt_number(p.u_rel0) + " m/s is too small for the Hertz contact time to be computed (got " +
                           fmt_number(t_c) + " s)");
    t_fast = std::min(t_fast, t_c);
  }
  return t_fast;
}

void HistoryTerm::make_spheres(const Scene& sc, const PairGeometry& p) {
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    try {
      h_[m] = std::make_unique<SphereHistory>(opt_, p.a[m], p.mu, p.rho_f, sc.spheres[m].velocity);
    } catch (const std::invalid_argument& e) {
      throw InputError(sc.path, "history", e.what());
    }
    states_ += h_[m]->states();
  }
  if (n_spheres_ == 2) h_[1]->share_steps_with(h_[0].get());  // soe-step, equal exponentials
  place_states(2 * n_spheres_);
}

void HistoryTerm::place_states(std::size_t first) {
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    offset_[m] = first;
    first += h_[m]->states();
  }
}

void HistoryTerm::set_choices(const Scene::History& h) {
  auto& c = choices_;
  c.push_back({"history.kernel", to_string(h.kernel)});
  c.push_back({"history.evaluator", to_string(h.evaluator)});
  c.push_back({"history.start", to_string(h.start)});
  c.push_back({"history.wall_correction", to_string(h.wall_correction)});
  if (h.kernel != KernelKind::basset) c.push_back({"history.reynolds", to_string(h.reynolds)});
  if (opt_.evaluator == HistoryEvaluator::direct) {
    c.push_back({"history.direct_step_s", choice_number(opt_.direct_step)});
  } else {
    c.push_back({"history.modes", std::to_string(h_[0]->modes())});
    c.push_back({"history.min_lag_s", choice_number(opt_.min_lag)});
    c.push_back({"history.horizon_s", choice_number(opt_.horizon)});
    c.push_back({"history.fit_error_basset", choice_number(h_[0]->soe()->base().max_rel_error)});
  }
}

double HistoryTerm::K_H(double gap) const { return kh_added_mass_ ? 1 + 3 * wall_.W(gap) : 1.0; }

double HistoryTerm::step_cap() const {
  return opt_.evaluator == HistoryEvaluator::direct ? opt_.direct_step : std::numeric_limits<double>::infinity();
}

std::span<const double> HistoryTerm::memory(std::span<const double> y, std::size_t m) const {
  return y.subspan(offset_[m], h_[m]->states());
}

void HistoryTerm::add(const TermInput& in, Evaluation& ev) const {
  const double kh = K_H(ev.gap);
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    const auto term = h_[m]->evaluate(in.t, ev.u[m], kh, memory(in.y, m));
    ev.f[m].term[slot()] = term.force;
    ev.f[m].mass[slot()] = term.mass;
  }
}

void HistoryTerm::append_names(std::vector<std::string>& names) const {
  for (std::size_t m = 0; m < n_spheres_; ++m)
    for (std::size_t i = 0; i < h_[m]->states(); ++i) names.push_back("mem" + std::to_string(m + 1) + "_" + std::to_string(i));
}

void HistoryTerm::append_tolerances(double u_floor, std::vector<double>& t) const {
  for (std::size_t m = 0; m < n_spheres_; ++m)
    for (double v : h_[m]->absolute_tolerances(u_floor)) t.push_back(v);
}

void HistoryTerm::initial_states(std::span<double> y, const std::function<Evaluation()>& evaluate_start) const {
  for (std::size_t m = 0; m < n_spheres_; ++m) h_[m]->initial_states(y.subspan(offset_[m], h_[m]->states()));
  // soe-step: the memory lives in the term (reset here, so that a second call starts afresh).
  std::array<std::vector<double>, 2> zs;
  for (std::size_t m = 0; m < n_spheres_; ++m)
    if (h_[m]->stepwise()) {
      zs[m].assign(h_[m]->modes(), 0.0);
      h_[m]->initial_states(zs[m]);
      h_[m]->reset_memory(0.0, zs[m]);
    }
  if (!opt_.impulsive) return;
  // Impulsive start: the start-up momentum below the force floor is given at t = 0.
  const Evaluation ev = evaluate_start();
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    auto& h = *h_[m];
    const std::span<double> z = h.stepwise() ? std::span<double>(zs[m]) : y.subspan(offset_[m], h.states());
    y[2 * m + 1] -= h.apply_start(K_H(ev.gap), ev.m_eff[m], z);
    if (h.stepwise()) h.reset_memory(0.0, zs[m]);
  }
}

void HistoryTerm::state_rhs(const std::array<double, 2>& acc, std::span<const double> y, std::span<double> ydot) const {
  for (std::size_t m = 0; m < n_spheres_; ++m)
    if (h_[m]->states()) h_[m]->state_rhs(acc[m], memory(y, m), ydot.subspan(offset_[m], h_[m]->states()));
}

void HistoryTerm::residual(std::span<const double> y, std::span<const double> yp, std::span<double> r) const {
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    if (!h_[m]->states()) continue;
    const auto& lam = h_[m]->rates();
    const std::size_t o = offset_[m];
    for (std::size_t i = 0; i < lam.size(); ++i) r[o + i] = yp[o + i] - (yp[2 * m + 1] - lam[i] * y[o + i]);
  }
}

double HistoryTerm::next_breakpoint() const {
  if (opt_.evaluator != HistoryEvaluator::direct) return std::numeric_limits<double>::infinity();
  return h_[0]->step() * static_cast<double>(direct_points_);
}

void HistoryTerm::at_breakpoint(double t, const Evaluation& ev) {
  if (opt_.evaluator != HistoryEvaluator::direct) return;
  for (std::size_t m = 0; m < n_spheres_; ++m) h_[m]->record(t, ev.u[m]);
  ++direct_points_;
}

void HistoryTerm::at_step(double t, const Evaluation& ev, bool restart) {
  if (opt_.evaluator != HistoryEvaluator::soe_step) return;
  for (std::size_t m = 0; m < n_spheres_; ++m) h_[m]->advance_memory(t, ev.u[m], restart);
}

void HistoryTerm::step_accepted(double t, const Evaluation& ev) {
  if (opt_.evaluator != HistoryEvaluator::soe_step) return;
  for (std::size_t m = 0; m < n_spheres_; ++m) h_[m]->accept_step(t, ev.u[m]);
}

bool HistoryTerm::modal_structure(const Evaluation& ev, std::size_t core, ModalStructure& s) const {
  if (states_ == 0) return false;
  const double K_H = this->K_H(ev.gap);
  s = ModalStructure{};
  s.core = core;
  s.groups = n_spheres_;
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    const auto& h = *h_[m];
    std::vector<double> g(h.states());
    h.gains(ev.u[m], K_H, g);
    for (std::size_t i = 0; i < h.states(); ++i) {
      s.source.push_back(2 * m + 1);  // velocity of sphere m
      s.group.push_back(m);
      s.rate.push_back(h.rates()[i]);
      s.gain.push_back(g[i]);
    }
  }
  return true;
}

std::unique_ptr<ForceTerm> make_history_term(const Scene& sc, const PairGeometry& p) { return std::make_unique<HistoryTerm>(sc, p); }

}  // namespace imcol::model
