// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Time integration of a DynamicalSystem with SUNDIALS CVODE (BDF) or IDA (residual form),
// root finding, re-initialisation after events and statistics summed over re-initialisations.
#include <map>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/choices.hpp"
#include "core/system.hpp"

namespace imcol {

struct IntegratorSettings {
  IntegratorMethod method = IntegratorMethod::cvode;
  LinearSolverChoice linear_solver = LinearSolverChoice::automatic;  // dense | schur | gmres (cvode only) | auto: schur when the state is large
  double krylov_tol = 0.05;      // gmres: CVodeSetEpsLin
  int gmres_max_krylov = 5;      // gmres: Krylov subspace size
  std::size_t gmres_auto_size = 24;  // auto: schur from this state size on (cvode, modal structure present)
  double rtol = 1e-8;
  double atol = 1e-10;           // dimensionless, see DynamicalSystem::absolute_tolerances
  double output_dt = 1e-4;       // s, sampling interval passed to the observer
  long max_steps = 1000000;      // internal steps allowed between two outputs or events
  int max_order = 5;
};

struct SolverStats {
  long steps = 0;
  long rhs_evals = 0;          // right-hand side (CVODE) or residual (IDA) evaluations, incl. finite-difference Jacobians
  long jac_evals = 0;
  long nonlin_iters = 0;
  long nonlin_conv_fails = 0;
  long error_test_fails = 0;
  long root_fn_evals = 0;
  long root_events = 0;        // roots found
  long reinits = 0;
  long lin_iters = 0;          // gmres iterations
  long lin_conv_fails = 0;
  long prec_setups = 0;        // Schur-complement preconditioner set-ups (with a Jacobian evaluation)
  long prec_solves = 0;
  long breakpoints = 0;        // stops on the system's fixed grid (direct history evaluator)
  long order_caps = 0;         // restarts with the BDF order capped at 2: a ringing order 3-5 (RingingDetector)
  std::string linear_solver;   // what ran: dense | schur | gmres
  std::size_t state_size = 0;
  std::map<std::string, long> as_map() const;
  /// The counters (all but linear_solver and state_size) by name, as as_map names them.
  static const std::vector<std::pair<const char*, long SolverStats::*>>& counters();
};

/// A stateful CVODE/IDA integration of one DynamicalSystem (as Cantera's Integrator driven by ReactorNet::advance):
/// construction samples t = 0; advance(t) integrates to t or to the system's stop time, handling roots (events),
/// re-initialisations and output samples on the way; statistics are summed over re-initialisations.
/// The system's right-hand side may change between two advance() calls (a coupled force) as long as it stays
/// continuous in t; call reinit() after a discontinuous change.
class Integrator {
 public:
  Integrator(DynamicalSystem& sys, const IntegratorSettings& settings, Observer& observer);
  ~Integrator();
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  /// Integrates to min(t_target, stop_time()) and returns the time reached. Throws SolverError on failure,
  /// naming the SUNDIALS flag, the time and the state components with the largest weighted error.
  double advance(double t_target);
  /// Restarts the method at the current (t, y) (after the model changed discontinuously).
  void reinit();
  bool finished() const;  // the stop time or a stop event was reached
  double time() const;
  std::span<const double> state() const;
  SolverStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Integrates from t = 0 until the system's stop_time(). Throws SolverError on failure,
/// naming the SUNDIALS flag, the time and the state components with the largest weighted error.
SolverStats integrate(DynamicalSystem& sys, const IntegratorSettings& settings, Observer& observer);

}  // namespace imcol
