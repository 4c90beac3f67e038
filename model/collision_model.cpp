// SPDX-License-Identifier: BSD-3-Clause
#include "model/collision_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.hpp"
#include "model/contact_term.hpp"
#include "model/force_terms.hpp"
#include "model/force_work.hpp"
#include "model/gap_resistance_term.hpp"

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

CollisionModel::CollisionModel(const Scene& sc) : scene_(sc), pair_(sc), added_mass_(sc, pair_) {
  target_ = pair_.target;
  n_spheres_ = pair_.n_spheres;
  a_ = pair_.a;
  D_ = pair_.D;
  delta_ss_m_ = pair_.delta_ss_m;
  u_ref_ = pair_.u_ref;
  u_rel0_ = pair_.u_rel0;
  coupled_ = has(Effect::flow);
  arm_gap_ = initial_gap();
  delta_sl_m_ = sc.contact.delta_sl * D_;
  const bool start_inside = pair_.start_inside;
  set_step_cap(sc);
  stop_time_ = sc.solver.t_end;
  build_terms(sc);
  if (coupled_) flow_.emplace(sc, pair_, terms_);
  if (start_inside) {
    // The contact begins at t = 0 with the law's state frozen at the initial speed.
    if (auto why = law_->start_inside_refusal(u_rel0_)) throw InputError(sc.path, "sphere[0].position", *why);
    std::vector<double> y0(size());
    initial_state(y0);
    freeze_contact(0.0, u_rel0_);
    phase_ = Phase::loading;
    record(0.0, tag(ModelRoot::start_in_contact), "start inside the contact zone", y0);
  }
  arm();
}

void CollisionModel::set_step_cap(const Scene& sc) {
  // Cap the step so that the contact zone cannot be crossed (in and out) inside one step.
  // With the roughness limit the zone (the roughness height) is far thinner than the Hertz indentation the contact
  // reaches: that indentation is the contact's length scale then.
  double zone = delta_ss_m_;
  if (has_target() && sc.lubrication.limit == LubricationLimit::roughness)
    zone = std::max(zone, hertz_max_indentation(pair_.m_star, u_ref_, pair_.E_star, pair_.a_star));
  max_step_ = sc.solver.max_step > 0 ? sc.solver.max_step : (has_target() ? 0.25 * zone / u_ref_ : sc.solver.t_end / 100);
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
}

void CollisionModel::build_terms(const Scene& sc) {
  terms_ = make_force_terms(sc, pair_);
  slots_ = model::kind_slots(terms_);
  fluid_ = FluidSlots(terms_);
  for (const auto& t : terms_) {
    const TermMass mass = t->properties().mass;
    if (mass == TermMass::implicit) implicit_slot_ = t->slot();
    if (mass != TermMass::none) mass_slots_.push_back(t->slot());
  }
  history_ = find_term<HistoryTerm>(terms_);
  for (const auto& t : terms_) {
    if (t->states() > 0) stateful_.push_back(t.get());
    states_ += t->states();
    term_step_cap_ = std::min(term_step_cap_, t->step_cap());
  }
  max_step_ = std::min(max_step_, term_step_cap_);
  if (auto* contact = find_term<ContactTerm>(terms_)) law_ = &contact->law();
  if (auto* gap = find_term<GapResistanceTerm>(terms_)) {
    lub_model_ = gap->model();
    h_min_ = gap->cutoff_m();
    h_c_ = gap->h_c_m();
  }
}

double CollisionModel::initial_gap() const {
  const auto& s = scene_.spheres;
  if (target_ == Target::sphere) return s[1].position - s[0].position - a_[0] - a_[1];
  if (target_ == Target::wall) return scene_.wall->position - s[0].position - a_[0];
  return std::numeric_limits<double>::infinity();
}

const HistoryOptions& CollisionModel::history_options() const {
  static const HistoryOptions none;
  return history_ ? history_->options() : none;
}

double CollisionModel::next_breakpoint(double) const {
  double t = std::numeric_limits<double>::infinity();
  for (const auto& term : terms_) t = std::min(t, term->next_breakpoint());
  return t;
}

void CollisionModel::at_breakpoint(double t, std::span<const double> y) {
  const Evaluation ev = kinematic_state(y);
  for (const auto& term : terms_) term->at_breakpoint(t, ev);
}

bool CollisionModel::modal_structure(double, std::span<const double> y, ModalStructure& s) const {
  // The structure of the first term with states (one term has them today: the history force's memory).
  for (const auto& term : terms_)
    if (term->states() > 0) return term->modal_structure(kinematic_state(y), core_size(), s);
  return false;
}

std::vector<std::string> CollisionModel::component_names() const {
  std::vector<std::string> names;
  if (target_ == Target::none) names = {"z1", "u1"};
  else if (target_ == Target::wall) names = {"gap", "u1"};
  else names = {"gap", "u1", "z2", "u2"};
  for (const auto& term : terms_) term->append_names(names);
  return names;
}

std::vector<double> CollisionModel::absolute_tolerances(double atol) const {
  std::vector<double> t;
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    t.push_back(atol * (m == 0 && has_target() ? pair_.gap_scale : D_));
    t.push_back(atol * u_ref_);
  }
  // The terms' states (the history memory): a force error below rtol times the drag at u_ref is noise (MODEL.md §2.3).
  for (const auto& term : terms_) term->append_tolerances(std::max(atol, scene_.solver.rtol) * u_ref_, t);
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
  for (const auto& term : terms_) term->initial_states(y, [&] { return evaluate(0.0, y); });
}

void CollisionModel::at_step(double t, std::span<const double> y, bool restart) {
  end_.open = false;
  const Evaluation ev = kinematic_state(y);
  for (const auto& term : terms_) term->at_step(t, ev, restart);
}

void CollisionModel::step_accepted(double t, std::span<const double> y) {
  if (keep_step_ends_) {
    end_.open = true;
    end_.t = t;
    end_.y.assign(y.begin(), y.end());
    end_.ev.reset();
  }
  const Evaluation ev = kinematic_state(y);
  for (const auto& term : terms_) term->step_accepted(t, ev);
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
    const bool automatic = !(scene_.solver.max_step > 0) && !(term_step_cap_ < std::numeric_limits<double>::infinity());
    if (!automatic || !(ev.u_rel > 0)) return max_step_;
    return std::max(max_step_, 0.25 * (ev.gap - delta_ss_m_) / ev.u_rel);
  }
  return std::min(max_step_, law_->max_step(ev.gap, ev.u_rel));
}

void CollisionModel::forces(double t, std::span<const double> y, Evaluation& ev) const {
  // ev is fresh (its forces and masses zero): each term writes only its own slot.
  const TermInput in{t, y, phase_ != Phase::approach, phase_ == Phase::loading || phase_ == Phase::unloading};
  for (const auto& term : terms_) term->add(in, ev);
  // The mass matrix's diagonal: m_p, the terms' masses in registration order, the pair added mass A.
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    const auto& f = ev.f[m];
    double d = pair_.mp[m];
    for (std::size_t s : mass_slots_) d += f.mass[s];
    ev.m_eff[m] = d + ev.m_pair;
  }
  if (flow_) flow_->apply(t, sim_, implicit_added_mass(ev.gap), ev);
}

double CollisionModel::blend(double gap) const {
  if (!has_target()) return 0.0;
  return blend_weight(gap, delta_sl_m_);
}

AddedMassMatrix CollisionModel::implicit_added_mass(double gap) const {
  if (flow_ && !flow_->estimate()) return {};  // f_SIM used explicitly (a demonstration setting)
  return added_mass_.matrix(gap);  // the model's own added mass (MODEL.md §2.2)
}

double CollisionModel::analytic_fluid_force(const Evaluation& ev, const std::array<double, 2>& a, std::size_t m) const {
  // Uncoupled, f_THR is the fluid terms' sum and no mass is blended: the blend's sums, unweighted.
  const double base = coupled_ ? ev.thr_base[m] : fluid_.force(ev.f[m]);
  const double m_hist = coupled_ ? ev.m_blended_full[m] : fluid_.mass(ev.f[m]);
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
  for (std::size_t s : slots_[static_cast<std::size_t>(ForceKind::contact)])
    for (std::size_t m = 0; m < n_spheres_; ++m) g[m] -= ev.f[m].term[s];
  return ev.accelerations(g, n_spheres_);
}

void CollisionModel::sphere_states(std::span<const double> y, std::array<double, 2>& z, std::array<double, 2>& u) const {
  Evaluation ev;
  kinematics(y, ev);
  z = ev.z;
  u = ev.u;
}

std::array<double, 2> CollisionModel::total_forces(const Evaluation& ev) const {
  // The slots in registration order (model/force_terms.cpp), then the simulated force.
  std::array<double, 2> g{};
  const std::size_t n = terms_.size();
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    const auto& f = ev.f[m];
    double sum = f.term[0];
    for (std::size_t s = 1; s < n; ++s) sum += f.term[s];
    g[m] = sum + f.simulated;
  }
  return g;
}

const Evaluation* CollisionModel::kept_end(double t, std::span<const double> y) const {
  if (!end_.open || t != end_.t || !std::equal(y.begin(), y.end(), end_.y.begin(), end_.y.end())) return nullptr;
  if (!end_.ev) end_.ev = evaluate_at(t, y);
  return &*end_.ev;
}

Evaluation CollisionModel::evaluate(double t, std::span<const double> y) const {
  if (const Evaluation* kept = kept_end(t, y)) return *kept;
  return evaluate_at(t, y);
}

Evaluation CollisionModel::evaluate_at(double t, std::span<const double> y) const {
  Evaluation ev;
  kinematics(y, ev);
  forces(t, y, ev);
  const auto acc = ev.accelerations(total_forces(ev), n_spheres_);
  for (std::size_t m = 0; m < n_spheres_; ++m) ev.f[m].accel = acc[m];
  add_acceleration_parts(acc, ev);
  return ev;
}

void CollisionModel::add_acceleration_parts(const std::array<double, 2>& acc, Evaluation& ev) const {
  // The implicit added mass is the mass matrix beyond m_p and the blended masses; those are their terms' own.
  const bool pair = n_spheres_ == 2;
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    auto& f = ev.f[m];
    const double other = pair ? ev.m_couple * acc[1 - m] : 0.0;
    double implicit = ev.m_eff[m] - pair_.mp[m];
    for (std::size_t s : fluid_.masses) implicit -= f.mass[s];
    double am_accel = implicit * acc[m] + other;  // the implicit added-mass force
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
    (implicit_slot_ ? f.term[*implicit_slot_] : f.implicit_added_mass) -= am_accel;
    for (std::size_t s : fluid_.masses) f.term[s] -= f.mass[s] * acc[m];
  }
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
  for (const ForceTerm* term : stateful_) term->state_rhs(acc, y, ydot);
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
  for (const ForceTerm* term : stateful_) term->residual(y, yp, r);
}

std::size_t CollisionModel::quadrature_size() const { return scene_.measure.energy_budget ? kForceKinds : 0; }

void CollisionModel::quadrature_rhs(double t, std::span<const double> y, std::span<double> qdot) {
  const auto p = with_evaluation(t, y, [&](const Evaluation& ev) { return force_powers(ev, n_spheres_, slots_); });
  std::copy(p.begin(), p.end(), qdot.begin());
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
  auto add = [&](ModelRoot k, const char* name, int dir) {
    armed_.push_back({name, dir});
    armed_kind_.push_back(tag(k));
    armed_watched_.emplace_back();
  };
  const bool elastic = has(Effect::elastic);
  switch (phase_) {
    case Phase::approach:
    case Phase::separated:
      if (elastic) add(ModelRoot::contact_in, "gap=delta_ss (in)", -1);
      break;
    case Phase::loading:
      add(ModelRoot::unload, "u_rel=0 (loading->unloading)", -1);
      add(ModelRoot::touch, "gap=0", -1);
      add(ModelRoot::contact_out, "gap=delta_ss (out)", +1);
      break;
    case Phase::unloading:
      add(ModelRoot::contact_out, "gap=delta_ss (out)", +1);
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
  if (has(Effect::lubrication) && lub_model_ == LubricationModel::asymptotic) add(ModelRoot::lub_edge, "gap=h_c (lubrication edge)", 0);
  if (coupled_) {
    // The ends of the blend H (MODEL.md §2.5): diagnostic, the right-hand side stays continuous there. Not armed
    // while the gap sits on one of them (a start at 2δ_SL: CVODE refuses a root at the initial time).
    const double tiny = 1e-9 * D_;
    if (std::abs(arm_gap_ - 2 * delta_sl_m_) > tiny) add(ModelRoot::blend_edge, "gap=2*delta_sl (blend edge)", 0);
    if (phase_ != Phase::loading && std::abs(arm_gap_) > tiny) add(ModelRoot::blend_end, "gap=0 (blend end)", 0);
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
    switch (static_cast<ModelRoot>(armed_kind_[i])) {
      case ModelRoot::contact_in:
      case ModelRoot::contact_out: g[i] = gap - delta_ss_m_; break;
      case ModelRoot::touch:
      case ModelRoot::blend_end: g[i] = gap; break;
      case ModelRoot::blend_edge: g[i] = gap - 2 * delta_sl_m_; break;
      case ModelRoot::unload: g[i] = u_rel; break;
      case ModelRoot::lub_edge: g[i] = regularised_gap(gap, h_min_) - h_c_; break;
      default: g[i] = 1; break;  // a declared state: never armed
    }
  }
}

void CollisionModel::record(double t, EventTag kind, const std::string& name, std::span<const double> y) {
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

void CollisionModel::handle(EventTag kind, const std::string& name, double t, std::span<const double> y) {
  record(t, kind, name, y);
  Evaluation ev;
  kinematics(y, ev);
  switch (static_cast<ModelRoot>(kind)) {  // a watcher's tag is none of these
    case ModelRoot::contact_in:
      freeze_contact(t, ev.u_rel);
      phase_ = Phase::loading;
      break;
    case ModelRoot::unload:
      law_->unload();
      phase_ = Phase::unloading;
      break;
    case ModelRoot::contact_out:
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
  end_.open = false;  // the events change the phase and the law
  // Handle in a fixed order so that coincident roots (e.g. instant_gap == delta_ss) are deterministic.
  const auto kinds = armed_kind_;
  const auto specs = armed_;
  const auto watched = armed_watched_;
  bool changed = false;
  for (std::size_t i : found) {
    handle(kinds.at(i), specs.at(i).name, t, y);
    const bool diagnostic = watched[i] ? !watched[i]->restarts
                                       : kinds[i] == tag(ModelRoot::touch) || kinds[i] == tag(ModelRoot::blend_edge) || kinds[i] == tag(ModelRoot::blend_end);
    changed = changed || !diagnostic;
  }
  if (t >= stop_time_) return EventAction::stop;
  if (!changed) return EventAction::proceed;
  // The force law or the armed roots changed: restart the integrator here.
  arm();
  return EventAction::reinit;
}

std::vector<std::pair<std::string, std::string>> CollisionModel::choices() const {
  Choices c;
  for (const auto& term : terms_) c.insert(c.end(), term->choices().begin(), term->choices().end());
  const Choices blend = flow_ ? flow_->choices() : FlowBlend::uncoupled_choices();
  c.insert(c.end(), blend.begin(), blend.end());
  return c;
}

}  // namespace imcol::model
