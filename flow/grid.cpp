// SPDX-License-Identifier: BSD-3-Clause
#include "flow/grid.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <new>
#include <stdexcept>

namespace imcol::flow {

void apply_stokes_operator(const LevelGeometry& g, const std::vector<double>& x, std::vector<double>& y) {
  y.assign(g.size(), 0.0);
  for_each_stokes(g, x, [&](std::size_t p, double v) { y[p] = v; });
}

std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

FastSolver::FastSolver(const LevelGeometry& g, std::vector<Op> ops, bool measure_plans) : g_(g), ops_(std::move(ops)) {
  if (g.nr < 2 || g.nz < 2) throw std::invalid_argument("FastSolver: grid needs at least 2 cells each way");
  m_ = g.nz - 1;
  n_ = g.nr - 1;
  N_ = g.nz;
  M_ = N_ % 4 == 0 ? N_ / 2 : 0;
  flags_ = measure_plans ? FFTW_MEASURE : FFTW_ESTIMATE;
  const std::size_t rows = static_cast<std::size_t>(n_);
  const std::size_t len = ext_len();
  buf_ = fftw_alloc_real(static_cast<std::size_t>(m_) * rows);
  ext_ = fftw_alloc_real(len * rows);
  spec_ = reinterpret_cast<double*>(fftw_alloc_complex((len / 2 + 1) * rows));
  line_ = fftw_alloc_real(2 * static_cast<std::size_t>(m_));
  if (M_) {
    wv_ = reinterpret_cast<double*>(fftw_alloc_complex(static_cast<std::size_t>(M_ / 2 + 1) * rows));
    vv_ = fftw_alloc_real(static_cast<std::size_t>(M_) * rows);
  }
  if (!buf_ || !ext_ || !spec_ || !line_ || (M_ && (!wv_ || !vv_))) {
    release();
    throw std::bad_alloc();
  }
  if (M_)
    for (int j = 0; j <= M_ / 2; ++j) {
      tw_c_.push_back(std::cos(M_PI * j / (2.0 * M_)));
      tw_s_.push_back(std::sin(M_PI * j / (2.0 * M_)));
    }
  for (int k = 0; k < m_; ++k) s1_.push_back(2 * std::sin(M_PI * (k + 1) / N_));
  if (N_ % 4 == 0)
    for (int k = 0; k < m_; ++k) {
      q1_.push_back(std::sin(M_PI * (k + 1) * 0.25) / N_);
      q3_.push_back(std::sin(M_PI * (k + 1) * 0.75) / N_);
    }
  try {
    prepare_rows(1);
    prepare_rows(n_);
    build_tables();
  } catch (...) {
    release();
    throw;
  }
}

void FastSolver::prepare_rows(int rows) {
  rows = std::clamp(rows, 1, n_);
  for (const Plans& p : plans_)
    if (p.rows == rows) return;
  Plans p{rows, nullptr, nullptr};
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    int n = static_cast<int>(ext_len()), nc = n / 2 + 1;
    p.fwd = fftw_plan_many_dft_r2c(1, &n, rows, ext_, nullptr, 1, n, reinterpret_cast<fftw_complex*>(spec_), nullptr, 1, nc, flags_);
    if (M_) {
      int mm = M_, mc = M_ / 2 + 1;
      p.bwd = fftw_plan_many_dft_c2r(1, &mm, rows, reinterpret_cast<fftw_complex*>(wv_), nullptr, 1, mc, vv_, nullptr, 1, mm, flags_);
    }
  }
  if (!p.fwd || (M_ && !p.bwd)) {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    if (p.fwd) fftw_destroy_plan(p.fwd);
    if (p.bwd) fftw_destroy_plan(p.bwd);
    throw std::runtime_error("FFTW could not plan the sine transform");
  }
  plans_.insert(std::upper_bound(plans_.begin(), plans_.end(), p, [](const Plans& a, const Plans& b) { return a.rows < b.rows; }), p);
}

const FastSolver::Plans& FastSolver::plans_for(int rows) const {
  for (const Plans& p : plans_)
    if (p.rows >= rows) return p;
  return plans_.back();
}

void FastSolver::build_tables() {
  lower_.assign(ops_.size(), {});
  upper_.assign(ops_.size(), {});
  inv_den_.assign(ops_.size(), {});
  for (std::size_t k = 0; k < ops_.size(); ++k) build_table(static_cast<int>(k));
}

void FastSolver::build_table(int k_op) {
  const Op& op = ops_[static_cast<std::size_t>(k_op)];
  const double ih2 = 1.0 / (g_.h * g_.h);
  std::vector<double> lower(n_ + 1), upper(n_ + 1), inv_den(static_cast<std::size_t>(n_) * m_);
  for (int ii = 0; ii < n_; ++ii) {
    const int i = ii + 1;
    lower[ii] = ii == 0 ? 0.0 : op.b * (i / (i - 0.5)) * ih2;
    upper[ii] = op.b * (i / (i + 0.5)) * ih2;
  }
  for (int k = 0; k < m_; ++k) {
    const double lam = (2 * std::cos(M_PI * (k + 1) / (m_ + 1)) - 2) * ih2;
    double cprev = 0;
    for (int ii = 0; ii < n_; ++ii) {
      const int i = ii + 1;
      const double cplus = i / (i + 0.5), cminus = i / (i - 0.5);
      const double diag = op.a + op.b * (-(cplus + cminus) * ih2 + lam);
      const double den = diag - lower[ii] * cprev;
      if (den == 0) throw std::runtime_error("FastSolver: singular operator");
      inv_den[static_cast<std::size_t>(ii) * m_ + k] = 1.0 / den;
      cprev = upper[ii] / den;
    }
  }
  lower_[static_cast<std::size_t>(k_op)] = std::move(lower);
  upper_[static_cast<std::size_t>(k_op)] = std::move(upper);
  inv_den_[static_cast<std::size_t>(k_op)] = std::move(inv_den);
}

void FastSolver::set_op(int k, Op op) {
  if (k < 0 || k >= static_cast<int>(ops_.size())) throw std::out_of_range("FastSolver::set_op: no such operator");
  ops_[static_cast<std::size_t>(k)] = op;
  build_table(k);
}

FastSolver::~FastSolver() { release(); }

void FastSolver::release() {
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    for (Plans& p : plans_) {
      if (p.fwd) fftw_destroy_plan(p.fwd);
      if (p.bwd) fftw_destroy_plan(p.bwd);
    }
    plans_.clear();
  }
  for (double* b : {buf_, ext_, spec_, wv_, vv_, line_}) fftw_free(b);
  buf_ = ext_ = spec_ = wv_ = vv_ = line_ = nullptr;
}

std::size_t FastSolver::bytes() const {
  const std::size_t rows = static_cast<std::size_t>(n_);
  const std::size_t len = ext_len();
  return sizeof(double) * (rows * m_ * (1 + ops_.size()) + rows * (len + 2 * (len / 2 + 1)) + (M_ ? rows * (M_ + 2 * (M_ / 2 + 1)) : 0));
}

void FastSolver::pack_row(int ii, const double* xr) {
  if (!M_) {  // odd extension of length 2N: RODFT00(x)_k = −Im Z_{k+1}
    const int len = 2 * N_;
    double* z = ext_ + static_cast<std::size_t>(ii) * len;
    z[0] = 0.0;
    z[N_] = 0.0;
    for (int k = 0; k < m_; ++k) {
      z[k + 1] = xr[k];
      z[len - 1 - k] = -xr[k];
    }
    return;
  }
  // split-radix: x_j (j = 1..N−1) is xr[j − 1]; d_j = x_j − x_{N−j}, t_j = s_{M−j} with s_j = x_j + x_{N−j}, s_M = x_M
  const int N = N_, M = M_, H = M_ / 2;
  const double* x = xr - 1;
  double* e = ext_ + static_cast<std::size_t>(ii) * N;
  double* w = wv_ + 2 * static_cast<std::size_t>(ii) * (H + 1);
  e[0] = 0.0;
  e[M] = 0.0;
  for (int j = 1; j < M; ++j) {
    const double d = x[j] - x[N - j];
    e[j] = d;
    e[N - j] = -d;
  }
  w[0] = 2 * x[M];
  w[1] = 0.0;
  for (int j = 1; j <= H; ++j) {
    // t_j = s_{M−j}, t_{M−j} = s_j;  W_j = (t_j − i t_{M−j}) e^{iπj/(2M)}
    const double tj = x[M - j] + x[M + j], tmj = x[j] + x[N - j];
    w[2 * j] = tj * tw_c_[j] + tmj * tw_s_[j];
    w[2 * j + 1] = tj * tw_s_[j] - tmj * tw_c_[j];
  }
}

void FastSolver::execute(int rows) {
  const Plans& P = plans_for(rows);
  fftw_execute(P.fwd);
  if (P.bwd) fftw_execute(P.bwd);
}

void FastSolver::unpack_row(int ii, double* y, double s) const {
  if (!M_) {
    const double* c = spec_ + 2 * (static_cast<std::size_t>(ii) * (N_ + 1) + 1) + 1;
    for (int k = 0; k < m_; ++k) y[k] = s * -c[2 * k];
    return;
  }
  const int M = M_, H = M_ / 2;
  const double* c = spec_ + 2 * (static_cast<std::size_t>(ii) * (N_ / 2 + 1)) + 1;  // Im Z_q at c[2q]
  const double* v = vv_ + static_cast<std::size_t>(ii) * M;
  // y[2q − 1] = −Im Z_q (q = 1..M−1); y[2q] = (−1)^q V_q, V_{2p} = v_p, V_{2p+1} = v_{M−1−p}
  for (int p = 0; p < H; ++p) {
    y[4 * p] = s * v[p];               // q = 2p
    y[4 * p + 2] = -s * v[M - 1 - p];  // q = 2p + 1
  }
  for (int q = 1; q < M; ++q) y[2 * q - 1] = -s * c[2 * q];
}

void FastSolver::dst(const double* src, std::size_t src_stride, double* dst, std::size_t dst_stride, double s, int rows) {
  rows = std::min(rows, n_);
  for (int ii = 0; ii < rows; ++ii) pack_row(ii, src + ii * src_stride);
  execute(rows);
  for (int ii = 0; ii < rows; ++ii) unpack_row(ii, dst + ii * dst_stride, s);
}

void FastSolver::rhs_row(int op, double s, const std::vector<double>& f, const std::vector<double>& x, int ii, double* row) const {
  // s f plus the boundary values of x moved to the right-hand side
  const double b = ops_[op].b, ih2 = 1.0 / (g_.h * g_.h);
  const int i = ii + 1;
  const double* fr = &f[g_.at(i, 1)];
  for (int k = 0; k < m_; ++k) row[k] = s * fr[k];
  row[0] -= b * ih2 * x[g_.at(i, 0)];
  row[m_ - 1] -= b * ih2 * x[g_.at(i, g_.nz)];
  if (ii == n_ - 1) {
    const double cplus = i / (i + 0.5);
    for (int k = 0; k < m_; ++k) row[k] -= b * ih2 * cplus * x[g_.at(g_.nr, k + 1)];
  }
}

void FastSolver::eliminate_row(int op, int ii) {
  double* d = buf_ + static_cast<std::size_t>(ii) * m_;
  const double* inv = inv_den_[op].data() + static_cast<std::size_t>(ii) * m_;
  if (ii == 0) {
    for (int k = 0; k < m_; ++k) d[k] *= inv[k];
    return;
  }
  const double* dm = d - m_;
  const double l = lower_[op][ii];
  for (int k = 0; k < m_; ++k) d[k] = (d[k] - l * dm[k]) * inv[k];
}

void FastSolver::substitute_row(int op, int ii) {
  double* d = buf_ + static_cast<std::size_t>(ii) * m_;
  const double* dn = d + m_;
  const double* inv = inv_den_[op].data() + static_cast<std::size_t>(ii) * m_;
  const double u = upper_[op][ii];
  for (int k = 0; k < m_; ++k) d[k] -= u * inv[k] * dn[k];
}

void FastSolver::forward(int op, double s, const std::vector<double>& f, const std::vector<double>& x) {
  chain(op, s, f, x, n_, false);  // every row transformed
}

void FastSolver::rechain(int op, double s, const std::vector<double>& f, const std::vector<double>& x, int phys_rows) {
  chain(op, s, f, x, phys_rows, true);
}

void FastSolver::forward_rows(int op, double s, const std::vector<double>& f, const std::vector<double>& x, int phys_rows) {
  chain(op, s, f, x, phys_rows, false);
}

void FastSolver::chain(int op, double s, const std::vector<double>& f, const std::vector<double>& x, int phys_rows, bool keep_modes) {
  phys_rows = std::clamp(phys_rows, 0, n_);
  const double b = ops_.at(op).b, ih2 = 1.0 / (g_.h * g_.h);
  double* outer = line_ + m_;
  if (phys_rows < n_) {  // the outer line's boundary terms: one row's DST (before the rows below reuse the buffers)
    const int i = g_.nr - 1;
    const double cplus = i / (i + 0.5);
    for (int k = 0; k < m_; ++k) line_[k] = -b * ih2 * cplus * x[g_.at(g_.nr, k + 1)];
    dst(line_, m_, outer, m_, 1.0, 1);
  }
  if (phys_rows > 0) {
    for (int ii = 0; ii < phys_rows; ++ii) {
      rhs_row(op, s, f, x, ii, line_);
      pack_row(ii, line_);
    }
    execute(phys_rows);
    for (int ii = 0; ii < phys_rows; ++ii) {
      unpack_row(ii, buf_ + static_cast<std::size_t>(ii) * m_, 1.0);
      eliminate_row(op, ii);
    }
  }
  // rows ≥ phys_rows: scale the modes (or none), add the DST of the top and bottom boundary terms (e_0, e_{m−1}:
  // s1_k, (−1)^k s1_k)
  for (int ii = phys_rows; ii < n_; ++ii) {
    const int i = ii + 1;
    double* row = buf_ + static_cast<std::size_t>(ii) * m_;
    const double c0 = -b * ih2 * x[g_.at(i, 0)], c1 = -b * ih2 * x[g_.at(i, g_.nz)];
    const double cp = c0 + c1, cm = c0 - c1;
    auto put = [&](int k, double c) { row[k] = (keep_modes ? s * row[k] : 0.0) + c * s1_[k]; };
    int k = 0;
    for (; k + 1 < m_; k += 2) {
      put(k, cp);
      put(k + 1, cm);
    }
    if (k < m_) put(k, cp);
    if (ii == n_ - 1)
      for (int kk = 0; kk < m_; ++kk) row[kk] += outer[kk];
    eliminate_row(op, ii);
  }
}

void FastSolver::back(int op, std::vector<double>& x, int rows) {
  rows = std::clamp(rows, 0, n_);
  for (int ii = n_ - 2; ii >= 0; --ii) {
    substitute_row(op, ii);
    if (ii + 1 < rows) pack_row(ii + 1, buf_ + static_cast<std::size_t>(ii + 1) * m_);
  }
  if (rows == 0) return;
  pack_row(0, buf_);
  execute(rows);
  const double s = 1.0 / (2.0 * N_);
  for (int ii = 0; ii < rows; ++ii) unpack_row(ii, &x[g_.at(ii + 1, 1)], s);
  for (int j = 0; j <= g_.nz; ++j) x[g_.at(0, j)] = 0.0;  // axis
}

void FastSolver::back_prolong(int op, std::vector<double>& x, int full_row, int point_rows) {
  if (q1_.empty()) throw std::logic_error("FastSolver::back_prolong needs nz a multiple of 4");
  full_row = std::clamp(full_row, 0, n_ - 1);
  point_rows = std::clamp(point_rows, 0, n_);
  const int j1 = N_ / 4, j3 = 3 * N_ / 4;
  auto finish = [&](int ii) {  // row ii is final
    const double* d = buf_ + static_cast<std::size_t>(ii) * m_;
    if (ii < point_rows) {
      double a = 0, c = 0;
      for (int k = 0; k < m_; ++k) {
        a += d[k] * q1_[k];
        c += d[k] * q3_[k];
      }
      x[g_.at(ii + 1, j1)] = a;
      x[g_.at(ii + 1, j3)] = c;
    }
    if (ii == full_row) pack_row(0, d);
  };
  finish(n_ - 1);
  for (int ii = n_ - 2; ii >= 0; --ii) {
    substitute_row(op, ii);
    finish(ii);
  }
  execute(1);
  unpack_row(0, &x[g_.at(full_row + 1, 1)], 1.0 / (2.0 * N_));
  for (int j = 0; j <= g_.nz; ++j) x[g_.at(0, j)] = 0.0;  // axis
}

void FastSolver::tridiag(int op) {
  for (int ii = 0; ii < n_; ++ii) eliminate_row(op, ii);
  for (int ii = n_ - 2; ii >= 0; --ii) substitute_row(op, ii);
}

void FastSolver::save_modes(std::vector<double>& out) const {
  out.resize(static_cast<std::size_t>(n_) * m_);
  std::copy(buf_, buf_ + out.size(), out.begin());
}

void FastSolver::add_modes(const std::vector<double>& in) {
  const std::size_t n = static_cast<std::size_t>(n_) * m_;
  for (std::size_t p = 0; p < n; ++p) buf_[p] += in[p];
}

void FastSolver::solve(int op, const std::vector<double>& f, std::vector<double>& x) {
  forward(op, 1.0, f, x);
  back(op, x, n_);
}

void FastSolver::solve_chain(const std::vector<int>& chain, const std::vector<double>& f,
                             const std::vector<std::vector<double>*>& out) {
  const std::size_t W = static_cast<std::size_t>(g_.nz + 1);
  dst(&f[g_.at(1, 1)], W, buf_, m_, 1.0, n_);
  for (std::size_t c = 0; c < chain.size(); ++c) {
    tridiag(chain[c]);
    if (out[c]) {  // the inverse transform reads the modes without changing them
      out[c]->resize(g_.size());
      for (int j = 0; j <= g_.nz; ++j) (*out[c])[g_.at(0, j)] = (*out[c])[g_.at(g_.nr, j)] = 0.0;
      for (int i = 0; i <= g_.nr; ++i) (*out[c])[g_.at(i, 0)] = (*out[c])[g_.at(i, g_.nz)] = 0.0;
      dst(buf_, m_, &(*out[c])[g_.at(1, 1)], W, 1.0 / (2.0 * N_), n_);
    }
  }
}

}  // namespace imcol::flow
