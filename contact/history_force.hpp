// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// History force of one sphere (MODEL.md §2.3, seed 6.9), in a quiescent fluid (slip = U):
//   f_H = −6πμa K_H ∫_0^t (dU/dτ) K(t − τ) dτ − [impulsive start] 6πμa K_H U(0) K(t)        [N]
// written as f_H = F_explicit − m_H dU/dt, so that the acceleration term joins the mass matrix.
//
// Evaluators:
//  soe     memory states z_i = ∫_0^t U'(τ) e^(−λ_i (t−τ)) dτ [m/s], z_i' = U' − λ_i z_i, carried by the
//          integrator; ∫ U' K ≈ Σ w_i(Re) z_i + κ(Re) U' (κ: short-lag correction, the last min_lag of
//          memory with U' taken constant). O(modes) per evaluation.
//  soe-step the same exponentials, but the modes are not integrator states: over a step from t_n,
//          z_i(t) = e^(−λ_i Δ) z_i(t_n) + ∫_0^Δ P'(σ) e^(−λ_i (Δ−σ)) dσ,  Δ = t − t_n,
//          P the polynomial through the last (up to kPoints = 3) accepted (t_j, U_j) and the current (t, U), integrated
//          exactly (M_j = ∫_0^Δ σ^j e^(−λ(Δ−σ)) dσ); advance_memory() moves t_n to each accepted step.
//          A restart (event) forgets the earlier points, where U' may jump. O(1) per evaluation at a
//          known Δ (Basset); per new Δ, O(modes with λΔ ≤ 40) (Basset's faster modes in closed form,
//          contact/soe_fast_modes.hpp); O(modes) per accepted step. Outputs inside an accepted step (accept_step ..
//          advance_memory) take P through the accepted end and, where accurate, the step's interpolant
//          (contact/step_outputs.hpp): O(1) each.
//  direct  product integration on its own fixed grid t_k = kΔ (the integrator stops on it): U piecewise
//          linear through the grid values and the current U(t), each segment integrated exactly against K
//          (HistoryKernel::integral). O(t/Δ) per evaluation, O(N²) per run; second order in Δ for smooth U.
// Slip jumps. `steady` start: the sphere has moved at U(0) for ever, no jump, z_i(0) = 0. `impulsive`:
// the jump 0 → U(0) at t = 0 is treated analytically: its force −c U(0) K(t) is added exactly (soe:
// z_i(0) = U(0) carries Σ w_i e^(−λ_i t), plus the exact remainder K − Σ w_i e^(−λ_i t) that the
// exponentials miss below min_lag). Below t_f = 1e-3 min_lag that force is held at its value at t_f
// and the momentum it misses (∝ √t_f) is applied at t = 0 (apply_start): the error left is that of
// moving an impulse ~3% of the start-up impulse over min_lag by at most t_f. A rebound is not a jump
// here (the contact force is continuous); it is resolved by the integrator's steps, and by the soe
// only down to min_lag: its error there is that of holding U' constant over the last min_lag.
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "contact/history_kernel.hpp"
#include "contact/soe_fast_modes.hpp"
#include "contact/step_outputs.hpp"

namespace imcol::contact {

struct HistoryOptions {
  KernelKind kernel = KernelKind::basset;
  HistoryEvaluator evaluator = HistoryEvaluator::soe;  // soe | soe-step (modes outside the state) | direct
  double tolerance = 1e-6;
  int modes = 0;               // > 0: fixed mode count
  double min_lag = 0, horizon = 0;  // s (resolved, > 0)
  bool impulsive = false;
  bool initial_re = false;     // finite-Re kernels: Re frozen at |U(0)|
  double direct_step = 0;      // s (resolved, > 0) for the direct evaluator
  // soe-step, Basset: outputs inside an accepted step (rows, the energy quadrature's middle) see the memory along the
  // step's own polynomial; with interpolate_outputs, from the step's interpolant (contact/step_outputs.hpp) where its
  // error estimate is below output_rtol |S| + output_atol [m/s] or the memory's own error in the step.
  bool interpolate_outputs = false;
  double output_rtol = 0, output_atol = 0;
};

/// The sum-of-exponentials kernel for these options, built once per process and per (kernel, D, ν, min_lag,
/// horizon, tolerance | modes) and reused by every later run and sweep point (thread-safe; at most 256 kept).
std::shared_ptr<const SoeKernel> shared_soe_kernel(const HistoryOptions& opt, double D, double nu);

class SphereHistory {
 public:
  /// a [m], μ [Pa s], ρ_f [kg/m³], U0 [m/s] the initial velocity.
  SphereHistory(const HistoryOptions& opt, double a, double mu, double rho_f, double U0);

  std::size_t states() const { return evaluator_ == HistoryEvaluator::soe ? soe_->modes() : 0; }
  /// Memory states at t = 0.
  void initial_states(std::span<double> z) const;
  /// Per-state absolute tolerances u_floor/(√n w_i): the modes' force errors add up to that of a
  /// velocity error u_floor [m/s].
  std::vector<double> absolute_tolerances(double u_floor) const;

  struct Term {
    double force = 0;  // F_explicit [N] (already times K_H)
    double mass = 0;   // m_H [kg]: f_H = force − mass·dU/dt
  };
  Term evaluate(double t, double U, double K_H, std::span<const double> z) const {
    if (lean_) return {-c_ * K_H * lean_sum(t, U), c_ * K_H * kappa_};
    return evaluate_general(t, U, K_H, z);
  }
  /// z_i' = U' − λ_i z_i.
  void state_rhs(double accel, std::span<const double> z, std::span<double> dz) const;
  /// Current weights c K_H w_i(Re) (force per unit z_i) [kg/s], for the preconditioner.
  void gains(double U, double K_H, std::span<double> g) const;
  const std::vector<double>& rates() const;

  /// Impulsive start: the momentum of the start-up force below the floor t_f, given at t = 0 to a
  /// sphere of mass m_eff [kg]. Returns the velocity drop dU [m/s] (the sphere starts at U(0) − dU)
  /// and shifts the memory states z so that they see that start.
  double apply_start(double K_H, double m_eff, std::span<double> z) const;

  // soe-step: the memory kept here
  bool stepwise() const { return evaluator_ == HistoryEvaluator::soe_step; }
  /// Sets the modes at t (initial memory; the impulsive start's shift included).
  void reset_memory(double t, std::span<const double> z);
  /// An accepted step (restart = false) or a restart to t with velocity U: the modes move to t with the
  /// polynomial of that step; a restart keeps only (t, U) as the next polynomial's history.
  void advance_memory(double t, double U, bool restart);
  /// The step to (t, U) is accepted; until advance_memory, evaluations inside it are its outputs (rows, the energy
  /// quadrature's middle). With fixed weights they take the memory along the step's polynomial through (t, U): from
  /// the step's interpolant where it is accurate (interpolate_outputs), else exactly.
  void accept_step(double t, double U);
  /// Outputs of accepted steps so far: from the interpolant, and evaluated exactly (counted by accept_step's windows).
  long interpolated_outputs() const { return interpolated_; }
  long exact_outputs() const { return exact_outputs_; }
  /// soe-step: reuse `twin`'s e^(−λΔ), M and their weighted sums at the same Δ when both have the same exponentials
  /// (equal spheres share one cached kernel).
  void share_steps_with(const SphereHistory* twin);

  // direct evaluator grid
  double step() const { return step_; }
  void record(double t, double U);  // value at the next grid point t_k = kΔ

  // reporting
  std::size_t modes() const { return direct() ? 0 : soe_->modes(); }
  double reynolds(double U) const;
  const SoeKernel* soe() const { return soe_.get(); }

 private:
  Term evaluate_general(double t, double U, double K_H, std::span<const double> z) const;
  /// Basset soe-step without a start-up jump (lean_): memory_sum, taking the slot in_step found last without a call
  /// where it serves.
  double lean_sum(double t, double U) const {
    const double dt = t - tn_;
    if (window_ && t < acc_t_ && dt > 0) return output_sum(dt);
    StepCache& c = cache_[cur_];
    if (!(c.dt == dt && c.z_gen == z_gen_ && dt > 0 && np_ > 0)) return memory_sum(t, U, w_);
    c.used = ++uses_;
    c_now_ = (U - c.q_at) / c.w_at;
    return c.sums[0] + c.a + c_now_ * c.b;
  }
  bool lean_ = false;  // Basset's kernel, soe-step, no start-up jump
  double jump_term(double t, double Re) const;  // the start-up jump's share of ∫ U' K (U(0) K(t), soe: minus its exponentials)
  /// soe-step: E_i = e^(−λ_i Δ), M_ij (j < kPoints) at Δ = t − t_n, and P's coefficient c for (t, U); false if Δ ≤ 0.
  bool in_step(double t, double U) const;
  /// soe-step: Σ w_i z_i(t) with the in-step polynomial through (t, U).
  double memory_sum(double t, double U, std::span<const double> w) const;
  double start_floor() const;

  HistoryKernel kernel_;
  std::shared_ptr<const SoeKernel> soe_;  // shared through the process-wide cache (shared_soe_kernel)
  HistoryEvaluator evaluator_;
  bool direct() const { return evaluator_ == HistoryEvaluator::direct; }
  bool impulsive_, initial_re_;
  double c_;        // 6πμa [kg/s]
  double D_, nu_, U0_, min_lag_;
  mutable std::vector<double> w_;  // the current weights (Basset: fixed at construction)
  bool fixed_weights_ = false;     // Basset: w_ and kappa_ do not depend on Re
  double kappa_ = 0;               // Basset's short-lag coefficient κ
  double step_ = 0;
  std::vector<double> grid_u_;     // U at t_k = kΔ, k = 0..n
  // soe-step
  std::vector<double> z_;               // modes at t_n
  std::vector<double> inv_rate_;        // 1/λ_i
  mutable std::vector<double> zs_;      // scratch: the modes inside a step (finite-Re kernels), the advance's new modes
  double tn_ = 0;
  static constexpr int kPoints = 3;     // accepted points kept: P of degree ≤ kPoints
  static_assert(kPoints == SoeFastModes::kPoints, "the fast modes' M_j are those of the in-step polynomial");
  std::array<double, kPoints> pt_{}, pu_{};  // accepted (t_j, U_j), most recent first (pt_[0] = t_n)
  int np_ = 0;
  // One Δ. kSlots are kept, the least recently used replaced: a step's end Δ = h, the energy quadrature's interior
  // nodes (h/2 for Simpson) and an output sample in it. e, M and their Basset sums depend on Δ alone and outlive a
  // step (CVODE often keeps h); sums[0] follows the modes z_ (generation z_gen).
  struct StepCache {
    double dt = -1;
    long z_gen = -1;
    long sum0_gen = -1;                 // Basset: sums[0] is that of the modes of this generation
    long used = 0;                      // when last used (uses_), for the replacement
    std::vector<double> e, we, m;       // e^(−λ_i Δ), Basset's w_i e^(−λ_i Δ); M_ij at [j · modes + i]
    std::size_t fast = 0;               // Basset: e, we, M kept for the modes below `fast` only, until `full`
    bool full = false;                  // e and M for every mode (advance_memory, Re-dependent weights)
    std::array<double, kPoints + 1> sums{};  // Basset: Σ w_i e^(−λ_i Δ) z_i, Σ w_i M_ij
    double q_at = 0, w_at = 1;          // Q(Δ), ω(Δ)
    double a = 0, b = 0;                // Basset: Σ_j Q'_j Σ_i w_i M_ij and Σ_j ω'_j Σ_i w_i M_ij
  };
  long z_gen_ = 0;                      // bumped whenever z_ changes
  static constexpr int kSlots = 4;
  mutable std::array<StepCache, kSlots> cache_;
  mutable int cur_ = 0;                 // the slot in_step filled or found last
  mutable long uses_ = 0;
  /// The slot holding Δ = dt, or the least recently used one.
  int slot_for(double dt) const;
  /// The slot at Δ = dt > 0 (found or filled), its sums those of the current modes; it becomes cur_.
  const StepCache& step_at(double dt) const;
  const SphereHistory* twin_ = nullptr; // an equal sphere (same exponentials) whose e and M are reused
  /// e and M of the modes [from, to) at Δ = dt.
  void fill_step(StepCache& c, double dt, std::size_t from, std::size_t to) const;
  /// A new Δ in slot c: the twin's values, or Basset's slower modes and sums, or every mode (Re-dependent weights).
  void new_step(StepCache& c, double dt) const;
  /// Basset: the slower modes one by one, the fast ones in closed form.
  void fill_basset(StepCache& c, double dt) const;
  /// e and M for every mode in slot c (before the memory moves by its Δ).
  void fill_all_modes(StepCache& c) const;
  SoeFastModes fast_;                   // Basset's fast modes
  /// soe-step: every z_i = e^(−λ_i Δ) z_i + Σ_j P'_j M_ij at slot c's Δ (c full), P's coefficient cf, into out (not z_).
  void modes_at(const StepCache& c, double cf, std::span<double> out) const;
  /// modes_at with the coefficient in_step found (c_now_); returns Σ_(i < c.fast) w_i e^(−λ_i Δ) out_i (Basset; 0
  /// otherwise): c's sums[0] for the modes in `out`.
  double modes_in_step(const StepCache& c, std::span<double> out) const;
  // The in-step polynomial P = Q + c ω: Q through the accepted points and ω(σ) = Π_k (σ − s_k), in monomials of σ
  // (step_polynomial, once per accepted step); c = (U − Q(Δ))/ω(Δ) from the current (t, U) (in_step).
  std::array<double, kPoints> pq_{};
  std::array<double, kPoints + 1> pw_{};
  mutable double c_now_ = 0;
  void step_polynomial();
  /// P'(σ) = Σ_j slope_j σ^j, j < np_ (P's coefficient c: c_now_, or the one given).
  double in_step_slope(int j) const { return in_step_slope(j, c_now_); }
  double in_step_slope(int j, double c) const;
  /// The monomial coefficients (in σ = t − t_n) of the polynomial through (s_k, u_k), k < m ≤ kPoints.
  static std::array<double, kPoints> monomials_through(const double* s, const double* u, int m);
  // Outputs inside the accepted step (accept_step .. advance_memory), Basset's fixed weights only.
  /// S and S' at the step's end Δ = dt from slot c with P's coefficient cf (before the modes move).
  StepOutputs::End end_of(const StepCache& c, double cf) const;
  /// The step's polynomial through the accepted end and, with interpolate_outputs, its interpolant: at the first output.
  void build_outputs() const;
  /// Σ w_i z_i at Δ = dt inside the accepted step (an output).
  double output_sum(double dt) const;
  /// The interior lag where the interpolant is checked: a kept Δ in [h/4, 3h/4] nearest h/2, else h/2.
  double check_lag(double h) const;
  /// At accept_step (Basset): the modes at the step's end into z_next_ and their sum, P's c (out_cf_); with
  /// interpolate_outputs S and S' there (outputs_end_, end_of).
  void step_end(double t, double U);
  std::vector<double> z_next_;           // the modes at the accepted end, taken by advance_memory
  bool next_ok_ = false;                 // z_next_ and next_sum0_ are those of (acc_t_, acc_u_) from modes z_gen next_gen_
  long next_gen_ = -1;
  double next_sum0_ = 0;                 // Σ_(slow) w_i e_i z_next_i in the slot of the step's Δ
  bool interpolate_ = false;
  double output_rtol_ = 0, output_atol_ = 0;
  mutable double out_cf_ = 0;            // P's coefficient c through the accepted end
  bool window_ = false;                  // between accept_step and advance_memory
  double acc_t_ = 0, acc_u_ = 0;         // the accepted step's end
  StepOutputs::End left_{};              // S, S' at t_n: the end of the step before
  bool left_ok_ = false;                 // false at the start and after a restart (U' may jump there)
  StepOutputs::End outputs_end_{};       // S, S' at the accepted end (step_end)
  mutable std::optional<StepOutputs> outputs_;
  mutable bool outputs_built_ = false;
  mutable long interpolated_ = 0, exact_outputs_ = 0;
  static double horner(const double* c, int degree, double x);
  static double dot(const double* a, const double* b, std::size_t n);  // Σ a_i b_i
};

}  // namespace imcol::contact
