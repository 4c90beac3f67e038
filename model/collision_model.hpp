// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reduced-order model of one head-on collision (MODEL.md §2, §3):
//   m_p,m dU_m/dt = f_D,m + f_lub,m + f_AM,m + f_SS,m + (m_p,m − m_f,m) g + f_H,m        (seed 6.4, 6.10)
// Each force is a term (model/force_term.hpp), built by make_force_terms only for the effects the scene lists:
// drag (model/drag_term.hpp), gap resistance (gap_resistance_term), added mass (added_mass_term), contact
// (contact_term), gravity (gravity_term), history (history_term). The model sums their slots, and their masses,
// in that registration order. The acceleration parts of the added mass and the history force are moved to the
// left-hand side, a mass matrix on the velocities. With the `flow` effect the analytic fluid terms are blended
// with the simulated force (model/flow_blend.hpp).
//
// State (SI): wall   [gap, u1]; pair [gap, u1, z2, u2]; free sphere [z1, u1]; then the terms' own states in
// registration order (the history memory of sphere 1, then of sphere 2: sum of exponentials only).
// The gap, not z1, is a state so that the error control acts on it relative to its own size:
// a contact happens over micrometres while z1 is centimetres.
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contact/contact_law.hpp"
#include "contact/formulas.hpp"
#include "contact/history_force.hpp"
#include "core/scene.hpp"
#include "core/system.hpp"
#include "model/event.hpp"
#include "model/watcher.hpp"
#include "model/added_mass_term.hpp"
#include "model/evaluation.hpp"
#include "model/flow_blend.hpp"
#include "model/force_term.hpp"
#include "model/history_term.hpp"
#include "model/pair.hpp"

namespace imcol::model {

using contact::ContactLaw;
using contact::HistoryOptions;
using contact::SphereHistory;
using contact::GapGeometry;

enum class Phase { approach, loading, unloading, separated };
const char* to_string(Phase p);

class CollisionModel : public DynamicalSystem {
 public:
  explicit CollisionModel(const Scene& scene);

  // ---- DynamicalSystem ----
  std::size_t size() const override { return core_size() + states_; }
  std::vector<std::string> component_names() const override;
  std::vector<double> absolute_tolerances(double atol) const override;
  void initial_state(std::span<double> y) const override;
  void rhs(double t, std::span<const double> y, std::span<double> ydot) override;
  void residual(double t, std::span<const double> y, std::span<const double> yp, std::span<double> r) override;
  /// The work of each force (model/force_work.hpp), carried as quadratures by the integrator.
  std::size_t quadrature_size() const override;
  void quadrature_rhs(double t, std::span<const double> y, std::span<double> qdot) override;
  std::vector<RootSpec> roots() const override { return armed_; }
  void root_values(double t, std::span<const double> y, std::span<double> g) override;
  EventAction on_roots(std::span<const std::size_t> found, double t, std::span<double> y) override;
  double stop_time() const override { return stop_time_; }
  /// Outside contact: max_step_ (the contact zone cannot be crossed in one step); while approaching with the automatic
  /// cap, up to a quarter of the time to reach the contact zone at the current relative speed. In contact (loading,
  /// unloading): also the contact law's step hint (ContactLaw::max_step).
  double max_step(double t, std::span<const double> y) const override;
  double max_step_outside_contact() const { return max_step_; }
  double next_breakpoint(double t) const override;
  void at_breakpoint(double t, std::span<const double> y) override;
  void at_step(double t, std::span<const double> y, bool restart) override;  // the terms' step hooks (soe-step memory)
  void step_accepted(double t, std::span<const double> y) override;
  bool modal_structure(double t, std::span<const double> y, ModalStructure& s) const override;

  // ---- Coupling seam (flow effect, MODEL.md (6.10), §5) ----
  /// The simulated force for the coming flow step; the right-hand side uses it from now on.
  void set_simulated_force(const SimulatedForce& f) {
    sim_ = f;
    end_.open = false;
  }
  /// H(δ/δ_SL): smoothstep on [0, 2], 1 at contact, ½ at δ_SL, 0 beyond 2δ_SL (and for a free sphere).
  double blend(double gap) const;
  /// The added mass kept implicit at this gap, including the estimate that stands for f_SIM's (§5).
  AddedMassMatrix implicit_added_mass(double gap) const;
  /// Positions (z1, z2) and velocities (u1, u2) of the spheres in the state y, m and m/s.
  void sphere_states(std::span<const double> y, std::array<double, 2>& z, std::array<double, 2>& u) const;
  /// The analytic fluid force f_THR on each sphere, unblended (MODEL.md (6.10): drag, lubrication, added mass and
  /// history as the scene lists them) at (t, y) with the accelerations a (m/s²), N. The Fig. 6.4 comparison uses it.
  std::array<double, 2> analytic_fluid_force(double t, std::span<const double> y, const std::array<double, 2>& a) const;
  /// Accelerations of the spheres at (t, y) without the solid contact force (m/s²): the coupling's predictor.
  std::array<double, 2> accelerations_without_contact(double t, std::span<const double> y) const;

  // ---- Physics, for reporting ----
  /// The model at (t, y). With keep_step_ends, at the end of an accepted step (step_accepted .. at_step) it is
  /// evaluated once and kept for the outputs there (the energy quadrature's end, a row at every step).
  Evaluation evaluate(double t, std::span<const double> y) const;
  /// f(evaluate(t, y)) without copying the kept step end.
  template <class F>
  decltype(auto) with_evaluation(double t, std::span<const double> y, F&& f) const {
    if (const Evaluation* kept = kept_end(t, y)) return f(*kept);
    return f(evaluate_at(t, y));
  }
  void keep_step_ends(bool on) { keep_step_ends_ = on; }
  /// Adds a rule that measures the run or ends it (model/watcher.hpp; run/ adds them before integrating) and re-arms
  /// the roots. The watcher must outlive the integration.
  void watch(EventWatcher& w);
  /// Called with each output sample (run/recorder.cpp): tells the watchers, records what they declare and takes their stop times.
  void observe(double t, const Evaluation& ev);
  /// Whether a watcher reads the forces and accelerations of the sample now; otherwise a kinematic sample
  /// (kinematic_state) is enough.
  bool observes_accelerations() const;
  /// The positions, velocities and gap at y, without forces.
  Evaluation kinematic_state(std::span<const double> y) const;
  /// Its gap alone, m (infinite without a target).
  double gap_of(std::span<const double> y) const { return has_target() ? y[0] : std::numeric_limits<double>::infinity(); }
  std::size_t n_spheres() const { return n_spheres_; }
  bool has_target() const { return target_ != Target::none; }
  bool has_wall() const { return target_ == Target::wall; }

  std::size_t core_size() const { return n_spheres_ * 2; }
  /// The force terms in registration order (their slots), and the slot of each kind of force.
  const ForceTerms& terms() const { return terms_; }
  const KindSlots& kind_slots() const { return slots_; }
  /// History of sphere m (null without the history effect).
  const SphereHistory* history(std::size_t m) const { return history_ ? history_->sphere(m) : nullptr; }
  const HistoryOptions& history_options() const;

  // Pair properties
  double a_star() const { return pair_.a_star; }
  double m_star() const { return pair_.m_star; }
  double e_dry() const { return pair_.e_dry; }
  const PairGeometry& geometry() const { return pair_; }
  double delta_ss_m() const { return delta_ss_m_; }
  double radius(int m) const { return a_[m]; }
  double mass(int m) const { return pair_.mp[m]; }
  double fluid_mass(int m) const { return pair_.mf[m]; }

  // What happened
  Phase phase() const { return phase_; }
  const std::vector<EventRecord>& events() const { return events_; }
  int contacts() const { return contacts_; }
  std::optional<double> t_contact() const { return t_contact_; }       // first δ_SS crossing inward
  std::optional<double> t_separation() const { return t_separation_; } // first δ_SS crossing outward after contact
  double impact_speed() const { return U_c_; }    // U_rel at the first δ_SS crossing, m/s
  double initial_u_rel() const { return u_rel0_; }  // U1 − U2 at t = 0, m/s
  double initial_gap() const;                        // m; infinite without a target
  bool started_in_contact() const { return t_contact_ && *t_contact_ == 0.0; }
  /// The solid contact law (null without the elastic effect or a target).
  const ContactLaw* contact_law() const { return law_; }
  /// Model choices that ran, name → value.
  std::vector<std::pair<std::string, std::string>> choices() const;

 private:

  /// max_step_ from the contact zone (or solver.max_step), refusing a run beyond solver.step_budget.
  void set_step_cap(const Scene& sc);
  /// Builds the terms and reads what the model needs of them: slots, states, step caps, the contact law, the lubrication edge.
  void build_terms(const Scene& sc);
  void arm();
  void kinematics(std::span<const double> y, Evaluation& ev) const;
  /// The slots in registration order, then the simulated force: each sphere's force beside the mass matrix.
  std::array<double, 2> total_forces(const Evaluation& ev) const;
  /// Reports the full added-mass and blended-mass forces of an evaluated state, with their acceleration parts.
  void add_acceleration_parts(const std::array<double, 2>& acc, Evaluation& ev) const;
  /// Forces without the added-mass acceleration terms: each term's slots, then m_eff in registration order, then the
  /// flow blend (MODEL.md (6.10), §5); fills ev.f, ev.m_eff and ev.m_couple of a fresh ev (kinematics() done).
  void forces(double t, std::span<const double> y, Evaluation& ev) const;
  Evaluation evaluate_at(double t, std::span<const double> y) const;
  struct EndOfStep {
    bool open = false;
    double t = 0;
    std::vector<double> y;
    std::optional<Evaluation> ev;
  };
  mutable EndOfStep end_;  // the accepted step's end and its evaluation, once made
  /// The kept evaluation when (t, y) is the accepted step's end (made at the first call), else null.
  const Evaluation* kept_end(double t, std::span<const double> y) const;
  bool keep_step_ends_ = false;
  /// f_THR of sphere m from an evaluated state (forces() done) and the accelerations.
  double analytic_fluid_force(const Evaluation& ev, const std::array<double, 2>& a, std::size_t m) const;
  void freeze_contact(double t, double u_rel);
  /// An armed root fired: its tag (a ModelRoot, or a watcher's kind).
  void handle(EventTag kind, const std::string& name, double t, std::span<const double> y);
  void record(double t, EventTag kind, const std::string& name, std::span<const double> y);
  /// Tells the watchers of the event just recorded, records what they declare and takes their stop times.
  void tell_watchers(double t, const Evaluation& ev);
  void declare(double t, const Evaluation& ev, const std::optional<Declared>& d);

  bool has(Effect e) const { return scene_.has(e); }

  const Scene scene_;
  const PairGeometry pair_;  // radii, masses, a*, m*, E*, e_dry, δ_SS, scales
  ForceTerms terms_;         // the effects the scene lists (make_force_terms), in registration order
  KindSlots slots_;          // the slot of each kind of force (the energy budget's, the contact's)
  FluidSlots fluid_;         // the fluid terms' slots and the blended masses (f_THR, the flow blend)
  std::optional<std::size_t> implicit_slot_;  // the term whose mass is kept implicit (the added mass), if any
  std::vector<std::size_t> mass_slots_;       // the slots of the terms with a mass, in registration order
  std::size_t states_ = 0;   // the terms' states, after the core states
  std::vector<const ForceTerm*> stateful_;  // the terms with states, in registration order (their rhs and residual rows)
  double term_step_cap_ = std::numeric_limits<double>::infinity();  // the terms' cap on the step (direct history grid), s
  const HistoryTerm* history_ = nullptr;  // among terms_, or null: its options and memories, for reporting
  AddedMassForm added_mass_;        // the model's own added mass, also the flow blend's estimate
  std::optional<FlowBlend> flow_;   // with the flow effect
  bool coupled_ = false;     // the flow effect: f_SL = H f_THR + (1 − H) f_SIM
  double delta_sl_m_ = 0;    // δ_SL, m
  double arm_gap_ = 0;       // the gap where the roots were last armed (t = 0 or the last event), m
  SimulatedForce sim_;
  Target target_;
  std::size_t n_spheres_;
  std::array<double, 2> a_{};
  double D_ = 0;
  double delta_ss_m_ = 0, u_ref_ = 0;
  double h_min_ = 0, h_c_ = 0;  // the gap resistance's cutoff and h_c (its lubrication-edge root), m
  double u_rel0_ = 0;       // initial U1 − U2, m/s (> 0: approaching)
  LubricationModel lub_model_ = LubricationModel::asymptotic;

  Phase phase_ = Phase::approach;
  ContactLaw* law_ = nullptr;  // f_SS (MODEL.md §2.4), from contact.law: the contact term's, among terms_
  double U_c_ = 0;
  int contacts_ = 0;
  std::optional<double> t_contact_, t_separation_;
  std::vector<RootSpec> armed_;
  std::vector<EventTag> armed_kind_;
  std::vector<std::optional<WatchedRoot>> armed_watched_;  // per armed root: the watcher's, or none for the model's own
  std::vector<EventWatcher*> watchers_;
  std::vector<EventRecord> events_;
  double stop_time_ = 0, max_step_ = 0;
};

}  // namespace imcol::model
