// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// History force f_H (MODEL.md §2.3, seed (6.9)) on each sphere: −6πμ a_m K_H(δ**) ∫ (dU_m/dτ) K(t − τ) dτ, N, by
// contact/history_force.hpp (SphereHistory). Its explicit part is a force; its acceleration part m_H,m dU_m/dt
// (kg) joins the mass matrix (its mass slot, TermMass::blended). K_H (history.wall_correction, choice): `none` 1; `added-mass` 1 + 3W(δ**),
// the wall amplification of the added mass (model/wall_function.hpp).
// It owns its memory states (sum of exponentials: those of sphere 1, then of sphere 2, where the model places them),
// the direct evaluator's grid (breakpoints) and the soe-step memory advanced at each accepted step.
#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "contact/history_force.hpp"
#include "core/scene.hpp"
#include "core/system.hpp"
#include "model/force_term.hpp"
#include "model/pair.hpp"
#include "model/wall_function.hpp"

namespace imcol::model {

class HistoryTerm : public ForceTerm {
 public:
  HistoryTerm(const Scene& sc, const PairGeometry& p);
  const contact::HistoryOptions& options() const { return opt_; }
  const contact::SphereHistory* sphere(std::size_t m) const { return h_[m].get(); }
  double K_H(double gap) const;
  /// The direct evaluator's grid step (a cap on the solver's step), or infinity.
  double step_cap() const override;
  TermSlot properties() const override { return {ForceKind::history, "f_hist", true, TermMass::blended}; }
  void add(const TermInput& in, Evaluation& ev) const override;

  // ---- its states and its part of the model's DynamicalSystem ----
  std::size_t states() const override { return states_; }
  void place_states(std::size_t first) override;
  void append_names(std::vector<std::string>& names) const override;
  void append_tolerances(double u_floor, std::vector<double>& t) const override;
  /// The memory's initial states in y (and the soe-step memory); an impulsive start then evaluates the model at
  /// the start (evaluate_start) and gives each sphere the start-up momentum below the force floor.
  void initial_states(std::span<double> y, const std::function<Evaluation()>& evaluate_start) const override;
  void state_rhs(const std::array<double, 2>& acc, std::span<const double> y, std::span<double> ydot) const override;
  /// The memory rows of the implicit form: z_i' − (U' − λ_i z_i) = 0.
  void residual(std::span<const double> y, std::span<const double> yp, std::span<double> r) const override;
  double next_breakpoint() const override;
  void at_breakpoint(double t, const Evaluation& ev) override;
  void at_step(double t, const Evaluation& ev, bool restart) override;
  void step_accepted(double t, const Evaluation& ev) override;  // soe-step: the memory's outputs inside the step
  bool modal_structure(const Evaluation& ev, std::size_t core, ModalStructure& s) const override;

 private:
  std::span<const double> memory(std::span<const double> y, std::size_t m) const;
  /// The fastest time scale the memory must resolve, s.
  static double fastest_time(const Scene& sc, const PairGeometry& p);
  void make_spheres(const Scene& sc, const PairGeometry& p);
  void set_choices(const Scene::History& h);

  contact::HistoryOptions opt_;
  WallFunction wall_;
  bool kh_added_mass_ = false;
  std::size_t n_spheres_ = 1;
  std::array<std::unique_ptr<contact::SphereHistory>, 2> h_;
  std::array<std::size_t, 2> offset_{};
  std::size_t states_ = 0;
  std::size_t direct_points_ = 1;  // grid points recorded by the direct evaluator (t_0 = 0 at construction)
};

std::unique_ptr<ForceTerm> make_history_term(const Scene& sc, const PairGeometry& p);

}  // namespace imcol::model
