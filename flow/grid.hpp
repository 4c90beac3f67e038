#pragma once
// One level of the nested axisymmetric vertex grid and its fast solver for (a I + b E²) x = f.
//
// E² = r ∂r(r⁻¹ ∂r) + ∂zz is the Stokes operator (E²ψ = −rω for the Stokes streamfunction ψ; MODEL.md §4).
// Vertex stencil on r_i = i h, z_j = z0 + j h (h in m, ψ in m³/s):
//   (E²ψ)_ij = [ (r_i/r_{i+½})(ψ_{i+1,j} − ψ_ij) − (r_i/r_{i−½})(ψ_ij − ψ_{i−1,j}) + ψ_{i,j+1} − 2ψ_ij + ψ_{i,j−1} ] / h²,
// which is symmetric after division by r_i. Fast solve (Colonius & Taira, CMAME 197, 2008, §3 idea; our own code):
// a DST-I in z (FFTW_RODFT00, eigenvalues (2cos(πk/nz) − 2)/h²) turns it into one tridiagonal system in r
// per mode, solved by the Thomas algorithm. ψ = 0 on the axis (i = 0); other boundary values are data.
// The DST-I of length m (FFTW's RODFT00, unnormalised) is computed as one real-to-complex FFT of length
// 2(m+1) of the odd extension [0, x, 0, −x reversed] per radial line, all lines in one FFTW many-plan:
// RODFT00(x)_k = −Im Z_{k+1}. Plans and buffers are made once per FastSolver: a solve allocates nothing
// (FFTW's own RODFT00 algorithms allocate a buffer on every call). FFTW's planner is not thread-safe:
// plan creation and destruction hold one process-wide mutex.
#include <cstddef>
#include <vector>

struct fftw_plan_s;

namespace imcol::flow {

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

/// Fast solver of (a I + b E²) x = f on the interior of one level for a fixed list of (a, b) pairs.
class FastSolver {
 public:
  struct Op { double a, b; };
  FastSolver(const LevelGeometry& g, std::vector<Op> ops, bool measure_plans = false);
  ~FastSolver();
  FastSolver(const FastSolver&) = delete;
  FastSolver& operator=(const FastSolver&) = delete;

  /// Solves op[k] x = f with the boundary values already stored in x (full-size arrays; f's boundary ignored).
  void solve(int op, const std::vector<double>& f, std::vector<double>& x);
  /// x = op_chain[n−1]⁻¹ ⋯ op_chain[0]⁻¹ f with zero boundary values, for each chained result:
  /// out[m] receives the product of the first m+1 inverses (one transform pair in all).
  void solve_chain(const std::vector<int>& chain, const std::vector<double>& f, const std::vector<std::vector<double>*>& out);
  const LevelGeometry& geometry() const { return g_; }
  std::size_t bytes() const;

 private:
  // DST-I of n_ lines of m_ values, line ii at src + ii·src_stride, into line ii at dst + ii·dst_stride, times s
  void dst(const double* src, std::size_t src_stride, double* dst, std::size_t dst_stride, double s);
  void tridiag(int op);                        // buf_ <- op⁻¹ buf_ in mode space
  void build_tables();                         // per op: the Thomas factors of every mode
  void release();                              // plan and buffers
  LevelGeometry g_;
  std::vector<Op> ops_;
  int m_ = 0, n_ = 0;                         // modes (nz−1), radial unknowns (nr−1)
  int len_ = 0;                               // FFT length 2(m_+1)
  double* buf_ = nullptr;                     // n_ × m_, row i, mode k contiguous
  double* ext_ = nullptr;                     // n_ × len_: odd extensions
  double* spec_ = nullptr;                    // n_ × (len_/2 + 1) complex (re, im): their spectra
  fftw_plan_s* plan_ = nullptr;
  std::vector<std::vector<double>> lower_, inv_den_, cp_;  // per op: lower[i], inv_den[i·m+k], cp[i·m+k]
};

}  // namespace imcol::flow
