#include "flow/grid.hpp"

#include <fftw3.h>

#include <cmath>
#include <mutex>
#include <new>
#include <stdexcept>

namespace imcol::flow {

void apply_stokes_operator(const LevelGeometry& g, const std::vector<double>& x, std::vector<double>& y) {
  y.assign(g.size(), 0.0);
  const double ih2 = 1.0 / (g.h * g.h);
  for (int i = 1; i < g.nr; ++i) {
    const double cp = i / (i + 0.5), cm = i / (i - 0.5);
    const double* xm = &x[g.at(i - 1, 0)];
    const double* x0 = &x[g.at(i, 0)];
    const double* xp = &x[g.at(i + 1, 0)];
    double* yy = &y[g.at(i, 0)];
    for (int j = 1; j < g.nz; ++j)
      yy[j] = ih2 * (cp * (xp[j] - x0[j]) - cm * (x0[j] - (i == 1 ? 0.0 : xm[j])) + x0[j + 1] - 2 * x0[j] + x0[j - 1]);
  }
}

namespace {
std::mutex& planner_mutex() {  // FFTW's planner (plan creation and destruction) is not thread-safe
  static std::mutex m;
  return m;
}
}  // namespace

FastSolver::FastSolver(const LevelGeometry& g, std::vector<Op> ops, bool measure_plans) : g_(g), ops_(std::move(ops)) {
  if (g.nr < 2 || g.nz < 2) throw std::invalid_argument("FastSolver: grid needs at least 2 cells each way");
  m_ = g.nz - 1;
  n_ = g.nr - 1;
  len_ = 2 * (m_ + 1);
  const std::size_t nc = static_cast<std::size_t>(len_ / 2 + 1);
  buf_ = fftw_alloc_real(static_cast<std::size_t>(m_) * n_);
  ext_ = fftw_alloc_real(static_cast<std::size_t>(len_) * n_);
  spec_ = reinterpret_cast<double*>(fftw_alloc_complex(nc * n_));
  if (!buf_ || !ext_ || !spec_) {
    release();
    throw std::bad_alloc();
  }
  {
    std::lock_guard<std::mutex> lock(planner_mutex());
    plan_ = fftw_plan_many_dft_r2c(1, &len_, n_, ext_, nullptr, 1, len_, reinterpret_cast<fftw_complex*>(spec_), nullptr, 1,
                                   static_cast<int>(nc), measure_plans ? FFTW_MEASURE : FFTW_ESTIMATE);
  }
  if (!plan_) {
    release();
    throw std::runtime_error("FFTW could not plan the sine transform");
  }
  try {
    build_tables();
  } catch (...) {
    release();
    throw;
  }
}

void FastSolver::build_tables() {
  const double ih2 = 1.0 / (g_.h * g_.h);
  for (const Op& op : ops_) {
    std::vector<double> lower(n_ + 1), inv_den(static_cast<std::size_t>(n_) * m_), cp(static_cast<std::size_t>(n_) * m_);
    for (int k = 0; k < m_; ++k) {
      const double lam = (2 * std::cos(M_PI * (k + 1) / (m_ + 1)) - 2) * ih2;
      double cprev = 0;
      for (int ii = 0; ii < n_; ++ii) {
        const int i = ii + 1;
        const double cplus = i / (i + 0.5), cminus = i / (i - 0.5);
        const double lo = ii == 0 ? 0.0 : op.b * cminus * ih2;
        const double up = op.b * cplus * ih2;
        const double diag = op.a + op.b * (-(cplus + cminus) * ih2 + lam);
        const double den = diag - lo * cprev;
        if (den == 0) throw std::runtime_error("FastSolver: singular operator");
        inv_den[static_cast<std::size_t>(ii) * m_ + k] = 1.0 / den;
        cprev = up / den;
        cp[static_cast<std::size_t>(ii) * m_ + k] = cprev;
        lower[ii] = lo;
      }
    }
    lower_.push_back(std::move(lower));
    inv_den_.push_back(std::move(inv_den));
    cp_.push_back(std::move(cp));
  }
}

FastSolver::~FastSolver() { release(); }

void FastSolver::release() {
  if (plan_) {
    std::lock_guard<std::mutex> lock(planner_mutex());
    fftw_destroy_plan(plan_);
    plan_ = nullptr;
  }
  fftw_free(buf_);
  fftw_free(ext_);
  fftw_free(spec_);
  buf_ = ext_ = spec_ = nullptr;
}

std::size_t FastSolver::bytes() const {
  const std::size_t lines = static_cast<std::size_t>(n_);
  return sizeof(double) * (lines * m_ * (1 + 2 * ops_.size()) + lines * len_ + lines * 2 * (len_ / 2 + 1));
}

void FastSolver::dst(const double* src, std::size_t src_stride, double* dst, std::size_t dst_stride, double s) {
  const std::size_t nc = static_cast<std::size_t>(len_ / 2 + 1);
  for (int ii = 0; ii < n_; ++ii) {
    const double* x = src + ii * src_stride;
    double* z = ext_ + static_cast<std::size_t>(ii) * len_;
    z[0] = 0.0;
    z[m_ + 1] = 0.0;
    for (int k = 0; k < m_; ++k) {
      z[k + 1] = x[k];
      z[len_ - 1 - k] = -x[k];
    }
  }
  fftw_execute(plan_);
  for (int ii = 0; ii < n_; ++ii) {
    const double* c = spec_ + 2 * (ii * nc + 1) + 1;  // Im Z_1, Im Z_2, ... at stride 2
    double* y = dst + ii * dst_stride;
    for (int k = 0; k < m_; ++k) y[k] = s * -c[2 * k];
  }
}

void FastSolver::tridiag(int op) {
  const auto& lo = lower_[op];
  const auto& id = inv_den_[op];
  const auto& cp = cp_[op];
  // forward elimination over i for all modes at once (contiguous in k)
  for (int k = 0; k < m_; ++k) buf_[k] *= id[k];
  for (int ii = 1; ii < n_; ++ii) {
    double* d = buf_ + static_cast<std::size_t>(ii) * m_;
    const double* dm = d - m_;
    const double* inv = id.data() + static_cast<std::size_t>(ii) * m_;
    const double l = lo[ii];
    for (int k = 0; k < m_; ++k) d[k] = (d[k] - l * dm[k]) * inv[k];
  }
  for (int ii = n_ - 2; ii >= 0; --ii) {
    double* d = buf_ + static_cast<std::size_t>(ii) * m_;
    const double* dn = d + m_;
    const double* c = cp.data() + static_cast<std::size_t>(ii) * m_;
    for (int k = 0; k < m_; ++k) d[k] -= c[k] * dn[k];
  }
}

void FastSolver::solve(int op, const std::vector<double>& f, std::vector<double>& x) {
  const double b = ops_.at(op).b, ih2 = 1.0 / (g_.h * g_.h);
  // move the boundary values of x to the right-hand side
  for (int ii = 0; ii < n_; ++ii) {
    const int i = ii + 1;
    double* row = buf_ + static_cast<std::size_t>(ii) * m_;
    for (int k = 0; k < m_; ++k) row[k] = f[g_.at(i, k + 1)];
    row[0] -= b * ih2 * x[g_.at(i, 0)];
    row[m_ - 1] -= b * ih2 * x[g_.at(i, g_.nz)];
  }
  {
    const int i = g_.nr - 1;
    const double cplus = i / (i + 0.5);
    double* row = buf_ + static_cast<std::size_t>(n_ - 1) * m_;
    for (int k = 0; k < m_; ++k) row[k] -= b * ih2 * cplus * x[g_.at(g_.nr, k + 1)];
  }
  const std::size_t W = static_cast<std::size_t>(g_.nz + 1);
  dst(buf_, m_, buf_, m_, 1.0);
  tridiag(op);
  dst(buf_, m_, &x[g_.at(1, 1)], W, 1.0 / (2.0 * (m_ + 1)));
  for (int j = 0; j <= g_.nz; ++j) x[g_.at(0, j)] = 0.0;  // axis
}

void FastSolver::solve_chain(const std::vector<int>& chain, const std::vector<double>& f,
                             const std::vector<std::vector<double>*>& out) {
  const std::size_t W = static_cast<std::size_t>(g_.nz + 1);
  dst(&f[g_.at(1, 1)], W, buf_, m_, 1.0);
  for (std::size_t c = 0; c < chain.size(); ++c) {
    tridiag(chain[c]);
    if (out[c]) {  // the inverse transform reads buf_ without changing it
      out[c]->resize(g_.size());
      for (int j = 0; j <= g_.nz; ++j) (*out[c])[g_.at(0, j)] = (*out[c])[g_.at(g_.nr, j)] = 0.0;
      for (int i = 0; i <= g_.nr; ++i) (*out[c])[g_.at(i, 0)] = (*out[c])[g_.at(i, g_.nz)] = 0.0;
      dst(buf_, m_, &(*out[c])[g_.at(1, 1)], W, 1.0 / (2.0 * (m_ + 1)));
    }
  }
}

}  // namespace imcol::flow
