// SPDX-License-Identifier: BSD-3-Clause
#include "flow/pressure.hpp"

#include <fftw3.h>

#include <cmath>
#include <memory>
#include <new>
#include <stdexcept>
#include <vector>

#include "flow/ib.hpp"

namespace imcol::flow {

namespace {

/// (1/r)∂r(r∂r B) + ∂zz B = rhs on one level's cells with Dirichlet values at its faces z_0, z_nz and r = R:
/// DST-II in z (FFTW RODFT10, inverse RODFT01 / 2nz), Thomas in r per mode.
class CellPoisson {
 public:
  explicit CellPoisson(const LevelGeometry& g) : g_(g), nr_(g.nr), nz_(g.nz) {
    const std::size_t n = static_cast<std::size_t>(nr_) * nz_;
    buf_ = fftw_alloc_real(n);
    if (!buf_) throw std::bad_alloc();
    {
      std::lock_guard<std::mutex> lock(fftw_planner_mutex());
      int len = nz_;
      const fftw_r2r_kind k10 = FFTW_RODFT10, k01 = FFTW_RODFT01;
      fwd_ = fftw_plan_many_r2r(1, &len, nr_, buf_, nullptr, 1, nz_, buf_, nullptr, 1, nz_, &k10, FFTW_ESTIMATE);
      bwd_ = fftw_plan_many_r2r(1, &len, nr_, buf_, nullptr, 1, nz_, buf_, nullptr, 1, nz_, &k01, FFTW_ESTIMATE);
    }
    if (!fwd_ || !bwd_) {
      release();
      throw std::runtime_error("FFTW could not plan the pressure's sine transform");
    }
    const double ih2 = 1.0 / (g.h * g.h);
    lower_.resize(nr_);
    upper_.resize(nr_);
    for (int i = 0; i < nr_; ++i) {
      lower_[i] = i / (i + 0.5) * ih2;  // r_i / r_{i+½}: 0 on the axis (no flux through it)
      upper_[i] = (i + 1) / (i + 0.5) * ih2;
    }
    inv_den_.resize(n);
    cp_.resize(n);
    for (int k = 0; k < nz_; ++k) {
      const double s = std::sin(M_PI * (k + 1) / (2.0 * nz_));
      const double lam = -4 * s * s * ih2;
      double cprev = 0;
      for (int i = 0; i < nr_; ++i) {
        double diag = -(lower_[i] + upper_[i]) + lam;
        if (i == nr_ - 1) diag -= upper_[i];  // ghost 2b − B beyond r = R
        const double den = diag - lower_[i] * cprev;
        const std::size_t p = static_cast<std::size_t>(i) * nz_ + k;
        inv_den_[p] = 1.0 / den;
        cp_[p] = cprev = upper_[i] / den;
      }
    }
  }
  ~CellPoisson() { release(); }
  /// This solver is the one for g (its size and spacing: what the plans and the tables depend on).
  bool fits(const LevelGeometry& g) const { return g.nr == nr_ && g.nz == nz_ && g.h == g_.h; }
  CellPoisson(const CellPoisson&) = delete;
  CellPoisson& operator=(const CellPoisson&) = delete;

  /// x.cells ← the solution for rhs with x's boundary values.
  void solve(const std::vector<double>& rhs, CellField& x) {
    const double ih2 = 1.0 / (g_.h * g_.h);
    for (int i = 0; i < nr_; ++i) {
      double* row = buf_ + static_cast<std::size_t>(i) * nz_;
      for (int j = 0; j < nz_; ++j) row[j] = rhs[static_cast<std::size_t>(i) * nz_ + j];
      row[0] -= 2 * ih2 * x.bottom[i];
      row[nz_ - 1] -= 2 * ih2 * x.top[i];
      if (i == nr_ - 1)
        for (int j = 0; j < nz_; ++j) row[j] -= 2 * upper_[i] * x.outer[j];
    }
    fftw_execute(fwd_);
    for (int i = 0; i < nr_; ++i) {  // forward sweep, all modes of a row at once
      double* d = buf_ + static_cast<std::size_t>(i) * nz_;
      const double* inv = &inv_den_[static_cast<std::size_t>(i) * nz_];
      for (int k = 0; k < nz_; ++k) d[k] = (d[k] - (i > 0 ? lower_[i] * d[k - nz_] : 0.0)) * inv[k];
    }
    for (int i = nr_ - 2; i >= 0; --i) {
      double* d = buf_ + static_cast<std::size_t>(i) * nz_;
      const double* cp = &cp_[static_cast<std::size_t>(i) * nz_];
      for (int k = 0; k < nz_; ++k) d[k] -= cp[k] * d[k + nz_];
    }
    fftw_execute(bwd_);
    const double s = 1.0 / (2.0 * nz_);
    x.cells.resize(static_cast<std::size_t>(nr_) * nz_);
    for (std::size_t p = 0; p < x.cells.size(); ++p) x.cells[p] = s * buf_[p];
  }

 private:
  void release() {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    if (fwd_) fftw_destroy_plan(fwd_);
    if (bwd_) fftw_destroy_plan(bwd_);
    fwd_ = bwd_ = nullptr;
    fftw_free(buf_);
    buf_ = nullptr;
  }
  LevelGeometry g_;
  int nr_, nz_;
  double* buf_ = nullptr;
  fftw_plan fwd_ = nullptr, bwd_ = nullptr;
  std::vector<double> lower_, upper_, inv_den_, cp_;
};

/// The solver for level g: each thread keeps those of the last levels it solved (a run's snapshots solve the same
/// levels again; planning and the tables cost more than a solve).
CellPoisson& cell_poisson(const LevelGeometry& g) {
  constexpr std::size_t kKept = 16;
  thread_local std::vector<std::unique_ptr<CellPoisson>> kept;
  for (auto& p : kept)
    if (p->fits(g)) return *p;
  if (kept.size() >= kKept) kept.erase(kept.begin());
  kept.push_back(std::make_unique<CellPoisson>(g));
  return *kept.back();
}

/// Cubic Lagrange weights at t ∈ [0, 1) for the nodes −1, 0, 1, 2.
void cubic_weights(double t, double w[4]) {
  w[0] = -t * (t - 1) * (t - 2) / 6;
  w[1] = (t + 1) * (t - 1) * (t - 2) / 2;
  w[2] = -(t + 1) * t * (t - 2) / 2;
  w[3] = (t + 1) * t * (t - 1) / 6;
}

/// A coarse level's cell field at (r, z) inside it (tensor cubic, even in r across the axis).
double interpolate_cells(const LevelGeometry& c, const CellField& f, double r, double z) {
  const double x = r / c.h - 0.5, y = (z - c.z0) / c.h - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  double wx[4], wy[4];
  cubic_weights(x - fx, wx);
  cubic_weights(y - fy, wy);
  double v = 0;
  for (int a = 0; a < 4; ++a) {
    int I = static_cast<int>(fx) - 1 + a;
    if (I < 0) I = -1 - I;
    if (I >= c.nr) throw std::logic_error("pressure: interpolation beyond the coarse level");
    for (int b = 0; b < 4; ++b) {
      const int J = static_cast<int>(fy) - 1 + b;
      if (J < 0 || J >= c.nz) throw std::logic_error("pressure: interpolation beyond the coarse level");
      v += wx[a] * wy[b] * f.cells[static_cast<std::size_t>(I) * c.nz + J];
    }
  }
  return v;
}

/// Face velocities of one level in the kernel's frame (the stream on the u_z faces).
FaceField frame_velocity(const Level& L, double u_inf) {
  FaceField u = face_velocity(L.g, L.psi);
  for (double& v : u.uz) v += u_inf;
  return u;
}

}  // namespace

std::vector<CellField> solve_axisymmetric_poisson(const std::vector<LevelGeometry>& levels, std::vector<std::vector<double>> rhs,
                                                  const std::function<double(double, double)>& far) {
  const int NL = static_cast<int>(levels.size());
  if (NL == 0 || rhs.size() != levels.size()) throw std::invalid_argument("pressure: one right-hand side per level");
  std::vector<CellField> out(NL);
  for (int l = NL - 1; l >= 0; --l) {
    const LevelGeometry& g = levels[l];
    CellField& x = out[l];
    x.bottom.resize(g.nr);
    x.top.resize(g.nr);
    x.outer.resize(g.nz);
    auto bc = [&](double r, double z) { return l == NL - 1 ? far(r, z) : interpolate_cells(levels[l + 1], out[l + 1], r, z); };
    for (int i = 0; i < g.nr; ++i) {
      x.bottom[i] = bc(g.r(i + 0.5), g.z(0));
      x.top[i] = bc(g.r(i + 0.5), g.z(g.nz));
    }
    for (int j = 0; j < g.nz; ++j) x.outer[j] = bc(g.r(g.nr), g.z(j + 0.5));
    cell_poisson(g).solve(rhs[l], x);
  }
  return out;
}

std::vector<double> cell_to_vertex(const LevelGeometry& g, const CellField& c) {
  std::vector<double> v(g.size());
  auto C = [&](int i, int j) { return c.cells[static_cast<std::size_t>(i) * g.nz + j]; };
  for (int i = 0; i <= g.nr; ++i)
    for (int j = 0; j <= g.nz; ++j) {
      double x;
      if (j == 0 || j == g.nz) {  // bottom and top lines: their boundary values (a corner also the outer one)
        const auto& b = j == 0 ? c.bottom : c.top;
        if (i == 0) x = b[0];
        else if (i < g.nr) x = 0.5 * (b[i - 1] + b[i]);
        else x = 0.5 * (b[g.nr - 1] + c.outer[j == 0 ? 0 : g.nz - 1]);
      } else if (i == g.nr) {
        x = 0.5 * (c.outer[j - 1] + c.outer[j]);
      } else if (i == 0) {  // the axis: the cells at r = h/2 (B is even in r)
        x = 0.5 * (C(0, j - 1) + C(0, j));
      } else {
        x = 0.25 * (C(i - 1, j - 1) + C(i, j - 1) + C(i - 1, j) + C(i, j));
      }
      v[g.at(i, j)] = x;
    }
  return v;
}

namespace {

/// The immersed-boundary force density H g on this level's faces: every point inside the level spread with this
/// level's delta — the sphere points (the kernel spreads them on the finest level only) and the wall points of this
/// level and of the finer ones (the kernel's coarsify carries their vorticity source here); the coarser levels'
/// wall points lie outside. `f` comes sized (zeros) as the level's face velocity.
void add_point_forces(const Solver& s, int level, FaceField& f) {
  const LevelGeometry& g = s.levels().at(level).g;
  const Eigen::VectorXd& gp = s.point_forces();
  const std::size_t ns = 2 * s.points().size();
  if (gp.size() == 0) return;
  auto add = [&](const BodyPoints& pts, std::size_t offset) {
    if (pts.size() == 0) return;
    const std::vector<double> part(gp.data() + offset, gp.data() + offset + 2 * pts.size());
    const FaceField h = spread(g, pts, part);
    for (std::size_t p = 0; p < f.uz.size(); ++p) f.uz[p] += h.uz[p];
    for (std::size_t p = 0; p < f.ur.size(); ++p) f.ur[p] += h.ur[p];
  };
  add(s.points(), 0);
  std::size_t o = ns;
  const auto& wall = s.wall_points();
  for (int l = 0; l < static_cast<int>(wall.size()); ++l) {
    if (l <= level) add(wall[l], o);
    o += 2 * wall[l].size();
  }
}

/// The Lamb vector and the body force on the faces: F_z(i+½, j) = ω ū_r, F_r(i, j+½) = −ω ū_z (Solver::nonlinear's
/// averages; one-sided on the level's boundary lines), plus H g.
struct FaceForce {
  const Level& L;
  const LevelGeometry& g;
  FaceField u, f;

  double uz(int i, int j) const { return u.uz[static_cast<std::size_t>(i) * (g.nz + 1) + j]; }  // (i+½, j)
  double ur(int i, int j) const { return u.ur[static_cast<std::size_t>(i) * g.nz + j]; }        // (i, j+½)
  double om(int i, int j) const { return i == 0 ? 0.0 : L.eta[g.at(i, j)] / g.r(i); }

  double Fz(int i, int j) const {
    double sum = 0;
    int n = 0;
    for (int jj : {j - 1, j})
      if (jj >= 0 && jj < g.nz) {
        sum += ur(i, jj) + ur(i + 1, jj);
        n += 2;
      }
    return 0.5 * (om(i, j) + om(i + 1, j)) * sum / n + f.uz[static_cast<std::size_t>(i) * (g.nz + 1) + j];
  }
  double Fr(int i, int j) const {
    double sum = 0;
    int n = 0;
    for (int ii : {i - 1, i})
      if (ii < g.nr) {
        sum += uz(ii, j) + uz(ii, j + 1);
        n += 2;
      }
    return -0.5 * (om(i, j) + om(i, j + 1)) * sum / n + f.ur[static_cast<std::size_t>(i) * g.nz + j];
  }
};

}  // namespace

std::vector<double> stagnation_source(const Solver& s, int level) {
  const Level& L = s.levels().at(level);
  const LevelGeometry& g = L.g;
  const int nr = g.nr, nz = g.nz;
  FaceForce F{L, g, frame_velocity(L, s.settings().u_inf), {}};
  F.f.uz.assign(F.u.uz.size(), 0.0);
  F.f.ur.assign(F.u.ur.size(), 0.0);
  add_point_forces(s, level, F.f);
  std::vector<double> rhs(static_cast<std::size_t>(nr) * nz);
  for (int i = 0; i < nr; ++i) {
    const double ri = g.r(i), rp = g.r(i + 1), rc = g.r(i + 0.5);
    for (int j = 0; j < nz; ++j) {
      const double fr_out = rp * F.Fr(i + 1, j), fr_in = i == 0 ? 0.0 : ri * F.Fr(i, j);
      rhs[static_cast<std::size_t>(i) * nz + j] = (F.Fz(i, j + 1) - F.Fz(i, j)) / g.h + (fr_out - fr_in) / (rc * g.h);
    }
  }
  return rhs;
}

std::vector<std::vector<double>> pressure(const Solver& s) {
  const auto& lv = s.levels();
  std::vector<LevelGeometry> geo;
  std::vector<std::vector<double>> rhs;
  for (std::size_t l = 0; l < lv.size(); ++l) {
    geo.push_back(lv[l].g);
    rhs.push_back(stagnation_source(s, static_cast<int>(l)));
  }
  const double u_inf = s.settings().u_inf, rho = s.settings().density;
  const auto B = solve_axisymmetric_poisson(geo, std::move(rhs), [&](double, double) { return 0.5 * u_inf * u_inf; });
  std::vector<std::vector<double>> p(lv.size());
  for (std::size_t l = 0; l < lv.size(); ++l) {
    const LevelGeometry& g = geo[l];
    const FaceField u = frame_velocity(lv[l], u_inf);
    // ½|u|² at the cells (face averages), then at the vertices the mean of the cells around them
    std::vector<double> ke(static_cast<std::size_t>(g.nr) * g.nz);
    for (int i = 0; i < g.nr; ++i)
      for (int j = 0; j < g.nz; ++j) {
        const double a = u.uz[static_cast<std::size_t>(i) * (g.nz + 1) + j], b = u.uz[static_cast<std::size_t>(i) * (g.nz + 1) + j + 1];
        const double c = u.ur[static_cast<std::size_t>(i) * g.nz + j], d = u.ur[static_cast<std::size_t>(i + 1) * g.nz + j];
        ke[static_cast<std::size_t>(i) * g.nz + j] = 0.25 * (a * a + b * b + c * c + d * d);
      }
    p[l] = cell_to_vertex(g, B[l]);
    for (int i = 0; i <= g.nr; ++i)
      for (int j = 0; j <= g.nz; ++j) {
        double sum = 0;
        int n = 0;
        for (int ci : {i - 1, i})
          for (int cj : {j - 1, j})
            if (ci >= 0 && ci < g.nr && cj >= 0 && cj < g.nz) {
              sum += ke[static_cast<std::size_t>(ci) * g.nz + cj];
              ++n;
            }
        double& v = p[l][g.at(i, j)];
        v = rho * (v - sum / n);
      }
  }
  return p;
}

}  // namespace imcol::flow
