#include "model/collision_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.hpp"

namespace imcol::model {

using namespace contact;  // the formulas, laws and history kernels this model assembles

const char* to_string(Phase p) {
  switch (p) {
    case Phase::approach: return "approach";
    case Phase::loading: return "loading";
    case Phase::unloading: return "unloading";
    case Phase::separated: return "separated";
  }
  return "?";
}

namespace {
double sphere_volume(double a) { return 4.0 / 3.0 * pi * a * a * a; }
}  // namespace

CollisionModel::CollisionModel(const Scene& sc) : scene_(sc) {
  target_ = sc.two_spheres() ? Target::sphere : (sc.wall ? Target::wall : Target::none);
  n_spheres_ = sc.spheres.size();
  if (sc.fluid) {
    mu_ = sc.fluid->viscosity;
    rho_f_ = sc.fluid->density;
  }
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    a_[m] = 0.5 * sc.spheres[m].diameter;
    mp_[m] = sc.spheres[m].density * sphere_volume(a_[m]);
    mf_[m] = rho_f_ * sphere_volume(a_[m]);
  }
  D_ = 2 * a_[0];
  const auto& s1 = sc.spheres[0];
  const double inf = std::numeric_limits<double>::infinity();
  if (target_ == Target::sphere) {
    const auto& s2 = sc.spheres[1];
    a_star_ = reduced(a_[0], a_[1]);
    m_star_ = reduced(mp_[0], mp_[1]);
    E_star_ = effective_modulus(s1.youngs_modulus, s1.poisson_ratio, s2.youngs_modulus, s2.poisson_ratio);
    c_log_ = lubrication_log_coefficient(a_[0], a_[1]);
  } else {
    a_star_ = a_[0];
    m_star_ = mp_[0];
    if (sc.wall) E_star_ = effective_modulus(s1.youngs_modulus, s1.poisson_ratio, sc.wall->youngs_modulus, sc.wall->poisson_ratio);
    c_log_ = lubrication_log_coefficient(a_[0], inf);
  }
  // Dry restitution of the pair (choice): the scene's contact.e_dry, else the smaller of the two materials' values.
  if (sc.contact.e_dry >= 0) {
    e_dry_ = sc.contact.e_dry;
  } else {
    double e = 1.0;
    bool any = false;
    auto take = [&](const std::optional<double>& v) { if (v) { e = any ? std::min(e, *v) : *v; any = true; } };
    take(s1.e_dry);
    if (target_ == Target::sphere) take(sc.spheres[1].e_dry);
    if (sc.wall) take(sc.wall->e_dry);
    e_dry_ = e;
  }
  delta_ss_m_ = sc.contact.delta_ss * D_;
  coupled_ = has(Effect::flow);
  arm_gap_ = initial_gap();
  delta_sl_m_ = sc.contact.delta_sl * D_;
  // A start inside the contact zone (the reader admits it only while approaching): the zone is
  // shortened to the initial gap, so that the contact law stores no energy at t = 0 and the contact begins.
  const bool start_inside = has_target() && has(Effect::elastic) && initial_gap() <= delta_ss_m_;
  if (start_inside) delta_ss_m_ = initial_gap();
  h_min_ = sc.lubrication.cutoff * D_;
  h_c_ = sc.lubrication.h_c * a_star_;
  dw_floor_ = sc.added_mass.dw_floor > 0 ? sc.added_mass.dw_floor : sc.contact.delta_ss * D_ / a_star_;
  drag_law_ = sc.drag.law;
  lub_model_ = sc.lubrication.model;
  gap_geo_ = {a_[0], target_ == Target::sphere ? a_[1] : inf, a_star_, c_log_, h_c_};
  lagrangian_am_ = sc.added_mass.model == AddedMassModel::lagrangian;
  mf_star_ = target_ == Target::sphere ? reduced(mf_[0], mf_[1]) : mf_[0];

  u_ref_ = std::max({std::abs(s1.velocity), n_spheres_ > 1 ? std::abs(sc.spheres[1].velocity) : 0.0, 1e-3});
  u_rel0_ = has_target() ? s1.velocity - (n_spheres_ > 1 ? sc.spheres[1].velocity : 0.0) : 0.0;
  // The gap matters on the scale of the contact, not of the sphere: use the Hertz indentation at
  // the initial approach speed (or the lubrication cutoff if smaller), so that atol does not limit
  // the accuracy of e.
  gap_scale_ = D_;
  if (has_target()) {
    if (has(Effect::lubrication)) gap_scale_ = std::min(gap_scale_, h_min_);
    if (has(Effect::elastic) && u_rel0_ != 0)
      gap_scale_ = std::min(gap_scale_, hertz_max_indentation(m_star_, std::abs(u_rel0_), E_star_, a_star_));
  }
  // Cap the step so that the contact zone cannot be crossed (in and out) inside one step.
  max_step_ = sc.solver.max_step > 0 ? sc.solver.max_step
                                     : (has_target() ? 0.25 * delta_ss_m_ / u_ref_ : sc.solver.t_end / 100);
  // The step cap forces at least t_end / max_step steps if the run lasts to t_end (it usually stops
  // earlier): refuse a run that could cost far more than usual unless solver.step_budget allows it.
  if (has_target() && sc.solver.t_end / max_step_ > sc.solver.step_budget) {
    std::ostringstream os;
    os << "the step cap " << max_step_ << " s (" << (sc.solver.max_step > 0 ? "solver.max_step" : "a quarter of the time to cross the contact zone")
       << ") allows up to " << sc.solver.t_end / max_step_ << " steps to t_end = " << sc.solver.t_end
       << " s, beyond solver.step_budget = " << sc.solver.step_budget
       << ": lower solver.t_end, or raise solver.step_budget to run anyway";
    throw InputError(sc.path, "solver.t_end", os.str());
  }
  stop_time_ = sc.solver.t_end;
  // Build the lookup tables now, not inside the first right-hand side.
  if (has(Effect::added_mass) && has_target()) {
    w_floor_ = added_mass_W(dw_floor_);
    dw_slope_ = added_mass_dW(dw_floor_);
  }
  if (has(Effect::lubrication) && lub_model_ != LubricationModel::asymptotic) brenner_lambda(1.0);
  if (has(Effect::history)) setup_history();
  if (has(Effect::elastic))
    law_ = make_contact_law(sc.contact.law, {m_star_, E_star_, a_star_, e_dry_, delta_ss_m_, D_, sc.contact.delta_ss, sc.contact.beta, sc.path});
  if (start_inside) {
    // The contact begins at t = 0 with the law's state frozen at the initial speed.
    if (auto why = law_->start_inside_refusal(u_rel0_)) throw InputError(sc.path, "sphere[0].position", *why);
    std::vector<double> y0(size());
    initial_state(y0);
    freeze_contact(0.0, u_rel0_);
    phase_ = Phase::loading;
    record(0.0, EventKind::start_in_contact, "start inside the contact zone", y0);
  }
  arm();
}

double CollisionModel::initial_gap() const {
  const auto& s = scene_.spheres;
  if (target_ == Target::sphere) return s[1].position - s[0].position - a_[0] - a_[1];
  if (target_ == Target::wall) return scene_.wall->position - s[0].position - a_[0];
  return std::numeric_limits<double>::infinity();
}

void CollisionModel::setup_history() {
  const auto& h = scene_.history;
  auto& o = hist_opt_;
  o.kernel = h.kernel;
  o.evaluator = h.evaluator;
  o.tolerance = h.tolerance;
  o.modes = static_cast<int>(h.modes);
  o.impulsive = h.start == HistoryStart::impulsive;
  o.initial_re = h.reynolds == HistoryReynolds::initial;
  kh_added_mass_ = h.wall_correction == WallCorrection::added_mass && has_target();
  if (kh_added_mass_ && !(w_floor_ > 0)) {
    w_floor_ = added_mass_W(dw_floor_);
    dw_slope_ = added_mass_dW(dw_floor_);
  }
  // Fastest time scale the memory must resolve: the viscous and particle relaxation times of each
  // sphere and, with a target, the time to cross the contact zone and the Hertz contact time.
  double t_fast = std::numeric_limits<double>::infinity();
  const double nu = mu_ / rho_f_;
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    t_fast = std::min(t_fast, a_[m] * a_[m] / nu);
    t_fast = std::min(t_fast, (mp_[m] + 0.5 * mf_[m]) / (6 * pi * mu_ * a_[m]));
  }
  if (has_target()) t_fast = std::min(t_fast, delta_ss_m_ / u_ref_);
  if (has_target() && has(Effect::elastic) && u_rel0_ > 0) {
    // t_c ∝ U^(-1/5) through U² in the indentation: a speed whose square underflows gives t_c = 0 (the reader's
    // bound |U| >= 1e-30 keeps it positive).
    const double t_c = hertz_contact_time(m_star_, u_rel0_, E_star_, a_star_);
    if (!(t_c > 0))
      throw InputError(scene_.path, "sphere[0].velocity",
                       "an approach speed of " + fmt_number(u_rel0_) + " m/s is too small for the Hertz contact time to be computed (got " +
                           fmt_number(t_c) + " s)");
    t_fast = std::min(t_fast, t_c);
  }
  o.horizon = h.horizon > 0 ? h.horizon : scene_.solver.t_end;
  o.min_lag = h.min_lag > 0 ? h.min_lag : 1e-3 * t_fast;
  if (o.horizon < 10 * o.min_lag)
    throw InputError(scene_.path, h.horizon > 0 ? "history.horizon" : "history.min_lag",
                     "the memory horizon " + fmt_number(o.horizon) + " s must be at least 10 × min_lag (" +
                         fmt_number(o.min_lag) + " s)");
  // Direct evaluator: 10 steps per fastest time scale, but at most 50000 steps up to t_end.
  o.direct_step = h.direct_step > 0 ? h.direct_step : std::max(0.1 * t_fast, scene_.solver.t_end / 50000);
  std::size_t offset = core_size();
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    try {
      history_[m] = std::make_unique<SphereHistory>(o, a_[m], mu_, rho_f_, scene_.spheres[m].velocity);
    } catch (const std::invalid_argument& e) {
      throw InputError(scene_.path, "history", e.what());
    }
    hist_offset_[m] = offset;
    offset += history_[m]->states();
  }
  history_states_ = offset - core_size();
  if (n_spheres_ == 2) history_[1]->share_steps_with(history_[0].get());  // soe-step, equal exponentials
  if (o.evaluator == HistoryEvaluator::direct) max_step_ = std::min(max_step_, o.direct_step);
}

double CollisionModel::next_breakpoint(double) const {
  if (!history_[0] || hist_opt_.evaluator != HistoryEvaluator::direct) return std::numeric_limits<double>::infinity();
  return history_[0]->step() * static_cast<double>(direct_points_);
}

void CollisionModel::at_breakpoint(double t, std::span<const double> y) {
  if (!history_[0] || hist_opt_.evaluator != HistoryEvaluator::direct) return;
  Evaluation ev;
  kinematics(y, ev);
  for (std::size_t m = 0; m < n_spheres_; ++m) history_[m]->record(t, ev.u[m]);
  ++direct_points_;
}

std::span<const double> CollisionModel::history_z(std::span<const double> y, std::size_t m) const {
  return y.subspan(hist_offset_[m], history_[m]->states());
}

bool CollisionModel::modal_structure(double, std::span<const double> y, ModalStructure& s) const {
  if (!history_[0] || history_states_ == 0) return false;
  Evaluation ev;
  kinematics(y, ev);
  const double K_H = history_K_H(ev.gap);
  s = ModalStructure{};
  s.core = core_size();
  s.groups = n_spheres_;
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    const auto& h = *history_[m];
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

double CollisionModel::wall_function_W(double gap) const {
  const double d = gap / a_star_;
  if (d >= dw_floor_) return added_mass_W(d);
  return w_floor_ + dw_slope_ * (d - dw_floor_);
}

double CollisionModel::history_K_H(double gap) const {
  // K_H (choice, MODEL.md §2.3): `none` 1; `added-mass` 1 + 3W(δ**), the wall amplification of the added mass.
  return kh_added_mass_ ? 1 + 3 * wall_function_W(gap) : 1.0;
}

std::vector<std::string> CollisionModel::component_names() const {
  std::vector<std::string> names;
  if (target_ == Target::none) names = {"z1", "u1"};
  else if (target_ == Target::wall) names = {"gap", "u1"};
  else names = {"gap", "u1", "z2", "u2"};
  for (std::size_t m = 0; m < n_spheres_; ++m)
    if (history_[m])
      for (std::size_t i = 0; i < history_[m]->states(); ++i)
        names.push_back("mem" + std::to_string(m + 1) + "_" + std::to_string(i));
  return names;
}

std::vector<double> CollisionModel::absolute_tolerances(double atol) const {
  std::vector<double> t;
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    t.push_back(atol * (m == 0 && has_target() ? gap_scale_ : D_));
    t.push_back(atol * u_ref_);
  }
  for (std::size_t m = 0; m < n_spheres_; ++m)
    if (history_[m])
      // Memory states: a force error below rtol times the drag at u_ref is noise (MODEL.md §2.3).
      for (double v : history_[m]->absolute_tolerances(std::max(atol, scene_.solver.rtol) * u_ref_)) t.push_back(v);
  return t;
}

void CollisionModel::initial_state(std::span<double> y) const {
  const auto& s = scene_.spheres;
  y[1] = s[0].velocity;
  if (target_ == Target::none) y[0] = s[0].position;
  else if (target_ == Target::wall) y[0] = scene_.wall->position - s[0].position - a_[0];
  else {
    y[0] = s[1].position - s[0].position - a_[0] - a_[1];
    y[2] = s[1].position;
    y[3] = s[1].velocity;
  }
  for (std::size_t m = 0; m < n_spheres_; ++m)
    if (history_[m]) history_[m]->initial_states(y.subspan(hist_offset_[m], history_[m]->states()));
  // soe-step: the memory lives in the model (reset here, so that a second call starts afresh).
  std::array<std::vector<double>, 2> zs;
  for (std::size_t m = 0; m < n_spheres_; ++m)
    if (history_[m] && history_[m]->stepwise()) {
      zs[m].assign(history_[m]->modes(), 0.0);
      history_[m]->initial_states(zs[m]);
      history_[m]->reset_memory(0.0, zs[m]);
    }
  // Impulsive start: the start-up momentum below the force floor is given at t = 0.
  if (history_[0] && hist_opt_.impulsive) {
    const Evaluation ev = evaluate(0.0, y);
    for (std::size_t m = 0; m < n_spheres_; ++m) {
      auto& h = *history_[m];
      const std::span<double> z = h.stepwise() ? std::span<double>(zs[m]) : y.subspan(hist_offset_[m], h.states());
      y[2 * m + 1] -= h.apply_start(history_K_H(ev.gap), ev.m_eff[m], z);
      if (h.stepwise()) h.reset_memory(0.0, zs[m]);
    }
  }
}

void CollisionModel::at_step(double t, std::span<const double> y, bool restart) {
  if (!history_[0] || hist_opt_.evaluator != HistoryEvaluator::soe_step) return;
  const Evaluation ev = kinematic_state(y);
  for (std::size_t m = 0; m < n_spheres_; ++m) history_[m]->advance_memory(t, ev.u[m], restart);
}

void CollisionModel::kinematics(std::span<const double> y, Evaluation& ev) const {
  ev.u[0] = y[1];
  if (target_ == Target::none) {
    ev.z[0] = y[0];
    ev.gap = std::numeric_limits<double>::infinity();
    ev.u_rel = 0;
    return;
  }
  ev.gap = y[0];
  if (target_ == Target::wall) {
    ev.z[0] = scene_.wall->position - a_[0] - y[0];
    ev.u_rel = y[1];
  } else {
    ev.z[1] = y[2];
    ev.u[1] = y[3];
    ev.z[0] = y[2] - a_[0] - a_[1] - y[0];
    ev.u_rel = y[1] - y[3];
  }
}

double CollisionModel::max_step(double, std::span<const double> y) const {
  if (!has_target()) return max_step_;
  const Evaluation ev = kinematic_state(y);
  if (phase_ != Phase::loading && phase_ != Phase::unloading) {
    // Approaching: a quarter of the time to reach the contact zone at the current speed, never below max_step_
    // (unless the cap is the user's solver.max_step or the direct evaluator's grid step).
    const bool automatic = !(scene_.solver.max_step > 0) && hist_opt_.evaluator != HistoryEvaluator::direct;
    if (!automatic || !(ev.u_rel > 0)) return max_step_;
    return std::max(max_step_, 0.25 * (ev.gap - delta_ss_m_) / ev.u_rel);
  }
  return std::min(max_step_, law_->max_step(ev.gap, ev.u_rel));
}

double CollisionModel::contact_force(double gap, double u_rel) const {
  if (phase_ == Phase::approach || !law_) return 0.0;
  return law_->force(gap, u_rel);
}

void CollisionModel::forces(double t, std::span<const double> y, Evaluation& ev) const {
  const auto& sc = scene_;
  const bool pair = target_ == Target::sphere;
  const double six_pi_mu = 6 * pi * mu_;
  // Added-mass wall function at δ** = h/a*. dW/dδ diverges like ln δ at contact: below dw_floor, W is
  // continued linearly with the slope it has there. dW/dδ is then bounded and still the derivative of
  // the W used in the mass, so the added-mass forces stay conservative (½ m_a(δ) U² is conserved in
  // an ideal fluid; bounding dW/dδ alone would create energy on approach).
  double W = 0, dW = 0;
  const bool am = has(Effect::added_mass) && has_target();
  if (am) {
    const double d = ev.gap / a_star_;
    W = wall_function_W(ev.gap);
    dW = d >= dw_floor_ ? added_mass_dW(d) : dw_slope_;
  }
  ev.m_couple = 0;
  ev.H = coupled_ ? blend(ev.gap) : 1.0;
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    auto& f = ev.f[m];
    f = SphereForces{};
    if (has(Effect::drag)) {
      const double Re = rho_f_ * 2 * a_[m] * std::abs(ev.u[m]) / mu_;
      f.drag = -six_pi_mu * a_[m] * ev.u[m] * drag_factor(drag_law_, Re);
    }
    if (has(Effect::gravity)) f.gravity = (mp_[m] - mf_[m]) * sc.gravity;
    ev.m_eff[m] = mp_[m];
    if (has(Effect::added_mass)) {
      if (lagrangian_am_ && pair) {
        ev.m_eff[m] += 0.5 * mf_[m];  // free-space part; the gap part A is added below
      } else {
        ev.m_eff[m] += 0.5 * mf_[m] * (1 + 3 * W);
        if (am) f.added_mass = 0.75 * mf_[m] * ev.u[m] * (ev.u_rel / a_star_) * dW;  // velocity part (6.8)
      }
    }
    ev.m_hist[m] = 0;
    if (history_[m]) {
      const auto term = history_[m]->evaluate(t, ev.u[m], history_K_H(ev.gap), history_z(y, m));
      f.history = term.force;
      ev.m_hist[m] = term.mass;
      ev.m_eff[m] += term.mass;
    }
  }
  if (am && lagrangian_am_ && pair) {
    // T = Σ ½ M_m U_m² + ½ A U_rel²: mass matrix [[M1+A, −A], [−A, M2+A]], forces ±½ A' U_rel²/a*.
    const double A = 1.5 * mf_star_ * W, dA = 1.5 * mf_star_ * dW;
    ev.m_eff[0] += A;
    ev.m_eff[1] += A;
    ev.m_couple = -A;
    const double f = 0.5 * dA * ev.u_rel * ev.u_rel / a_star_;
    ev.f[0].added_mass = f;
    ev.f[1].added_mass = -f;
  }
  if (has(Effect::lubrication)) {
    // Per sphere: equal and opposite for brenner and asymptotic, in the ratio a2/a1 for the seed's law.
    const GapResistance R = gap_resistance(lub_model_, gap_geo_, regularised_gap(ev.gap, h_min_));
    ev.f[0].lubrication = -six_pi_mu * R.on1 * ev.u_rel;
    if (pair) ev.f[1].lubrication = six_pi_mu * R.on2 * ev.u_rel;
  }
  if (has(Effect::elastic)) {
    const double f = contact_force(ev.gap, ev.u_rel);
    ev.f[0].contact = -f;
    if (pair) ev.f[1].contact = f;
  }
  if (coupled_) blend_in_simulated(t, ev);
}

void CollisionModel::blend_in_simulated(double t, Evaluation& ev) const {
  // f_SL = H f_THR + (1 − H) f_SIM (6.10). The acceleration parts: f_SIM's added mass is removed from it
  // (f_rest = f_SIM + M_A a) and kept implicit, so the mass matrix carries M_A in full whatever H is; the
  // history force's κ-like mass is blended like its force.
  const double H = ev.H;
  const bool am_listed = has(Effect::added_mass);
  const AddedMassMatrix M = implicit_added_mass(ev.gap);
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    auto& f = ev.f[m];
    ev.thr_base[m] = f.drag + f.lubrication + f.added_mass + f.history;
    ev.m_hist_full[m] = ev.m_hist[m];
    f.drag *= H;
    f.lubrication *= H;
    f.added_mass *= H;  // velocity (dW/dδ) part
    f.history *= H;
    ev.m_eff[m] -= (1 - H) * ev.m_hist[m];
    ev.m_hist[m] *= H;
    ev.f_rest[m] = sim_.at(t, m);
    f.simulated = (1 - H) * ev.f_rest[m];
  }
  if (!am_listed) {
    // No analytic added mass: only the (1 − H) share standing for f_SIM's is implicit.
    ev.m_eff[0] += (1 - H) * M.m11;
    if (n_spheres_ == 2) ev.m_eff[1] += (1 - H) * M.m22;
    ev.m_couple += (1 - H) * M.m12;
  }
}

double CollisionModel::blend(double gap) const {
  if (!has_target()) return 0.0;
  const double x = std::clamp(0.5 * gap / delta_sl_m_, 0.0, 1.0);
  return 1.0 - x * x * (3 - 2 * x);
}

AddedMassMatrix CollisionModel::implicit_added_mass(double gap) const {
  if (coupled_ && !scene_.flow.added_mass_estimate) return {};  // f_SIM used explicitly (a demonstration setting)
  // The model's own added mass (MODEL.md §2.2): the seed's per-sphere ½ m_f (1 + 3W) or the lagrangian pair form.
  const bool pair = target_ == Target::sphere;
  const double W = has_target() ? wall_function_W(gap) : 0.0;
  AddedMassMatrix M;
  if (lagrangian_am_ && pair) {
    const double A = 1.5 * mf_star_ * W;
    M.m11 = 0.5 * mf_[0] + A;
    M.m22 = 0.5 * mf_[1] + A;
    M.m12 = -A;
  } else {
    M.m11 = 0.5 * mf_[0] * (1 + 3 * W);
    if (n_spheres_ == 2) M.m22 = 0.5 * mf_[1] * (1 + 3 * W);
  }
  return M;
}

double CollisionModel::analytic_fluid_force(const Evaluation& ev, const std::array<double, 2>& a, std::size_t m) const {
  const auto& f = ev.f[m];
  const double base = coupled_ ? ev.thr_base[m] : f.drag + f.lubrication + f.added_mass + f.history;
  const double m_hist = coupled_ ? ev.m_hist_full[m] : ev.m_hist[m];
  double am = 0;
  if (has(Effect::added_mass)) {
    const AddedMassMatrix M = implicit_added_mass(ev.gap);
    am = (m == 0 ? M.m11 : M.m22) * a[m] + (n_spheres_ == 2 ? M.m12 * a[1 - m] : 0.0);
  }
  return base - am - m_hist * a[m];
}

std::array<double, 2> CollisionModel::analytic_fluid_force(double t, std::span<const double> y, const std::array<double, 2>& a) const {
  Evaluation ev;
  kinematics(y, ev);
  forces(t, y, ev);
  return {analytic_fluid_force(ev, a, 0), n_spheres_ == 2 ? analytic_fluid_force(ev, a, 1) : 0.0};
}

std::array<double, 2> CollisionModel::accelerations_without_contact(double t, std::span<const double> y) const {
  Evaluation ev;
  kinematics(y, ev);
  forces(t, y, ev);
  auto g = total_forces(ev);
  for (std::size_t m = 0; m < n_spheres_; ++m) g[m] -= ev.f[m].contact;
  return ev.accelerations(g, n_spheres_);
}

void CollisionModel::sphere_states(std::span<const double> y, std::array<double, 2>& z, std::array<double, 2>& u) const {
  Evaluation ev;
  kinematics(y, ev);
  z = ev.z;
  u = ev.u;
}

std::array<double, 2> Evaluation::accelerations(const std::array<double, 2>& g, std::size_t n) const {
  if (n == 1) return {g[0] / m_eff[0], 0.0};
  const double det = m_eff[0] * m_eff[1] - m_couple * m_couple;
  return {(m_eff[1] * g[0] - m_couple * g[1]) / det, (m_eff[0] * g[1] - m_couple * g[0]) / det};
}

std::array<double, 2> CollisionModel::total_forces(const Evaluation& ev) const {
  std::array<double, 2> g{};
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    const auto& f = ev.f[m];
    g[m] = f.drag + f.lubrication + f.added_mass + f.contact + f.gravity + f.history + f.simulated;
  }
  return g;
}

Evaluation CollisionModel::evaluate(double t, std::span<const double> y) const {
  Evaluation ev;
  kinematics(y, ev);
  forces(t, y, ev);
  const auto acc = ev.accelerations(total_forces(ev), n_spheres_);
  for (std::size_t m = 0; m < n_spheres_; ++m) ev.f[m].accel = acc[m];
  // Report the full added-mass and history forces, including their acceleration parts (the mass matrix beyond m_p).
  const bool pair = n_spheres_ == 2;
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    const double other = pair ? ev.m_couple * acc[1 - m] : 0.0;
    double am_accel = (ev.m_eff[m] - mp_[m] - ev.m_hist[m]) * acc[m] + other;  // the implicit added-mass force
    if (coupled_) {
      // Split the implicit added mass: its H share is f_THR's, the rest stands for f_SIM's (MODEL.md §5).
      const AddedMassMatrix M = implicit_added_mass(ev.gap);
      const double MA_a = (m == 0 ? M.m11 : M.m22) * acc[m] + (pair ? M.m12 * acc[1 - m] : 0.0);
      const double H = ev.H;
      ev.f[m].f_sim = ev.f_rest[m] - MA_a;
      ev.f[m].simulated -= (1 - H) * MA_a;
      am_accel -= (1 - H) * MA_a;
      ev.f[m].f_thr = analytic_fluid_force(ev, acc, m);
    }
    ev.f[m].added_mass -= am_accel;
    ev.f[m].history -= ev.m_hist[m] * acc[m];
  }
  return ev;
}

void CollisionModel::rhs(double t, std::span<const double> y, std::span<double> ydot) {
  Evaluation ev;
  kinematics(y, ev);
  forces(t, y, ev);
  const auto acc = ev.accelerations(total_forces(ev), n_spheres_);
  ydot[0] = target_ == Target::none ? ev.u[0] : -ev.u_rel;
  ydot[1] = acc[0];
  if (target_ == Target::sphere) {
    ydot[2] = ev.u[1];
    ydot[3] = acc[1];
  }
  for (std::size_t m = 0; m < n_spheres_; ++m)
    if (history_[m] && history_[m]->states())
      history_[m]->state_rhs(acc[m], history_z(y, m), ydot.subspan(hist_offset_[m], history_[m]->states()));
}

void CollisionModel::residual(double t, std::span<const double> y, std::span<const double> yp, std::span<double> r) {
  Evaluation ev;
  kinematics(y, ev);
  forces(t, y, ev);
  const auto g = total_forces(ev);
  r[0] = yp[0] - (target_ == Target::none ? ev.u[0] : -ev.u_rel);
  if (target_ != Target::sphere) {
    r[1] = ev.m_eff[0] * yp[1] - g[0];
  } else {
    r[1] = ev.m_eff[0] * yp[1] + ev.m_couple * yp[3] - g[0];
    r[2] = yp[2] - ev.u[1];
    r[3] = ev.m_couple * yp[1] + ev.m_eff[1] * yp[3] - g[1];
  }
  // Memory states: z_i' − (U' − λ_i z_i) = 0.
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    if (!history_[m] || !history_[m]->states()) continue;
    const auto& lam = history_[m]->rates();
    const std::size_t o = hist_offset_[m];
    for (std::size_t i = 0; i < lam.size(); ++i) r[o + i] = yp[o + i] - (yp[2 * m + 1] - lam[i] * y[o + i]);
  }
}

// ---------- Events (MODEL.md §3) ----------
void CollisionModel::watch(EventWatcher& w) {
  watchers_.push_back(&w);
  arm();
}

void CollisionModel::arm() {
  armed_.clear();
  armed_kind_.clear();
  armed_watched_.clear();
  if (!has_target()) return;
  auto add = [&](RootKind k, const char* name, int dir) {
    armed_.push_back({name, dir});
    armed_kind_.push_back(k);
    armed_watched_.emplace_back();
  };
  const bool elastic = has(Effect::elastic);
  switch (phase_) {
    case Phase::approach:
    case Phase::separated:
      if (elastic) add(RootKind::contact_in, "gap=delta_ss (in)", -1);
      break;
    case Phase::loading:
      add(RootKind::unload, "u_rel=0 (loading->unloading)", -1);
      add(RootKind::touch, "gap=0", -1);
      add(RootKind::contact_out, "gap=delta_ss (out)", +1);
      break;
    case Phase::unloading:
      add(RootKind::contact_out, "gap=delta_ss (out)", +1);
      break;
  }
  // The watchers' roots (measurements and stop rules), in their order.
  std::vector<WatchedRoot> watched;
  for (const EventWatcher* w : watchers_) w->roots(watched);
  for (auto& r : watched) {
    armed_.push_back({r.name, r.direction});
    armed_kind_.push_back(r.kind);
    armed_watched_.push_back(std::move(r));
  }
  if (has(Effect::lubrication) && lub_model_ == LubricationModel::asymptotic) add(RootKind::lub_edge, "gap=h_c (lubrication edge)", 0);
  if (coupled_) {
    // The ends of the blend H (MODEL.md §2.5): diagnostic, the right-hand side stays continuous there. Not armed
    // while the gap sits on one of them (a start at 2δ_SL: CVODE refuses a root at the initial time).
    const double tiny = 1e-9 * D_;
    if (std::abs(arm_gap_ - 2 * delta_sl_m_) > tiny) add(RootKind::blend_edge, "gap=2*delta_sl (blend edge)", 0);
    if (phase_ != Phase::loading && std::abs(arm_gap_) > tiny) add(RootKind::blend_end, "gap=0 (blend end)", 0);
  }
}

void CollisionModel::root_values(double, std::span<const double> y, std::span<double> g) {
  Evaluation ev;
  kinematics(y, ev);
  const double gap = ev.gap, u_rel = ev.u_rel;
  for (std::size_t i = 0; i < armed_kind_.size(); ++i) {
    if (const auto& w = armed_watched_[i]) {
      g[i] = (w->of == WatchedRoot::Of::gap ? gap : u_rel) - w->level;
      continue;
    }
    switch (armed_kind_[i]) {
      case RootKind::contact_in:
      case RootKind::contact_out: g[i] = gap - delta_ss_m_; break;
      case RootKind::touch:
      case RootKind::blend_end: g[i] = gap; break;
      case RootKind::blend_edge: g[i] = gap - 2 * delta_sl_m_; break;
      case RootKind::unload: g[i] = u_rel; break;
      case RootKind::lub_edge: g[i] = regularised_gap(gap, h_min_) - h_c_; break;
      default: g[i] = 1; break;  // the watchers' kinds (above) and declared states: never the model's own roots
    }
  }
}

void CollisionModel::record(double t, EventKind kind, const std::string& name, std::span<const double> y) {
  Evaluation ev;
  kinematics(y, ev);
  arm_gap_ = ev.gap;
  events_.push_back({t, name, ev.gap, ev.u_rel, kind});
}

void CollisionModel::freeze_contact(double t, double u_rel) {
  law_->begin_contact(t, u_rel);  // the law freezes its state at the relative speed U_c of the δ_SS crossing
  if (contacts_ == 0) {
    U_c_ = u_rel;
    t_contact_ = t;
  }
  ++contacts_;
}

void CollisionModel::handle(RootKind kind, const std::string& name, double t, std::span<const double> y) {
  record(t, kind, name, y);
  Evaluation ev;
  kinematics(y, ev);
  switch (kind) {
    case RootKind::contact_in:
      freeze_contact(t, ev.u_rel);
      phase_ = Phase::loading;
      break;
    case RootKind::unload:
      law_->unload();
      phase_ = Phase::unloading;
      break;
    case RootKind::contact_out:
      law_->end_contact();
      phase_ = Phase::separated;
      if (!t_separation_) t_separation_ = t;
      break;
    default:  // diagnostic (touch, lubrication and blend edges) or a watcher's
      break;
  }
  tell_watchers(t, ev);
}

void CollisionModel::tell_watchers(double t, const Evaluation& ev) {
  const EventRecord e = events_.back();
  for (EventWatcher* w : watchers_) declare(t, ev, w->on_event(e));
}

void CollisionModel::declare(double t, const Evaluation& ev, const std::optional<Declared>& d) {
  if (d) events_.push_back({t, d->name, ev.gap, ev.u_rel, d->kind});
  stop_time_ = scene_.solver.t_end;
  for (const EventWatcher* w : watchers_) stop_time_ = std::min(stop_time_, w->stop_time());
}

bool CollisionModel::observes_accelerations() const {
  return std::any_of(watchers_.begin(), watchers_.end(), [](const EventWatcher* w) { return w->wants_forces(); });
}

Evaluation CollisionModel::kinematic_state(std::span<const double> y) const {
  Evaluation ev;
  kinematics(y, ev);
  return ev;
}

void CollisionModel::observe(double t, const Evaluation& ev) {
  for (EventWatcher* w : watchers_) declare(t, ev, w->on_sample(t, ev));
}

EventAction CollisionModel::on_roots(std::span<const std::size_t> found, double t, std::span<double> y) {
  // Handle in a fixed order so that coincident roots (e.g. instant_gap == delta_ss) are deterministic.
  const auto kinds = armed_kind_;
  const auto specs = armed_;
  const auto watched = armed_watched_;
  bool changed = false;
  for (std::size_t i : found) {
    handle(kinds.at(i), specs.at(i).name, t, y);
    const bool diagnostic = watched[i] ? !watched[i]->restarts
                                       : kinds[i] == RootKind::touch || kinds[i] == RootKind::blend_edge || kinds[i] == RootKind::blend_end;
    changed = changed || !diagnostic;
  }
  if (t >= stop_time_) return EventAction::stop;
  if (!changed) return EventAction::proceed;
  // The force law or the armed roots changed: restart the integrator here.
  arm();
  return EventAction::reinit;
}

std::vector<std::pair<std::string, std::string>> CollisionModel::choices() const {
  std::vector<std::pair<std::string, std::string>> c;
  auto num = [](double v) {
    std::ostringstream os;
    os.precision(6);
    os << v;
    return os.str();
  };
  const auto& sc = scene_;
  if (has(Effect::drag)) c.push_back({"drag.law", to_string(sc.drag.law)});
  if (has(Effect::lubrication)) {
    c.push_back({"lubrication.model", to_string(sc.lubrication.model)});
    c.push_back({"lubrication.law", lub_model_ == LubricationModel::asymptotic
                                        ? "two-sphere asymptote, exact as h -> 0: 6 pi mu [a*^2/h + c_log ln(a*/h)] U_rel (Jeffrey & Onishi), shifted to vanish at h_c"
                                        : lub_model_ == LubricationModel::brenner
                                              ? "exact sphere-wall series: 6 pi mu a (lambda(h/a) - 1) U (Brenner 1961)"
                                              : "the seed's gap law as read from its 6.2.1: 6 pi mu a_m (lambda(h/a*) - 1) U_rel on sphere m (Brenner's wall series at h/a*)"});
    c.push_back({"lubrication.cutoff_m", num(h_min_)});
    if (lub_model_ == LubricationModel::asymptotic) c.push_back({"lubrication.h_c_m", num(h_c_)});
    if (lub_model_ == LubricationModel::seed && target_ == Target::sphere)
      c.push_back({"lubrication.pair_forces", a_[0] == a_[1] ? std::string("equal and opposite (equal radii)")
                                                             : "differ: |f_lub2/f_lub1| = a2/a1 = " + num(a_[1] / a_[0]) +
                                                                   " (the seed's law does not conserve the pair's momentum)"});
  }
  if (has(Effect::added_mass)) {
    c.push_back({"added_mass.model", to_string(sc.added_mass.model)});
    c.push_back({"added_mass.dw_floor", num(dw_floor_)});
  }
  if (law_) {
    c.push_back({"contact.law", to_string(law_->kind())});
    for (auto& kv : law_->choices()) c.push_back(std::move(kv));
  }
  if (has(Effect::elastic)) {
    c.push_back({"contact.e_dry", num(e_dry_)});
    c.push_back({"contact.delta_ss_m", num(delta_ss_m_)});
  }
  if (history_[0]) {
    const auto& h = sc.history;
    c.push_back({"history.kernel", to_string(h.kernel)});
    c.push_back({"history.evaluator", to_string(h.evaluator)});
    c.push_back({"history.start", to_string(h.start)});
    c.push_back({"history.wall_correction", to_string(h.wall_correction)});
    if (h.kernel != KernelKind::basset) c.push_back({"history.reynolds", to_string(h.reynolds)});
    if (hist_opt_.evaluator == HistoryEvaluator::direct) {
      c.push_back({"history.direct_step_s", num(hist_opt_.direct_step)});
    } else {
      c.push_back({"history.modes", std::to_string(history_[0]->modes())});
      c.push_back({"history.min_lag_s", num(hist_opt_.min_lag)});
      c.push_back({"history.horizon_s", num(hist_opt_.horizon)});
      c.push_back({"history.fit_error_basset", num(history_[0]->soe()->base().max_rel_error)});
    }
  }
  if (coupled_) {
    c.push_back({"blend.H", "smoothstep: H = 1 - (3t^2 - 2t^3), t = gap/(2 delta_sl) in [0, 1]"});
    c.push_back({"blend.delta_sl_m", num(delta_sl_m_)});
    c.push_back({"blend.added_mass_estimate", lagrangian_am_ && target_ == Target::sphere ? "lagrangian pair matrix, implicit" : "1/2 m_f (1 + 3W), implicit"});
  } else {
    c.push_back({"blend.H", "1 (reduced-order: no f_SIM)"});
  }
  return c;
}

}  // namespace imcol::model
