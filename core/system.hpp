// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The abstract ODE/DAE system that the integrators drive (Cantera-style "function evaluator").
// Physics implements it; integrators/ wraps it in SUNDIALS. No SUNDIALS types appear here.
//
// ODE form:      y' = f(t, y)
// Residual form: F(t, y, y') = M(t, y) y' - g(t, y) = 0  (M: the added mass sits on y')
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace imcol {

/// One root function g(t, y) = 0 armed in the current phase.
struct RootSpec {
  std::string name;
  int direction = 0;  // +1 rising only, -1 falling only, 0 both
};

enum class EventAction {
  proceed,   // diagnostic only: the right-hand side did not change
  reinit,    // the right-hand side or the root set changed: re-initialise the integrator here
  stop       // the run is complete
};

/// Optional structure of a state with memory ("modal") components, used by the iterative linear
/// solver's Schur-complement preconditioner. Components [0, core) are the core. Each modal
/// component i ≥ core obeys z_i' = y'_source(i) − rate_i z_i, and the core right-hand side depends
/// on the modal components only through the sums h_g = Σ_{i in group g} gain_i z_i.
struct ModalStructure {
  std::size_t core = 0;
  std::size_t groups = 0;
  std::vector<std::size_t> source, group;  // per modal component (index i − core)
  std::vector<double> rate, gain;
};

class DynamicalSystem {
 public:
  virtual ~DynamicalSystem() = default;

  virtual std::size_t size() const = 0;
  virtual std::vector<std::string> component_names() const = 0;
  /// Per-component absolute tolerance for a dimensionless atol (atol times the component's scale).
  virtual std::vector<double> absolute_tolerances(double atol) const = 0;
  virtual void initial_state(std::span<double> y) const = 0;

  virtual void rhs(double t, std::span<const double> y, std::span<double> ydot) = 0;
  /// Residual F(t, y, y') = M(t, y) y' − g(t, y) of the implicit form (same model as rhs).
  virtual void residual(double t, std::span<const double> y, std::span<const double> yp, std::span<double> r) = 0;

  /// Roots armed in the current phase; the list may change after an event that returns reinit.
  virtual std::vector<RootSpec> roots() const = 0;
  virtual void root_values(double t, std::span<const double> y, std::span<double> g) = 0;
  /// Called once per root return with the indices (into roots()) of all roots found at t.
  /// May modify y and re-arm the roots (then it returns reinit).
  virtual EventAction on_roots(std::span<const std::size_t> found, double t, std::span<double> y) = 0;

  /// Latest time to integrate to in the current phase (t_end, or an earlier stop once measurements are complete).
  virtual double stop_time() const = 0;
  /// Largest internal step allowed from the accepted state (t, y), so that no root or sharp force can hide
  /// inside one step. Asked before every step; CVODE and IDA size a step at the end of the one before, so a
  /// new value limits the step after next.
  virtual double max_step(double t, std::span<const double> y) const = 0;

  /// Next time after t at which the integrator must stop exactly and call at_breakpoint
  /// (a fixed-step history grid, for example); +infinity if none.
  virtual double next_breakpoint(double /*t*/) const { return std::numeric_limits<double>::infinity(); }
  virtual void at_breakpoint(double /*t*/, std::span<const double> /*y*/) {}

  /// Called after every accepted internal step (t, y at its end, before the next step) and, with
  /// restart = true, at t = 0 and at each re-initialisation: a system that keeps state outside y (memory
  /// advanced step by step) updates it here. Samples inside the step come before the call.
  virtual void at_step(double /*t*/, std::span<const double> /*y*/, bool /*restart*/) {}
  /// Called once a step to (t, y) is accepted, before its samples and quadratures and before at_step: evaluations
  /// inside the step from here to at_step are outputs (the solver's own trial evaluations are over).
  virtual void step_accepted(double /*t*/, std::span<const double> /*y*/) {}

  /// Quadratures carried beside the state (integrals q' = w(t, y) the solution does not depend on, such as the work of
  /// each force): their number and integrands. They take no part in the error test or the Newton iteration.
  virtual std::size_t quadrature_size() const { return 0; }
  virtual void quadrature_rhs(double /*t*/, std::span<const double> /*y*/, std::span<double> /*qdot*/) {}

  /// Fills the modal structure at (t, y) and returns true, or returns false if the state has none.
  virtual bool modal_structure(double /*t*/, std::span<const double> /*y*/, ModalStructure& /*s*/) const { return false; }
};

/// Receives the solution: at every output time and at every event.
class Observer {
 public:
  virtual ~Observer() = default;
  virtual void sample(double t, std::span<const double> y, bool at_event) = 0;
  /// The system's quadratures at the time of the sample that follows (only for a system with quadratures).
  virtual void quadratures(std::span<const double> q) { (void)q; }
  /// After each accepted solver step: the steps taken so far in this run (for a progress display).
  virtual void stepped(long steps) { (void)steps; }
  /// After each accepted solver step that ends without an event: its end (t, y), before the system's at_step (an
  /// output of the step, as its samples).
  virtual void step_end(double t, std::span<const double> y) { (void)t, (void)y; }
};

}  // namespace imcol
