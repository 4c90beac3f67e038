// SPDX-License-Identifier: BSD-3-Clause
// CVODE / IDA driver for imcol::DynamicalSystem (SUNDIALS 6.x). The only SUNDIALS user in imcol.
#include <cvode/cvode.h>
#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_iterative.h>
#include <sundials/sundials_linearsolver.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>

#include "core/errors.hpp"
#include "integrators/integrator.hpp"
#include "integrators/step_quadrature.hpp"

#if SUNDIALS_VERSION_MAJOR != 6
#error "imcol's SUNDIALS driver is written for SUNDIALS 6.x"
#endif

namespace imcol {

const std::vector<std::pair<const char*, long SolverStats::*>>& SolverStats::counters() {
  static const std::vector<std::pair<const char*, long SolverStats::*>> list = {
      {"steps", &SolverStats::steps},
      {"rhs_evals", &SolverStats::rhs_evals},
      {"jac_evals", &SolverStats::jac_evals},
      {"nonlin_iters", &SolverStats::nonlin_iters},
      {"nonlin_conv_fails", &SolverStats::nonlin_conv_fails},
      {"error_test_fails", &SolverStats::error_test_fails},
      {"root_fn_evals", &SolverStats::root_fn_evals},
      {"root_events", &SolverStats::root_events},
      {"reinits", &SolverStats::reinits},
      {"lin_iters", &SolverStats::lin_iters},
      {"lin_conv_fails", &SolverStats::lin_conv_fails},
      {"prec_setups", &SolverStats::prec_setups},
      {"prec_solves", &SolverStats::prec_solves},
      {"breakpoints", &SolverStats::breakpoints},
      {"order_caps", &SolverStats::order_caps}};
  return list;
}

std::map<std::string, long> SolverStats::as_map() const {
  std::map<std::string, long> m;
  for (const auto& [name, field] : counters()) m[name] = this->*field;
  m["state_size"] = static_cast<long>(state_size);
  return m;
}

namespace {

std::span<const double> view(N_Vector v) { return {N_VGetArrayPointer(v), static_cast<std::size_t>(N_VGetLength(v))}; }
std::span<double> mview(N_Vector v) { return {N_VGetArrayPointer(v), static_cast<std::size_t>(N_VGetLength(v))}; }

/// Exact solve of the Newton matrix I − γJ for a state with modal (memory) components
/// (DynamicalSystem::ModalStructure). With δh_g = Σ_{i∈g} gain_i δz_i, the modal rows give
///   δz_i = (r_i + γ q_g)/(1 + γ λ_i),  q_g = (J_pp δp)_src(g) + Σ_g' B_src(g),g' δh_g',
/// with B = ∂f_core/∂h. Eliminating δz leaves a (core + groups) dense system (the Schur complement):
///   (I − γJ_pp) δp − γ B δh = r_p,   δh_g − γ σ_g q_g = ρ_g,
///   σ_g = Σ_{i∈g} gain_i/(1 + γλ_i),  ρ_g = Σ_{i∈g} gain_i r_i/(1 + γλ_i).
/// J_pp and B come from core + groups finite differences of the right-hand side, so a set-up costs
/// O(core + groups) evaluations however many modes there are; as a left preconditioner for GMRES it
/// is exact up to the age of the Jacobian.
class SchurPreconditioner {
 public:
  void setup(DynamicalSystem& sys, double t, std::span<const double> y, std::span<const double> fy,
             std::span<const double> atol) {
    if (!sys.modal_structure(t, y, ms_)) throw SolverError("gmres: the system has no modal structure for the preconditioner");
    const std::size_t n = y.size(), p = ms_.core, S = ms_.groups;
    src_.assign(S, 0);
    for (std::size_t i = 0; i < ms_.source.size(); ++i) src_[ms_.group[i]] = ms_.source[i];
    std::vector<double> yt(y.begin(), y.end()), ft(n);
    const double sqeps = std::sqrt(std::numeric_limits<double>::epsilon());
    Jpp_.resize(p, p);
    B_.resize(p, S);
    for (std::size_t j = 0; j < p; ++j) {
      const double inc = sqeps * std::max(std::abs(y[j]), atol[j]);
      yt[j] = y[j] + inc;
      sys.rhs(t, yt, ft);
      yt[j] = y[j];
      for (std::size_t k = 0; k < p; ++k) Jpp_(k, j) = (ft[k] - fy[k]) / inc;
    }
    for (std::size_t g = 0; g < S; ++g) {
      // Perturb the mode of this group with the largest gain so that h_g changes by `inc`.
      std::size_t best = n;
      double hg = 0, scale = 0;
      for (std::size_t i = 0; i < ms_.gain.size(); ++i) {
        if (ms_.group[i] != g) continue;
        hg += ms_.gain[i] * y[p + i];
        scale += std::abs(ms_.gain[i]) * atol[p + i];
        if (best == n || std::abs(ms_.gain[i]) > std::abs(ms_.gain[best - p])) best = p + i;
      }
      B_.col(g).setZero();
      if (best == n || ms_.gain[best - p] == 0) continue;
      const double inc = sqeps * std::max(std::abs(hg), scale);
      const double dz = inc / ms_.gain[best - p];
      yt[best] = y[best] + dz;
      sys.rhs(t, yt, ft);
      yt[best] = y[best];
      for (std::size_t k = 0; k < p; ++k) B_(k, g) = (ft[k] - fy[k]) / inc;
    }
    gamma_ = -1;  // force a refactorisation
  }

  /// Solves (I − γJ) x = r.
  void solve(std::span<const double> r, std::span<double> x, double gamma) {
    const std::size_t p = ms_.core, S = ms_.groups, nm = ms_.rate.size();
    if (gamma != gamma_) factor(gamma);
    rhs_.resize(p + S);
    q_.resize(S);
    for (std::size_t k = 0; k < p; ++k) rhs_[k] = r[k];
    for (std::size_t g = 0; g < S; ++g) rhs_[p + g] = 0;
    for (std::size_t i = 0; i < nm; ++i) rhs_[p + ms_.group[i]] += ms_.gain[i] * r[p + i] * inv_[i];
    sol_.noalias() = lu_.solve(rhs_);
    for (std::size_t g = 0; g < S; ++g) {
      double v = 0;
      for (std::size_t l = 0; l < p; ++l) v += Jpp_(src_[g], l) * sol_[l];
      for (std::size_t h = 0; h < S; ++h) v += B_(src_[g], h) * sol_[p + h];
      q_[g] = gamma * v;
    }
    for (std::size_t k = 0; k < p; ++k) x[k] = sol_[k];
    for (std::size_t i = 0; i < nm; ++i) x[p + i] = (r[p + i] + q_[ms_.group[i]]) * inv_[i];
  }

 private:
  void factor(double gamma) {
    const std::size_t p = ms_.core, S = ms_.groups;
    std::vector<double> sigma(S, 0.0);
    inv_.resize(ms_.rate.size());
    for (std::size_t i = 0; i < ms_.rate.size(); ++i) {
      inv_[i] = 1 / (1 + gamma * ms_.rate[i]);
      sigma[ms_.group[i]] += ms_.gain[i] * inv_[i];
    }
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(p + S, p + S);
    A.topLeftCorner(p, p) = Eigen::MatrixXd::Identity(p, p) - gamma * Jpp_;
    A.topRightCorner(p, S) = -gamma * B_;
    for (std::size_t g = 0; g < S; ++g) {
      A.block(p + g, 0, 1, p) = -gamma * sigma[g] * Jpp_.row(src_[g]);
      A.block(p + g, p, 1, S) = -gamma * sigma[g] * B_.row(src_[g]);
      A(p + g, p + g) += 1.0;
    }
    lu_.compute(A);
    gamma_ = gamma;
  }

  ModalStructure ms_;
  std::vector<std::size_t> src_;
  Eigen::MatrixXd Jpp_, B_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  Eigen::VectorXd rhs_, sol_;       // solve() scratch
  std::vector<double> q_, inv_;     // inv_i = 1/(1 + γλ_i) at the factored γ
  double gamma_ = -1;
};

/// The `schur` linear solver: CVODE sees an iterative solver (so it keeps its Jacobian-age heuristics
/// and hands over the current γ), but the solve is one application of the exact Schur-complement solve
/// above, without Krylov iterations (GMRES converged in about one, which cost a second solve, a J·v
/// product and the orthogonalisation).
struct SchurDirectContent {
  void* P_data = nullptr;
  SUNPSetupFn pset = nullptr;
  SUNPSolveFn psol = nullptr;
  int last_flag = 0;
};
SchurDirectContent* schur_content(SUNLinearSolver S) { return static_cast<SchurDirectContent*>(S->content); }

SUNLinearSolver make_schur_direct(SUNContext ctx) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  S->content = new SchurDirectContent;
  S->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_ITERATIVE; };
  S->ops->setatimes = [](SUNLinearSolver, void*, SUNATimesFn) { return 0; };
  S->ops->setpreconditioner = [](SUNLinearSolver S, void* P, SUNPSetupFn ps, SUNPSolveFn pv) {
    auto* c = schur_content(S);
    c->P_data = P, c->pset = ps, c->psol = pv;
    return 0;
  };
  S->ops->setscalingvectors = [](SUNLinearSolver, N_Vector, N_Vector) { return 0; };
  S->ops->setzeroguess = [](SUNLinearSolver, sunbooleantype) { return 0; };
  S->ops->initialize = [](SUNLinearSolver) { return 0; };
  S->ops->setup = [](SUNLinearSolver S, SUNMatrix) {
    auto* c = schur_content(S);
    c->last_flag = c->pset ? c->pset(c->P_data) : 0;
    return c->last_flag == 0 ? 0 : (c->last_flag < 0 ? SUNLS_PSET_FAIL_UNREC : SUNLS_PSET_FAIL_REC);
  };
  S->ops->solve = [](SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, sunrealtype tol) {
    auto* c = schur_content(S);
    c->last_flag = c->psol(c->P_data, b, x, tol, SUN_PREC_LEFT);
    return c->last_flag == 0 ? 0 : (c->last_flag < 0 ? SUNLS_PSOLVE_FAIL_UNREC : SUNLS_PSOLVE_FAIL_REC);
  };
  S->ops->numiters = [](SUNLinearSolver) { return 0; };
  S->ops->lastflag = [](SUNLinearSolver S) { return static_cast<sunindextype>(schur_content(S)->last_flag); };
  S->ops->free = [](SUNLinearSolver S) {
    if (!S) return 0;
    delete schur_content(S);
    S->content = nullptr;
    SUNLinSolFreeEmpty(S);
    return 0;
  };
  return S;
}

/// State shared with the C callbacks. Exceptions never cross SUNDIALS: they are stored and rethrown.
struct Callback {
  DynamicalSystem* sys;
  SchurPreconditioner* prec = nullptr;
  std::vector<double> atol;
  std::size_t nroots = 0;  // roots armed now
  std::exception_ptr error;
  std::string last_message;

  template <class F>
  int guard(F&& f) {
    try {
      f();
      return 0;
    } catch (...) {
      error = std::current_exception();
      return -1;
    }
  }
};

void error_handler(int code, const char* module, const char* function, char* msg, void* data) {
  auto* cb = static_cast<Callback*>(data);
  std::ostringstream os;
  os << module << "/" << function << " (" << code << "): " << msg;
  cb->last_message = os.str();
}

int cv_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
  auto* cb = static_cast<Callback*>(data);
  return cb->guard([&] { cb->sys->rhs(t, view(y), mview(ydot)); });
}
int cv_psetup(sunrealtype t, N_Vector y, N_Vector fy, sunbooleantype jok, sunbooleantype* jcur, sunrealtype gamma,
              void* data) {
  auto* cb = static_cast<Callback*>(data);
  (void)gamma;
  return cb->guard([&] {
    if (jok) {
      *jcur = SUNFALSE;
      return;
    }
    cb->prec->setup(*cb->sys, t, view(y), view(fy), cb->atol);
    *jcur = SUNTRUE;
  });
}
int cv_psolve(sunrealtype, N_Vector, N_Vector, N_Vector r, N_Vector z, sunrealtype gamma, sunrealtype, int,
              void* data) {
  auto* cb = static_cast<Callback*>(data);
  return cb->guard([&] { cb->prec->solve(view(r), mview(z), gamma); });
}
int cv_root(sunrealtype t, N_Vector y, sunrealtype* g, void* data) {
  auto* cb = static_cast<Callback*>(data);
  return cb->guard([&] { cb->sys->root_values(t, view(y), {g, cb->nroots}); });
}
int ida_res(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, void* data) {
  auto* cb = static_cast<Callback*>(data);
  return cb->guard([&] { cb->sys->residual(t, view(y), view(yp), mview(r)); });
}
int ida_root(sunrealtype t, N_Vector y, N_Vector, sunrealtype* g, void* data) {
  auto* cb = static_cast<Callback*>(data);
  return cb->guard([&] { cb->sys->root_values(t, view(y), {g, cb->nroots}); });
}

void check(int flag, const char* call) {
  if (flag < 0) throw SolverError(std::string("SUNDIALS setup call ") + call + " failed with flag " + std::to_string(flag));
}

std::vector<int> root_directions(const std::vector<RootSpec>& roots) {
  std::vector<int> dir;
  for (const auto& r : roots) dir.push_back(r.direction);
  return dir;
}

/// The operations the event loop needs, implemented once for CVODE and once for IDA. Every call takes one
/// internal step (CV_ONE_STEP / IDA_ONE_STEP), so solver.max_steps is the loop's own count (quiet_steps), not
/// CVodeSetMaxNumSteps (which counts steps within one call).
class Backend {
 public:
  virtual ~Backend() = default;
  virtual void init(double t, N_Vector y) = 0;  // (re)initialise at (t, y)
  virtual void set_roots(const std::vector<RootSpec>& roots) = 0;
  /// One internal step toward tstop (tout only sizes the first step after an initialisation):
  /// >0 a root at t (y = y(t)), 0 a step to t = the internal time (y = y(t)), <0 failure.
  virtual int step(double tout, double tstop, N_Vector y, double& t) = 0;
  /// The solver's interpolant at t within the last step (CVodeGetDky / IDAGetDky).
  virtual void interpolate(double t, N_Vector y) = 0;
  virtual double internal_time() = 0;
  virtual void set_max_step(double h) = 0;
  virtual int too_much_work() = 0;  // the solver's flag for more than max_steps steps between two returns
  virtual void root_info(int* found) = 0;
  virtual void add_stats(SolverStats& s) = 0;
  virtual std::string flag_name(int flag) = 0;
  virtual void error_vectors(N_Vector w, N_Vector e) = 0;
  virtual int last_order() = 0;              // the BDF order of the last step
  virtual void set_max_order(int q) = 0;     // at most the order the solver was created with
};

class CvodeBackend : public Backend {
 public:
  CvodeBackend(SUNContext ctx, Callback& cb, const IntegratorSettings& st, N_Vector y, N_Vector abstol)
      : cb_(cb), abstol_(abstol) {
    mem_ = CVodeCreate(CV_BDF, ctx);
    if (!mem_) throw SolverError("CVodeCreate failed");
    check(CVodeSetErrHandlerFn(mem_, error_handler, &cb_), "CVodeSetErrHandlerFn");
    check(CVodeInit(mem_, cv_rhs, 0.0, y), "CVodeInit");
    check(CVodeSetUserData(mem_, &cb_), "CVodeSetUserData");
    check(CVodeSVtolerances(mem_, st.rtol, abstol_), "CVodeSVtolerances");
    if (cb_.prec) {
      const bool direct = st.linear_solver == LinearSolverChoice::schur;
      LS_ = direct ? make_schur_direct(ctx) : SUNLinSol_SPGMR(y, SUN_PREC_LEFT, st.gmres_max_krylov, ctx);
      if (!LS_) throw SolverError("creating the linear solver failed");
      check(CVodeSetLinearSolver(mem_, LS_, nullptr), "CVodeSetLinearSolver");
      check(CVodeSetPreconditioner(mem_, cv_psetup, cv_psolve), "CVodeSetPreconditioner");
      if (!direct) check(CVodeSetEpsLin(mem_, st.krylov_tol), "CVodeSetEpsLin");
    } else {
      A_ = SUNDenseMatrix(N_VGetLength(y), N_VGetLength(y), ctx);
      LS_ = SUNLinSol_Dense(y, A_, ctx);
      check(CVodeSetLinearSolver(mem_, LS_, A_), "CVodeSetLinearSolver");
    }
    check(CVodeSetMaxOrd(mem_, st.max_order), "CVodeSetMaxOrd");
    check(CVodeSetNoInactiveRootWarn(mem_), "CVodeSetNoInactiveRootWarn");
  }
  ~CvodeBackend() override {
    CVodeFree(&mem_);
    SUNLinSolFree(LS_);
    if (A_) SUNMatDestroy(A_);
  }
  void init(double t, N_Vector y) override {
    check(CVodeReInit(mem_, t, y), "CVodeReInit");
  }
  void set_roots(const std::vector<RootSpec>& roots) override {
    cb_.nroots = roots.size();
    check(CVodeRootInit(mem_, static_cast<int>(roots.size()), roots.empty() ? nullptr : cv_root), "CVodeRootInit");
    if (roots.empty()) return;
    std::vector<int> dir = root_directions(roots);
    check(CVodeSetRootDirection(mem_, dir.data()), "CVodeSetRootDirection");
  }
  int step(double tout, double tstop, N_Vector y, double& t) override {
    check(CVodeSetStopTime(mem_, tstop), "CVodeSetStopTime");
    int flag = CVode(mem_, tout, y, &t, CV_ONE_STEP);
    if (flag == CV_ROOT_RETURN) return 1;
    return flag < 0 ? flag : 0;
  }
  void interpolate(double t, N_Vector y) override { check(CVodeGetDky(mem_, t, 0, y), "CVodeGetDky"); }
  double internal_time() override {
    double t = 0;
    CVodeGetCurrentTime(mem_, &t);
    return t;
  }
  void set_max_step(double h) override { check(CVodeSetMaxStep(mem_, h), "CVodeSetMaxStep"); }
  int too_much_work() override { return CV_TOO_MUCH_WORK; }
  int last_order() override {
    int q = 0;
    CVodeGetLastOrder(mem_, &q);
    return q;
  }
  void set_max_order(int q) override { check(CVodeSetMaxOrd(mem_, q), "CVodeSetMaxOrd"); }
  void root_info(int* found) override { CVodeGetRootInfo(mem_, found); }
  void add_stats(SolverStats& s) override {
    long v = 0;
    CVodeGetNumSteps(mem_, &v); s.steps += v;
    CVodeGetNumRhsEvals(mem_, &v); s.rhs_evals += v;
    CVodeGetNumLinRhsEvals(mem_, &v); s.rhs_evals += v;
    CVodeGetNumJacEvals(mem_, &v); s.jac_evals += v;
    CVodeGetNumNonlinSolvIters(mem_, &v); s.nonlin_iters += v;
    CVodeGetNumNonlinSolvConvFails(mem_, &v); s.nonlin_conv_fails += v;
    CVodeGetNumErrTestFails(mem_, &v); s.error_test_fails += v;
    CVodeGetNumGEvals(mem_, &v); s.root_fn_evals += v;
    if (!cb_.prec) return;
    CVodeGetNumLinIters(mem_, &v); s.lin_iters += v;
    CVodeGetNumLinConvFails(mem_, &v); s.lin_conv_fails += v;
    CVodeGetNumPrecEvals(mem_, &v); s.prec_setups += v;
    CVodeGetNumPrecSolves(mem_, &v); s.prec_solves += v;
  }
  std::string flag_name(int flag) override {
    char* name = CVodeGetReturnFlagName(flag);
    std::string s = name ? name : "?";
    free(name);
    return s;
  }
  void error_vectors(N_Vector w, N_Vector e) override {
    CVodeGetErrWeights(mem_, w);
    CVodeGetEstLocalErrors(mem_, e);
  }

 private:
  Callback& cb_;
  N_Vector abstol_;
  void* mem_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver LS_ = nullptr;
};

class IdaBackend : public Backend {
 public:
  IdaBackend(SUNContext ctx, Callback& cb, const IntegratorSettings& st, N_Vector y, N_Vector abstol)
      : cb_(cb), abstol_(abstol) {
    yp_ = N_VClone(y);
    consistent_yp(0.0, y);
    mem_ = IDACreate(ctx);
    if (!mem_) throw SolverError("IDACreate failed");
    check(IDASetErrHandlerFn(mem_, error_handler, &cb_), "IDASetErrHandlerFn");
    check(IDAInit(mem_, ida_res, 0.0, y, yp_), "IDAInit");
    check(IDASetUserData(mem_, &cb_), "IDASetUserData");
    check(IDASVtolerances(mem_, st.rtol, abstol_), "IDASVtolerances");
    A_ = SUNDenseMatrix(N_VGetLength(y), N_VGetLength(y), ctx);
    LS_ = SUNLinSol_Dense(y, A_, ctx);
    check(IDASetLinearSolver(mem_, LS_, A_), "IDASetLinearSolver");
    check(IDASetMaxOrd(mem_, st.max_order), "IDASetMaxOrd");
    check(IDASetNoInactiveRootWarn(mem_), "IDASetNoInactiveRootWarn");
  }
  ~IdaBackend() override {
    IDAFree(&mem_);
    SUNLinSolFree(LS_);
    SUNMatDestroy(A_);
    N_VDestroy(yp_);
  }
  void init(double t, N_Vector y) override {
    consistent_yp(t, y);
    check(IDAReInit(mem_, t, y, yp_), "IDAReInit");
  }
  void set_roots(const std::vector<RootSpec>& roots) override {
    cb_.nroots = roots.size();
    check(IDARootInit(mem_, static_cast<int>(roots.size()), roots.empty() ? nullptr : ida_root), "IDARootInit");
    if (roots.empty()) return;
    std::vector<int> dir = root_directions(roots);
    check(IDASetRootDirection(mem_, dir.data()), "IDASetRootDirection");
  }
  int step(double tout, double tstop, N_Vector y, double& t) override {
    check(IDASetStopTime(mem_, tstop), "IDASetStopTime");
    int flag = IDASolve(mem_, tout, &t, y, yp_, IDA_ONE_STEP);
    if (flag == IDA_ROOT_RETURN) return 1;
    return flag < 0 ? flag : 0;
  }
  void interpolate(double t, N_Vector y) override { check(IDAGetDky(mem_, t, 0, y), "IDAGetDky"); }
  double internal_time() override {
    double t = 0;
    IDAGetCurrentTime(mem_, &t);
    return t;
  }
  void set_max_step(double h) override { check(IDASetMaxStep(mem_, h), "IDASetMaxStep"); }
  int too_much_work() override { return IDA_TOO_MUCH_WORK; }
  int last_order() override {
    int q = 0;
    IDAGetLastOrder(mem_, &q);
    return q;
  }
  void set_max_order(int q) override { check(IDASetMaxOrd(mem_, q), "IDASetMaxOrd"); }
  void root_info(int* found) override { IDAGetRootInfo(mem_, found); }
  void add_stats(SolverStats& s) override {
    long v = 0;
    IDAGetNumSteps(mem_, &v); s.steps += v;
    IDAGetNumResEvals(mem_, &v); s.rhs_evals += v;
    IDAGetNumLinResEvals(mem_, &v); s.rhs_evals += v;
    IDAGetNumJacEvals(mem_, &v); s.jac_evals += v;
    IDAGetNumNonlinSolvIters(mem_, &v); s.nonlin_iters += v;
    IDAGetNumNonlinSolvConvFails(mem_, &v); s.nonlin_conv_fails += v;
    IDAGetNumErrTestFails(mem_, &v); s.error_test_fails += v;
    IDAGetNumGEvals(mem_, &v); s.root_fn_evals += v;
  }
  std::string flag_name(int flag) override {
    char* name = IDAGetReturnFlagName(flag);
    std::string s = name ? name : "?";
    free(name);
    return s;
  }
  void error_vectors(N_Vector w, N_Vector e) override {
    IDAGetErrWeights(mem_, w);
    IDAGetEstLocalErrors(mem_, e);
  }

 private:
  void consistent_yp(double t, N_Vector y) { cb_.sys->rhs(t, view(y), mview(yp_)); }
  Callback& cb_;
  N_Vector abstol_;
  N_Vector yp_ = nullptr;
  void* mem_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver LS_ = nullptr;
};

struct ContextDeleter {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;

}  // namespace

/// A lightly damped stiff oscillation that a BDF method of order 3 to 5 sustains instead of damping (those orders are not
/// A-stable: near the imaginary axis they amplify, e.g. a resting contact whose only damping is the liquid film, ζ ~ 1e-3).
/// The error test then holds the amplitude at the tolerance and the steps at a fraction of its period, to t_end. The
/// sign: some component's step increment reverses at least kReversals times in each of kWindows consecutive windows of
/// kWindow steps, all taken at order ≥ 3 (increments below the component's absolute tolerance do not count).
class RingingDetector {
 public:
  static constexpr int kWindow = 50, kReversals = 5, kWindows = 5;
  void reset() {
    prev_.clear();
    in_window_ = rung_ = 0;
  }
  /// After an accepted step to y at order q: whether the solution has been ringing at order ≥ 3.
  bool step(std::span<const double> y, std::span<const double> atol, int q) {
    if (q < 3) {
      reset();
      return false;
    }
    if (prev_.size() != y.size()) {
      prev_.assign(y.begin(), y.end());
      sign_.assign(y.size(), 0);
      count_.assign(y.size(), 0);
      in_window_ = 0;
      return false;
    }
    for (std::size_t i = 0; i < y.size(); ++i) {
      const double d = y[i] - prev_[i];
      prev_[i] = y[i];
      if (!(std::abs(d) > atol[i])) continue;
      const int s = d > 0 ? 1 : -1;
      if (sign_[i] != 0 && s != sign_[i]) ++count_[i];
      sign_[i] = s;
    }
    if (++in_window_ < kWindow) return false;
    const bool rang = std::any_of(count_.begin(), count_.end(), [](int c) { return c >= kReversals; });
    std::fill(count_.begin(), count_.end(), 0);
    in_window_ = 0;
    rung_ = rang ? rung_ + 1 : 0;
    return rung_ >= kWindows;
  }

 private:
  std::vector<double> prev_;
  std::vector<int> sign_, count_;
  int in_window_ = 0, rung_ = 0;
};

struct Integrator::Impl {
  Impl(DynamicalSystem& s, const IntegratorSettings& settings, Observer& o) : sys(s), st(settings), observer(o), quad(s) {}
  DynamicalSystem& sys;
  IntegratorSettings st;
  Observer& observer;
  std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter> ctx;
  VectorPtr y, abstol, yi;  // yi: interpolated output samples
  StepQuadrature quad;      // the system's quadratures, if any
  VectorPtr y_mid;          // the state in the middle of a step (quad)
  Callback cb{};
  SchurPreconditioner prec;
  std::unique_ptr<Backend> be;
  SolverStats stats;
  std::vector<std::string> names;
  double t = 0.0;
  long k_out = 1;  // output times k·dt, counted so that they cannot stop advancing
  double t_sampled = -1;  // time of the last output sample
  long quiet_steps = 0;   // internal steps since the last output sample, event or stop (solver.max_steps bounds them)
  double max_step = 0;    // the value last passed to the solver (it persists across re-initialisations); 0: none yet
  long steps_taken = 0;   // accepted internal steps of this run (for the observer's progress display)
  std::vector<double> g;  // root values (root_exactly_zero)
  bool done = false;
  RingingDetector ringing;
  std::vector<double> atol;  // per component, for the detector
  bool order_capped = false;  // BDF order at most 2 until the next event's re-initialisation

  /// The events found at the step to t: samples them and lets the system act. True when the run stops there.
  bool on_roots() {
    std::vector<int> flags(sys.roots().size(), 0);
    be->root_info(flags.data());
    std::vector<std::size_t> found;
    for (std::size_t i = 0; i < flags.size(); ++i)
      if (flags[i]) found.push_back(i);
    stats.root_events += static_cast<long>(found.size());
    give_quadratures(quad.value());
    observer.sample(t, view(y.get()), true);
    const EventAction action = sys.on_roots(found, t, mview(y.get()));
    if (action == EventAction::stop) return done = true;
    // A root function exactly zero here (a gap or speed that moves so slowly that its change over the solver's
    // smallest step is below rounding) would be found again at t + ε on the next step, which CVODE and IDA refuse
    // ("Root found at and very near t", *_ILL_INPUT). A restart here lets them hold it inactive until it leaves 0.
    if (action == EventAction::reinit || root_exactly_zero()) restart(false);
    return false;
  }

  /// Re-initialises at (t, y); `cap`: with the BDF order at most 2 (ringing), else with the settings' maximum order.
  void restart(bool cap) {
    be->add_stats(stats);
    ++stats.reinits;
    const int q = cap ? std::min(2, st.max_order) : st.max_order;
    if (cap != order_capped) be->set_max_order(q);
    order_capped = cap;
    ringing.reset();
    sys.at_step(t, view(y.get()), true);
    quad.restart(t, view(y.get()));
    be->init(t, y.get());
    be->set_roots(sys.roots());
  }

  /// Passes the quadratures to the observer before a sample (nothing without quadratures).
  void give_quadratures(std::span<const double> q) {
    if (quad.active()) observer.quadratures(q);
  }
  /// A sample of the state y at t (not an event), with its quadratures.
  void sample_at(double t_s) {
    give_quadratures(quad.value());
    observer.sample(t_s, view(y.get()), false);
  }
  /// Integrates the quadratures over the last step, from t to t1 (y1 = y(t1)).
  void integrate_quadratures(double t1, N_Vector y1) {
    if (!quad.active() || !(t1 > t)) return;
    be->interpolate(0.5 * (t + t1), y_mid.get());
    quad.advance(t1, view(y1), view(y_mid.get()));
  }

  /// Samples the output times k·dt in (t, t_upto) (strict) or (t, t_upto] from the solver's interpolant,
  /// without stopping the solver there. If the system's stop time falls to a sample (the observer ended the
  /// run), the state becomes the one at that sample and true is returned.
  /// Not strict, an output time less than t_eps after t_upto counts as reached at t_upto, as everywhere in the loop
  /// (the next step starts there and would pass it unsampled): it is sampled under its time k·dt with the state at
  /// t_upto. So a stop a rounding short of the output grid (a breakpoint kΔ, a coupled run's target n·Δt) keeps the
  /// output times of a run that does not stop there. The stop time is left to advance(), which samples the end.
  bool emit_outputs(double t_upto, bool strict) {
    const double t_eps = 1e-12 * std::max(1.0, std::abs(t));
    const double eps_upto = 1e-12 * std::max(1.0, std::abs(t_upto));
    while (k_out * st.output_dt <= t + t_eps) ++k_out;
    for (;; ++k_out) {
      const double tau = k_out * st.output_dt;
      const bool in_step = strict ? tau < t_upto : tau <= t_upto;
      if (!in_step && (strict || tau > t_upto + eps_upto || t_upto >= sys.stop_time() - eps_upto)) return false;
      be->interpolate(in_step ? tau : t_upto, yi.get());
      if (quad.active()) give_quadratures(quad.at(in_step ? tau : t_upto));
      observer.sample(tau, view(yi.get()), false);
      t_sampled = tau;
      if (tau >= sys.stop_time() - 1e-12 * std::max(1.0, std::abs(tau))) {
        if (in_step) quad.end_at(tau, view(yi.get()));
        N_VScale(1.0, yi.get(), y.get());
        t = tau;
        ++k_out;
        return true;
      }
    }
  }

  /// Whether an armed root function is exactly zero at the current (t, y).
  bool root_exactly_zero() {
    const std::size_t n = sys.roots().size();
    if (n == 0) return false;
    g.assign(n, 1.0);
    sys.root_values(t, view(y.get()), g);
    return std::any_of(g.begin(), g.end(), [](double v) { return v == 0.0; });
  }

  /// An exception from the model: input and solver errors pass through (a solver error given the integrator's facts
  /// if it has none), anything else becomes a SolverError that says where it happened.
  [[noreturn]] void rethrow_model_error(int flag = 0) {
    const auto err = cb.error;
    cb.error = nullptr;
    try {
      std::rethrow_exception(err);
    } catch (const InputError&) {
      throw;
    } catch (const SolverError& e) {
      if (e.failure()) throw;
      throw SolverError(e.what(), failure(flag));  // the same message, with the integrator's facts
    } catch (const std::exception& e) {
      std::ostringstream os;
      os << to_string(st.method) << ": the model failed near t = " << t << " s: " << e.what();
      throw SolverError(os.str(), failure(flag));
    }
  }
  /// The facts of a failure at (t, y): the integrator, the flag (0: none) and the state.
  SolverFailure failure(int flag) {
    SolverFailure f;
    f.integrator = to_string(st.method);
    f.flag = flag;
    if (flag != 0) f.flag_name = be->flag_name(flag);
    f.time = t;
    f.names = names;
    const auto ys = view(y.get());
    f.state.assign(ys.begin(), ys.end());
    return f;
  }
  [[noreturn]] void fail(int flag) {
    if (cb.error) rethrow_model_error(flag);
    SolverFailure f = failure(flag);
    VectorPtr w(N_VClone(y.get())), e(N_VClone(y.get()));
    be->error_vectors(w.get(), e.get());
    auto ws = view(w.get()), es = view(e.get());
    std::vector<std::size_t> idx(ws.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](auto a, auto b) { return std::abs(ws[a] * es[a]) > std::abs(ws[b] * es[b]); });
    for (std::size_t k = 0; k < std::min<std::size_t>(3, idx.size()); ++k)
      f.local_errors.emplace_back(names[idx[k]], std::abs(ws[idx[k]] * es[idx[k]]));
    std::ostringstream os;
    os << f.integrator << " failed at t = " << f.time << " s with " << f.flag_name;
    if (!cb.last_message.empty()) os << " [" << cb.last_message << "]";
    os << "; largest weighted local errors:";
    for (const auto& [name, err] : f.local_errors) os << " " << name << "=" << err;
    throw SolverError(os.str(), std::move(f));
  }
};

Integrator::Integrator(DynamicalSystem& sys, const IntegratorSettings& st, Observer& observer)
    : impl_(std::make_unique<Impl>(sys, st, observer)) {
  auto& m = *impl_;
  if (!(st.rtol > 0) || !(st.atol > 0)) throw SolverError("tolerances must be positive");
  if (!(st.output_dt > 0)) throw SolverError("output interval must be positive");
  SUNContext raw = nullptr;
  if (SUNContext_Create(nullptr, &raw) != 0) throw SolverError("SUNContext_Create failed");
  m.ctx.reset(raw);

  const auto n = static_cast<sunindextype>(sys.size());
  m.y.reset(N_VNew_Serial(n, m.ctx.get()));
  m.abstol.reset(N_VNew_Serial(n, m.ctx.get()));
  m.yi.reset(N_VNew_Serial(n, m.ctx.get()));
  sys.initial_state(mview(m.y.get()));
  auto tol = sys.absolute_tolerances(st.atol);
  std::copy(tol.begin(), tol.end(), mview(m.abstol.get()).begin());
  m.atol = tol;

  m.cb = Callback{&sys, nullptr, {tol.begin(), tol.end()}, 0, nullptr, {}};
  ModalStructure probe;
  const bool modal = sys.modal_structure(0.0, view(m.y.get()), probe);
  using LS = LinearSolverChoice;
  LS ls = st.linear_solver;
  const bool cvode = st.method == IntegratorMethod::cvode;
  if (ls == LS::automatic) ls = (cvode && modal && sys.size() >= st.gmres_auto_size) ? LS::schur : LS::dense;
  if (ls == LS::gmres || ls == LS::schur) {
    const std::string name = to_string(ls);
    if (!cvode) throw SolverError("the " + name + " linear solver is implemented for cvode only");
    if (!modal) throw SolverError("the " + name + " linear solver needs memory modes in the integrator's state: the history effect with history.evaluator = \"soe\"");
    m.cb.prec = &m.prec;
  }
  m.st.linear_solver = ls;
  if (cvode) m.be = std::make_unique<CvodeBackend>(m.ctx.get(), m.cb, m.st, m.y.get(), m.abstol.get());
  else m.be = std::make_unique<IdaBackend>(m.ctx.get(), m.cb, m.st, m.y.get(), m.abstol.get());

  m.stats.linear_solver = to_string(ls);
  m.stats.state_size = sys.size();
  m.names = sys.component_names();
  m.be->init(m.t, m.y.get());
  m.be->set_roots(sys.roots());
  sys.at_step(m.t, view(m.y.get()), true);
  if (m.quad.active()) {
    m.y_mid.reset(N_VNew_Serial(n, m.ctx.get()));
    m.quad.restart(m.t, view(m.y.get()));
  }
  m.give_quadratures(m.quad.value());
  observer.sample(m.t, view(m.y.get()), true);
}

Integrator::~Integrator() = default;

double Integrator::time() const { return impl_->t; }
bool Integrator::finished() const { return impl_->done; }
std::span<const double> Integrator::state() const { return view(impl_->y.get()); }

SolverStats Integrator::stats() const {
  SolverStats s = impl_->stats;
  impl_->be->add_stats(s);  // the counters since the last re-initialisation
  return s;
}

void Integrator::reinit() { impl_->restart(false); }

double Integrator::advance(double t_target) {
  auto& m = *impl_;
  auto& sys = m.sys;
  auto& be = m.be;
  double& t = m.t;
  // One internal step per solver call (CV_ONE_STEP / IDA_ONE_STEP): the output samples are interpolated
  // (CVodeGetDky / IDAGetDky) within each step, so the output grid never makes the solver return.
  while (!m.done) {
    const double t_eps = 1e-12 * std::max(1.0, std::abs(t));  // times closer than this count as reached
    const double tstop = sys.stop_time();
    if ((m.done = t >= tstop - t_eps) || t >= t_target - t_eps) break;  // the stop time ends the run; t_target, the call
    const double bp = sys.next_breakpoint(t);
    const double t_limit = std::min({tstop, bp, t_target});
    double t_new = t;
    int flag = 0;
    if (t_limit < be->internal_time()) {
      // The solver has stepped past t_limit (an event or a sample moved the stop time back, which CVODE's
      // stop time cannot follow): the samples and the state at t_limit come from its interpolant.
      t_new = t_limit;
      be->interpolate(t_new, m.yi.get());
      sys.step_accepted(t_new, view(m.yi.get()));
      m.integrate_quadratures(t_new, m.yi.get());
      if (m.emit_outputs(t_new, false)) continue;
      be->interpolate(t_new, m.y.get());
    } else {
      while (m.k_out * m.st.output_dt <= t + t_eps) ++m.k_out;
      const double tout = std::min(m.k_out * m.st.output_dt, t_limit);  // sizes the first step after a (re)start
      if (m.quiet_steps >= m.st.max_steps) m.fail(be->too_much_work());
      const double h_max = sys.max_step(t, view(m.y.get()));
      if (h_max != m.max_step) be->set_max_step(m.max_step = h_max);
      flag = be->step(tout, t_limit, m.y.get(), t_new);
      if (flag < 0) m.fail(flag);
      if (m.cb.error) m.rethrow_model_error();
      sys.step_accepted(t_new, view(m.y.get()));
      m.integrate_quadratures(t_new, m.y.get());
      m.observer.stepped(++m.steps_taken);
      const double sampled = m.t_sampled;
      if (m.emit_outputs(t_new, flag > 0)) continue;  // the observer ended the run at a sample (y is there)
      m.quiet_steps = (flag != 0 || m.t_sampled != sampled || t_new >= t_limit) ? 0 : m.quiet_steps + 1;
    }
    t = t_new;
    if (flag > 0) {
      if (m.on_roots()) break;
      continue;
    }
    m.observer.step_end(t, view(m.y.get()));
    sys.at_step(t, view(m.y.get()), false);  // the step to t is accepted (its samples are taken)
    const double t_eps_new = 1e-12 * std::max(1.0, std::abs(t));
    if (t >= bp - t_eps_new) {
      sys.at_breakpoint(t, view(m.y.get()));
      ++m.stats.breakpoints;
    }
    if (t >= sys.stop_time() - t_eps_new && !(std::abs(m.t_sampled - t) <= t_eps_new)) m.sample_at(t);
    // A ringing BDF order 3-5 (RingingDetector): restart here with the order at most 2 (A-stable, it damps), until the next event.
    if (!m.order_capped && m.st.max_order > 2 && t < sys.stop_time() - t_eps_new && m.ringing.step(view(m.y.get()), m.atol, be->last_order())) {
      ++m.stats.order_caps;
      m.restart(true);
    }
  }
  return t;
}

SolverStats integrate(DynamicalSystem& sys, const IntegratorSettings& st, Observer& observer) {
  Integrator it(sys, st, observer);
  it.advance(std::numeric_limits<double>::infinity());
  return it.stats();
}

}  // namespace imcol
