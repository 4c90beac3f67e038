// CVODE / IDA driver for imcol::DynamicalSystem (SUNDIALS 6.x). The only SUNDIALS user in imcol.
#include <cvode/cvode.h>
#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <numeric>
#include <sstream>

#include "core/errors.hpp"
#include "integrators/integrator.hpp"

#if SUNDIALS_VERSION_MAJOR != 6
#error "imcol's SUNDIALS driver is written for SUNDIALS 6.x"
#endif

namespace imcol {

std::map<std::string, long> SolverStats::as_map() const {
  return {{"steps", steps},
          {"rhs_evals", rhs_evals},
          {"jac_evals", jac_evals},
          {"nonlin_iters", nonlin_iters},
          {"nonlin_conv_fails", nonlin_conv_fails},
          {"error_test_fails", error_test_fails},
          {"root_fn_evals", root_fn_evals},
          {"root_events", root_events},
          {"reinits", reinits}};
}

namespace {

std::span<const double> view(N_Vector v) { return {N_VGetArrayPointer(v), static_cast<std::size_t>(N_VGetLength(v))}; }
std::span<double> mview(N_Vector v) { return {N_VGetArrayPointer(v), static_cast<std::size_t>(N_VGetLength(v))}; }

/// State shared with the C callbacks. Exceptions never cross SUNDIALS: they are stored and rethrown.
struct Callback {
  DynamicalSystem* sys;
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

/// The operations the event loop needs, implemented once for CVODE and once for IDA.
class Backend {
 public:
  virtual ~Backend() = default;
  virtual void init(double t, N_Vector y) = 0;  // (re)initialise at (t, y)
  virtual void set_roots(const std::vector<RootSpec>& roots) = 0;
  virtual int solve(double tout, double tstop, N_Vector y, double& t) = 0;  // >0 root, 0 ok, <0 fail
  virtual void root_info(int* found) = 0;
  virtual void add_stats(SolverStats& s) = 0;
  virtual std::string flag_name(int flag) = 0;
  virtual void error_vectors(N_Vector w, N_Vector e) = 0;
};

class CvodeBackend : public Backend {
 public:
  CvodeBackend(SUNContext ctx, Callback& cb, const IntegratorSettings& st, N_Vector y, N_Vector abstol)
      : cb_(cb), st_(st), abstol_(abstol) {
    mem_ = CVodeCreate(CV_BDF, ctx);
    if (!mem_) throw SolverError("CVodeCreate failed");
    check(CVodeSetErrHandlerFn(mem_, error_handler, &cb_), "CVodeSetErrHandlerFn");
    check(CVodeInit(mem_, cv_rhs, 0.0, y), "CVodeInit");
    check(CVodeSetUserData(mem_, &cb_), "CVodeSetUserData");
    check(CVodeSVtolerances(mem_, st.rtol, abstol_), "CVodeSVtolerances");
    A_ = SUNDenseMatrix(N_VGetLength(y), N_VGetLength(y), ctx);
    LS_ = SUNLinSol_Dense(y, A_, ctx);
    check(CVodeSetLinearSolver(mem_, LS_, A_), "CVodeSetLinearSolver");
    check(CVodeSetMaxOrd(mem_, st.max_order), "CVodeSetMaxOrd");
    check(CVodeSetNoInactiveRootWarn(mem_), "CVodeSetNoInactiveRootWarn");
  }
  ~CvodeBackend() override {
    CVodeFree(&mem_);
    SUNLinSolFree(LS_);
    SUNMatDestroy(A_);
  }
  void init(double t, N_Vector y) override {
    check(CVodeReInit(mem_, t, y), "CVodeReInit");
    check(CVodeSetMaxStep(mem_, cb_.sys->max_step()), "CVodeSetMaxStep");
    check(CVodeSetMaxNumSteps(mem_, st_.max_steps), "CVodeSetMaxNumSteps");
  }
  void set_roots(const std::vector<RootSpec>& roots) override {
    cb_.nroots = roots.size();
    check(CVodeRootInit(mem_, static_cast<int>(roots.size()), roots.empty() ? nullptr : cv_root), "CVodeRootInit");
    if (roots.empty()) return;
    std::vector<int> dir;
    for (const auto& r : roots) dir.push_back(r.direction);
    check(CVodeSetRootDirection(mem_, dir.data()), "CVodeSetRootDirection");
  }
  int solve(double tout, double tstop, N_Vector y, double& t) override {
    check(CVodeSetStopTime(mem_, tstop), "CVodeSetStopTime");
    int flag = CVode(mem_, tout, y, &t, CV_NORMAL);
    if (flag == CV_ROOT_RETURN) return 1;
    return flag < 0 ? flag : 0;
  }
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
  const IntegratorSettings& st_;
  N_Vector abstol_;
  void* mem_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver LS_ = nullptr;
};

class IdaBackend : public Backend {
 public:
  IdaBackend(SUNContext ctx, Callback& cb, const IntegratorSettings& st, N_Vector y, N_Vector abstol)
      : cb_(cb), st_(st), abstol_(abstol) {
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
    check(IDASetMaxStep(mem_, cb_.sys->max_step()), "IDASetMaxStep");
    check(IDASetMaxNumSteps(mem_, st_.max_steps), "IDASetMaxNumSteps");
  }
  void set_roots(const std::vector<RootSpec>& roots) override {
    cb_.nroots = roots.size();
    check(IDARootInit(mem_, static_cast<int>(roots.size()), roots.empty() ? nullptr : ida_root), "IDARootInit");
    if (roots.empty()) return;
    std::vector<int> dir;
    for (const auto& r : roots) dir.push_back(r.direction);
    check(IDASetRootDirection(mem_, dir.data()), "IDASetRootDirection");
  }
  int solve(double tout, double tstop, N_Vector y, double& t) override {
    check(IDASetStopTime(mem_, tstop), "IDASetStopTime");
    int flag = IDASolve(mem_, tout, &t, y, yp_, IDA_NORMAL);
    if (flag == IDA_ROOT_RETURN) return 1;
    return flag < 0 ? flag : 0;
  }
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
  const IntegratorSettings& st_;
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

SolverStats integrate(DynamicalSystem& sys, const IntegratorSettings& st, Observer& observer) {
  if (!(st.rtol > 0) || !(st.atol > 0)) throw SolverError("tolerances must be positive");
  if (!(st.output_dt > 0)) throw SolverError("output interval must be positive");
  SUNContext raw = nullptr;
  if (SUNContext_Create(nullptr, &raw) != 0) throw SolverError("SUNContext_Create failed");
  std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter> ctx(raw);

  const auto n = static_cast<sunindextype>(sys.size());
  VectorPtr y(N_VNew_Serial(n, ctx.get()));
  VectorPtr abstol(N_VNew_Serial(n, ctx.get()));
  sys.initial_state(mview(y.get()));
  auto tol = sys.absolute_tolerances(st.atol);
  std::copy(tol.begin(), tol.end(), mview(abstol.get()).begin());

  Callback cb{&sys, 0, nullptr, {}};
  std::unique_ptr<Backend> be;
  if (st.method == "cvode") be = std::make_unique<CvodeBackend>(ctx.get(), cb, st, y.get(), abstol.get());
  else if (st.method == "ida") be = std::make_unique<IdaBackend>(ctx.get(), cb, st, y.get(), abstol.get());
  else throw SolverError("unknown integrator '" + st.method + "'");

  SolverStats stats;
  double t = 0.0;
  be->init(t, y.get());
  be->set_roots(sys.roots());
  observer.sample(t, view(y.get()), true);

  const auto names = sys.component_names();
  // An exception from the model: input and solver errors pass through, anything else becomes a
  // SolverError that says where it happened.
  auto rethrow_model_error = [&] {
    try {
      std::rethrow_exception(cb.error);
    } catch (const InputError&) {
      throw;
    } catch (const SolverError&) {
      throw;
    } catch (const std::exception& e) {
      std::ostringstream os;
      os << st.method << ": the model failed near t = " << t << " s: " << e.what();
      throw SolverError(os.str());
    }
  };
  auto fail = [&](int flag) {
    if (cb.error) rethrow_model_error();
    std::ostringstream os;
    os << st.method << " failed at t = " << t << " s with " << be->flag_name(flag);
    if (!cb.last_message.empty()) os << " [" << cb.last_message << "]";
    VectorPtr w(N_VClone(y.get())), e(N_VClone(y.get()));
    be->error_vectors(w.get(), e.get());
    auto ws = view(w.get()), es = view(e.get());
    std::vector<std::size_t> idx(ws.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](auto a, auto b) { return std::abs(ws[a] * es[a]) > std::abs(ws[b] * es[b]); });
    os << "; largest weighted local errors:";
    for (std::size_t k = 0; k < std::min<std::size_t>(3, idx.size()); ++k)
      os << " " << names[idx[k]] << "=" << std::abs(ws[idx[k]] * es[idx[k]]);
    throw SolverError(os.str());
  };

  long k_out = 1;  // output times k·dt, counted so that they cannot stop advancing
  while (true) {
    const double t_eps = 1e-12 * std::max(1.0, std::abs(t));  // times closer than this count as reached
    const double tstop = sys.stop_time();
    if (t >= tstop - t_eps) break;
    // The next output time must lie strictly ahead (an event may have landed on it).
    while (k_out * st.output_dt <= t + t_eps) ++k_out;
    const double next_out = k_out * st.output_dt;
    const double tout = std::min(next_out, tstop);
    int flag = be->solve(tout, tstop, y.get(), t);
    if (flag < 0) fail(flag);
    if (cb.error) rethrow_model_error();
    if (flag > 0) {
      std::vector<int> flags(sys.roots().size(), 0);
      be->root_info(flags.data());
      std::vector<std::size_t> found;
      for (std::size_t i = 0; i < flags.size(); ++i)
        if (flags[i]) found.push_back(i);
      stats.root_events += static_cast<long>(found.size());
      observer.sample(t, view(y.get()), true);
      const EventAction action = sys.on_roots(found, t, mview(y.get()));
      if (action == EventAction::stop) break;
      if (action == EventAction::reinit) {
        be->add_stats(stats);
        ++stats.reinits;
        be->init(t, y.get());
        be->set_roots(sys.roots());
      }
      continue;
    }
    observer.sample(t, view(y.get()), false);
  }
  be->add_stats(stats);
  return stats;
}

}  // namespace imcol
