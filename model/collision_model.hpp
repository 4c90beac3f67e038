#pragma once
// Reduced-order model of one head-on collision (MODEL.md §2, §3 with H ≡ 1, no f_SIM):
//   m_p,m dU_m/dt = f_D,m + f_lub,m + f_AM,m + f_SS,m + (m_p,m − m_f,m) g        (seed 6.4, 6.10)
// The added-mass acceleration terms are moved to the left-hand side (a mass matrix on the velocities):
//   `seed`        (6.8) per sphere: m_p,m + ½ m_f,m (1 + 3W) on its own dU_m/dt (diagonal);
//   `lagrangian`  (choice) kinetic energy T = Σ ½ (m_p,m + ½ m_f,m) U_m² + ½ A(δ) U_rel²,
//                 A = (3/2) m_f* W(δ**), m_f* = (1/m_f,1 + 1/m_f,2)⁻¹: the same as (6.8) for a wall,
//                 and for a pair it conserves momentum and, in an ideal fluid, the relative energy.
// Only the effects the scene lists are built.
//
// With the history effect (MODEL.md §2.3, contact/history_force.hpp) f_H,m joins the forces and its
// acceleration part m_H,m dU_m/dt the mass matrix.
//
// State (SI): wall   [gap, u1]; pair [gap, u1, z2, u2]; free sphere [z1, u1]; then the history
// memory states of sphere 1, then of sphere 2 (sum of exponentials only).
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
#include "model/watcher.hpp"

namespace imcol::model {

using contact::ContactLaw;
using contact::HistoryOptions;
using contact::SphereHistory;
using contact::GapGeometry;

/// Forces acting on one sphere (N along z). With the `flow` effect the fluid terms are the blended ones that act,
/// H × (analytic term), and `simulated` is (1 − H) f_SIM (MODEL.md (6.10)).
struct SphereForces {
  double drag = 0, lubrication = 0, added_mass = 0, contact = 0, gravity = 0, history = 0;  // N along z
  double simulated = 0;
  double accel = 0;  // m/s^2
  double f_thr = 0;  // the analytic fluid force f_THR unblended, incl. its acceleration parts (reporting)
  double f_sim = 0;  // the flow kernel's force f_SIM, reconstructed with the current acceleration (reporting)
};

/// The simulated fluid force over one flow step (MODEL.md §5): per sphere, the flow kernel's force with the
/// model's added-mass estimate removed, f_rest = f_SIM + M_A a_flow, linear in t between (t0, f0) and (t1, f1)
/// (extrapolated linearly outside). The model adds (1 − H) f_rest and keeps M_A implicit in its mass matrix.
struct SimulatedForce {
  double t0 = 0, t1 = 1;
  std::array<double, 2> f0{}, f1{};
  double at(double t, std::size_t m) const {
    const double w = t1 > t0 ? (t - t0) / (t1 - t0) : 1.0;
    return f0[m] + w * (f1[m] - f0[m]);
  }
};

/// The added-mass matrix the model keeps implicit (kg): [[m11, m12], [m12, m22]].
struct AddedMassMatrix {
  double m11 = 0, m22 = 0, m12 = 0;
};

struct Evaluation {
  double gap = 0;    // m
  double u_rel = 0;  // m/s, U1 − U2 (> 0 approaching)
  std::array<double, 2> z{}, u{};
  std::array<double, 2> m_eff{};  // diagonal of the velocity mass matrix, kg
  double m_couple = 0;            // its off-diagonal entry (lagrangian pair added mass), kg
  std::array<double, 2> m_hist{};  // the history force's share of m_eff (κ-like term), kg
  double H = 1;                     // blend weight of f_THR (MODEL.md §2.5); 1 without the flow effect
  std::array<double, 2> f_rest{};   // SimulatedForce at t (flow effect), N
  std::array<double, 2> thr_base{}, m_hist_full{};  // unblended f_THR without acceleration parts, N; history mass, kg
  /// Solves the 2×2 mass system for the accelerations given the forces g.
  std::array<double, 2> accelerations(const std::array<double, 2>& g, std::size_t n) const;
  std::array<SphereForces, 2> f{};
};

/// What an event is: the root that fired (the model's own or a watcher's, model/watcher.hpp), or a declared state
/// (a start inside the contact zone by the model, at rest by a watcher).
enum class EventKind { contact_in, contact_out, unload, touch, instant_in, instant_out, closest, lub_edge, blend_edge, blend_end,
                       apex, rebound_stalled, measure_out, start_in_contact, at_rest };

/// A discrete event in the run, for the summary.
struct EventRecord {
  double t;
  std::string name;
  double gap;
  double u_rel;
  EventKind kind;
};

enum class Phase { approach, loading, unloading, separated };
const char* to_string(Phase p);

class CollisionModel : public DynamicalSystem {
 public:
  explicit CollisionModel(const Scene& scene);

  // ---- DynamicalSystem ----
  std::size_t size() const override { return core_size() + history_states_; }
  std::vector<std::string> component_names() const override;
  std::vector<double> absolute_tolerances(double atol) const override;
  void initial_state(std::span<double> y) const override;
  void rhs(double t, std::span<const double> y, std::span<double> ydot) override;
  void residual(double t, std::span<const double> y, std::span<const double> yp, std::span<double> r) override;
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
  void at_step(double t, std::span<const double> y, bool restart) override;  // history evaluator soe-step
  bool modal_structure(double t, std::span<const double> y, ModalStructure& s) const override;

  // ---- Coupling seam (flow effect, MODEL.md (6.10), §5) ----
  bool coupled() const { return coupled_; }
  /// The simulated force for the coming flow step; the right-hand side uses it from now on.
  void set_simulated_force(const SimulatedForce& f) { sim_ = f; }
  const SimulatedForce& simulated_force() const { return sim_; }
  /// H(δ/δ_SL): smoothstep on [0, 2], 1 at contact, ½ at δ_SL, 0 beyond 2δ_SL (and for a free sphere).
  double blend(double gap) const;
  /// The added mass kept implicit at this gap, including the estimate that stands for f_SIM's (§5).
  AddedMassMatrix implicit_added_mass(double gap) const;
  /// Positions (z1, z2) and velocities (u1, u2) of the spheres in the state y, m and m/s.
  void sphere_states(std::span<const double> y, std::array<double, 2>& z, std::array<double, 2>& u) const;
  double delta_sl_m() const { return delta_sl_m_; }
  /// The analytic fluid force f_THR on each sphere, unblended (MODEL.md (6.10): drag, lubrication, added mass and
  /// history as the scene lists them) at (t, y) with the accelerations a (m/s²), N. The Fig. 6.4 comparison uses it.
  std::array<double, 2> analytic_fluid_force(double t, std::span<const double> y, const std::array<double, 2>& a) const;
  /// Accelerations of the spheres at (t, y) without the solid contact force (m/s²): the coupling's predictor.
  std::array<double, 2> accelerations_without_contact(double t, std::span<const double> y) const;

  // ---- Physics, for reporting ----
  Evaluation evaluate(double t, std::span<const double> y) const;
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
  std::size_t n_spheres() const { return n_spheres_; }
  bool has_target() const { return target_ != Target::none; }
  bool has_wall() const { return target_ == Target::wall; }

  std::size_t core_size() const { return n_spheres_ * 2; }
  /// History of sphere m (null without the history effect).
  const SphereHistory* history(std::size_t m) const { return history_[m].get(); }
  const HistoryOptions& history_options() const { return hist_opt_; }

  // Pair properties
  double a_star() const { return a_star_; }
  double m_star() const { return m_star_; }
  double E_star() const { return E_star_; }
  double e_dry() const { return e_dry_; }
  double delta_ss_m() const { return delta_ss_m_; }
  double radius(int m) const { return a_[m]; }
  double mass(int m) const { return mp_[m]; }
  double fluid_mass(int m) const { return mf_[m]; }

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
  const ContactLaw* contact_law() const { return law_.get(); }
  double max_contact_force() const { return max_contact_force_; }
  /// Model choices that ran, name → value.
  std::vector<std::pair<std::string, std::string>> choices() const;

 private:
  enum class Target { none, wall, sphere };
  using RootKind = EventKind;

  void arm();
  void kinematics(std::span<const double> y, Evaluation& ev) const;
  std::array<double, 2> total_forces(const Evaluation& ev) const;
  /// Forces without the added-mass acceleration terms; fills ev.f, ev.m_eff and ev.m_couple.
  void forces(double t, std::span<const double> y, Evaluation& ev) const;
  /// Weights the analytic fluid terms by H and adds (1 − H) f_SIM (MODEL.md (6.10), §5).
  void blend_in_simulated(double t, Evaluation& ev) const;
  /// f_THR of sphere m from an evaluated state (forces() done) and the accelerations.
  double analytic_fluid_force(const Evaluation& ev, const std::array<double, 2>& a, std::size_t m) const;
  double wall_function_W(double gap) const;  // W(δ**) continued linearly below dw_floor
  double history_K_H(double gap) const;
  std::span<const double> history_z(std::span<const double> y, std::size_t m) const;
  void setup_history();
  double contact_force(double gap, double u_rel) const;  // magnitude, pushes the pair apart
  void freeze_contact(double t, double u_rel);
  void handle(RootKind kind, const std::string& name, double t, std::span<const double> y);
  void record(double t, EventKind kind, const std::string& name, std::span<const double> y);
  /// Tells the watchers of the event just recorded, records what they declare and takes their stop times.
  void tell_watchers(double t, const Evaluation& ev);
  void declare(double t, const Evaluation& ev, const std::optional<Declared>& d);

  bool has(Effect e) const { return scene_.has(e); }

  const Scene scene_;
  bool coupled_ = false;     // the flow effect: f_SL = H f_THR + (1 − H) f_SIM
  double delta_sl_m_ = 0;    // δ_SL, m
  double arm_gap_ = 0;       // the gap where the roots were last armed (t = 0 or the last event), m
  SimulatedForce sim_;
  Target target_;
  std::size_t n_spheres_;
  std::array<double, 2> a_{}, mp_{}, mf_{};
  double D_ = 0, a_star_ = 0, m_star_ = 0, E_star_ = 0, e_dry_ = 1, c_log_ = 0;
  double mu_ = 0, rho_f_ = 0;
  double delta_ss_m_ = 0, h_min_ = 0, h_c_ = 0, dw_floor_ = 0, u_ref_ = 0, gap_scale_ = 0;
  double w_floor_ = 0, dw_slope_ = 0;  // W and dW/dδ at dw_floor
  double u_rel0_ = 0;       // initial U1 − U2, m/s (> 0: approaching)
  DragLaw drag_law_ = DragLaw::stokes;
  LubricationModel lub_model_ = LubricationModel::asymptotic;
  GapGeometry gap_geo_;  // the gap law's radii, a*, c_log, h_c
  bool lagrangian_am_ = false;
  double mf_star_ = 0;  // reduced fluid mass for the lagrangian pair added mass
  HistoryOptions hist_opt_;
  std::array<std::unique_ptr<SphereHistory>, 2> history_;
  std::array<std::size_t, 2> hist_offset_{};
  std::size_t history_states_ = 0;
  std::size_t direct_points_ = 1;  // grid points recorded by the direct evaluator (t_0 = 0 at construction)
  bool kh_added_mass_ = false;

  Phase phase_ = Phase::approach;
  std::unique_ptr<ContactLaw> law_;  // f_SS (MODEL.md §2.4), from contact.law
  double U_c_ = 0;
  double max_contact_force_ = 0;
  int contacts_ = 0;
  std::optional<double> t_contact_, t_separation_;
  std::vector<RootSpec> armed_;
  std::vector<RootKind> armed_kind_;
  std::vector<std::optional<WatchedRoot>> armed_watched_;  // per armed root: the watcher's, or none for the model's own
  std::vector<EventWatcher*> watchers_;
  std::vector<EventRecord> events_;
  double stop_time_ = 0, max_step_ = 0;
};

}  // namespace imcol::model
