// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One level of the nested axisymmetric vertex grid and its fast solver for (a I + b E²) x = f.
//
// E² = r ∂r(r⁻¹ ∂r) + ∂zz is the Stokes operator (E²ψ = −rω for the Stokes streamfunction ψ; MODEL.md §4).
// Vertex stencil on r_i = i h, z_j = z0 + j h (h in m, ψ in m³/s):
//   (E²ψ)_ij = [ (r_i/r_{i+½})(ψ_{i+1,j} − ψ_ij) − (r_i/r_{i−½})(ψ_ij − ψ_{i−1,j}) + ψ_{i,j+1} − 2ψ_ij + ψ_{i,j−1} ] / h²,
// which is symmetric after division by r_i. Fast solve (Colonius & Taira, CMAME 197, 2008, §3 idea; our own code):
// a DST-I in z (eigenvalues (2cos(πk/nz) − 2)/h²) turns it into one tridiagonal system in r per mode, solved by
// the Thomas algorithm. ψ = 0 on the axis (i = 0); other boundary values are data.
// DST-I y_k = 2 Σ_j x_j sin(πjk/N), N = nz, all radial lines at once with FFTW many-plans (FFTW's own RODFT00
// allocates on every call). N a multiple of 4 (N = 2M): one split-radix step, exact up to rounding: the even
// outputs are the DST-I of length M − 1 of x_j − x_{N−j} (a real FFT of length N of its odd extension), the odd
// ones a DCT-III of length M of the sums x_j + x_{N−j} (a c2r FFT of length M, Makhoul 1980). Other N: one real FFT
// of length 2N of the odd extension. Plans and buffers are made once per FastSolver (also for the partial row
// counts given to prepare_rows): a solve allocates nothing. FFTW's planner is not thread-safe: plan creation and
// destruction hold one process-wide mutex.
#include <cstddef>
#include <mutex>
#include <vector>

struct fftw_plan_s;

namespace imcol::flow {

/// FFTW's planner (plan creation and destruction) is not thread-safe: every plan made in flow/ holds this mutex.
std::mutex& fftw_planner_mutex();

/// Geometry of one level: vertices i = 0..nr (r = i h), j = 0..nz (z = z0 + j h). Arrays are stored
/// full size (nr+1)(nz+1), index i·(nz+1) + j.
struct LevelGeometry {
  int nr = 0, nz = 0;
  double h = 0, z0 = 0;
  std::size_t size() const { return static_cast<std::size_t>(nr + 1) * (nz + 1); }
  std::size_t at(int i, int j) const { return static_cast<std::size_t>(i) * (nz + 1) + j; }
  double r(double i) const { return i * h; }
  double z(double j) const { return z0 + j * h; }
};

/// Applies E² at interior vertices (boundary values of x are used; the result is 0 on the boundary).
void apply_stokes_operator(const LevelGeometry& g, const std::vector<double>& x, std::vector<double>& y);

/// The stencil above, interior vertices only: out(p, (E²x)_p) for p = at(i, j), 1 ≤ i < nr, 1 ≤ j < nz, line by line
/// (the axis line i = 0 is taken as 0, as ψ there).
template <class Out>
void for_each_stokes(const LevelGeometry& g, const std::vector<double>& x, Out&& out) {
  const double ih2 = 1.0 / (g.h * g.h);
  for (int i = 1; i < g.nr; ++i) {
    const double cp = i / (i + 0.5), cm = i / (i - 0.5);
    const std::size_t row = g.at(i, 0);
    const double* xm = &x[g.at(i - 1, 0)];
    const double* x0 = &x[row];
    const double* xp = &x[g.at(i + 1, 0)];
    for (int j = 1; j < g.nz; ++j)
      out(row + j, ih2 * (cp * (xp[j] - x0[j]) - cm * (x0[j] - (i == 1 ? 0.0 : xm[j])) + x0[j + 1] - 2 * x0[j] + x0[j - 1]));
  }
}

/// Fast solver of (a I + b E²) x = f on the interior of one level for a fixed list of (a, b) pairs.
/// Rows: interior radial lines i = 1..nr−1 are rows 0..nr−2 of the mode-space buffer (row i−1, mode k contiguous).
class FastSolver {
 public:
  struct Op { double a, b; };
  FastSolver(const LevelGeometry& g, std::vector<Op> ops, bool measure_plans = false);
  ~FastSolver();
  FastSolver(const FastSolver&) = delete;
  FastSolver& operator=(const FastSolver&) = delete;

  /// Solves op[k] x = f with the boundary values already stored in x (full-size arrays; f's boundary ignored).
  void solve(int op, const std::vector<double>& f, std::vector<double>& x);
  /// Replaces op[k] (its Thomas factors rebuilt; the transforms are kept).
  void set_op(int k, Op op);
  /// x = op_chain[n−1]⁻¹ ⋯ op_chain[0]⁻¹ f with zero boundary values, for each chained result:
  /// out[m] receives the product of the first m+1 inverses (one transform pair in all).
  void solve_chain(const std::vector<int>& chain, const std::vector<double>& f, const std::vector<std::vector<double>*>& out);

  // The solve in steps, staying in mode space between them: forward or rechain (the right-hand side's modes,
  // forward-eliminated for op as each row arrives), then back (the back substitution, each row packed for the
  // inverse transform as it is finished).
  /// modes ← DST of (s f + op's boundary terms from x) on every row, forward-eliminated for op.
  void forward(int op, double s, const std::vector<double>& f, const std::vector<double>& x);
  /// As forward, but modes ← s·modes + op's boundary terms from x, except rows < phys_rows: DST of (s f + boundary
  /// terms) there. After a solve of another op, chains it without transforming the unchanged rows back and forth.
  void rechain(int op, double s, const std::vector<double>& f, const std::vector<double>& x, int phys_rows);
  /// As forward when f vanishes on rows ≥ phys_rows: only rows < phys_rows are transformed.
  void forward_rows(int op, double s, const std::vector<double>& f, const std::vector<double>& x, int phys_rows);
  /// Completes modes ← op⁻¹(right-hand side) and writes rows 0..rows−1 of x's interior (lines i = 1..rows, none for
  /// rows = 0) as their inverse DST; x on the axis ← 0. The modes are kept; other rows of x are left as they were.
  void back(int op, std::vector<double>& x, int rows);
  /// As back, but writes only what prolong_boundary reads of a coarse level: the whole line full_row + 1 and, on
  /// lines 1..point_rows, the vertices j = nz/4 and 3nz/4 (direct sums; nz a multiple of 4).
  void back_prolong(int op, std::vector<double>& x, int full_row, int point_rows);
  /// Makes the plans for transforms of the first `rows` rows (partial forward and inverse); other counts than
  /// those prepared (and all rows) fall back to all rows.
  void prepare_rows(int rows);
  void save_modes(std::vector<double>& out) const;  // out ← modes (resized once)
  void add_modes(const std::vector<double>& in);    // modes += in
  int rows() const { return n_; }
  const LevelGeometry& geometry() const { return g_; }
  std::size_t bytes() const;

 private:
  /// modes ← op⁻¹ modes (both sweeps).
  void tridiag(int op);
  struct Plans { int rows; fftw_plan_s* fwd; fftw_plan_s* bwd; };  // split: fwd r2c, bwd c2r; padded: fwd only
  const Plans& plans_for(int rows) const;      // the smallest prepared count ≥ rows
  std::size_t ext_len() const { return M_ ? static_cast<std::size_t>(N_) : 2 * static_cast<std::size_t>(N_); }  // odd extension: N or 2N
  // DST-I of `rows` lines of m_ values, line ii at src + ii·src_stride, into line ii at dst + ii·dst_stride, times s
  void dst(const double* src, std::size_t src_stride, double* dst, std::size_t dst_stride, double s, int rows);
  void pack_row(int ii, const double* x);         // transform input row ii
  void execute(int rows);                         // the plans for at least `rows` rows
  void unpack_row(int ii, double* y, double s) const;  // transform output row ii, times s
  void rhs_row(int op, double s, const std::vector<double>& f, const std::vector<double>& x, int ii, double* row) const;
  void eliminate_row(int op, int ii);             // forward sweep of the Thomas algorithm on row ii
  void substitute_row(int op, int ii);            // its back substitution on row ii (row ii + 1 final)
  void chain(int op, double s, const std::vector<double>& f, const std::vector<double>& x, int phys_rows, bool keep_modes);
  void build_tables();                         // per op: the Thomas factors of every mode
  void build_table(int op);                    // op's Thomas factors
  void release();                              // plans and buffers
  LevelGeometry g_;
  std::vector<Op> ops_;
  int m_ = 0, n_ = 0;                         // modes (nz−1), radial unknowns (nr−1)
  int N_ = 0, M_ = 0;                         // N = nz; split-radix when N % 4 == 0: M = N/2, else M = 0
  double* buf_ = nullptr;                     // n_ × m_: the modes
  double* ext_ = nullptr;                     // per row: odd extension (length N, or 2N padded)
  double* spec_ = nullptr;                    // per row: its spectrum, N/2 + 1 (or N + 1) complex
  double* wv_ = nullptr;                      // split: per row the DCT-III input, M/2 + 1 complex
  double* vv_ = nullptr;                      // split: per row its c2r output, M
  double* line_ = nullptr;                    // two rows of scratch (m_ each)
  std::vector<double> tw_c_, tw_s_;           // split: cos, sin(πj/(2M)), j = 0..M/2
  std::vector<double> s1_;                    // DST of the unit vector e_0: 2 sin(π(k+1)/N)
  std::vector<double> q1_, q3_;               // inverse DST at j = N/4, 3N/4: sin(π(k+1)j/N)/N
  std::vector<Plans> plans_;                  // by increasing rows; the last has all n_ rows
  unsigned flags_ = 0;
  std::vector<std::vector<double>> lower_, upper_, inv_den_;  // per op: lower[i], upper[i], inv_den[i·m+k]
};

}  // namespace imcol::flow
