// SPDX-License-Identifier: BSD-3-Clause
// Flow kernel identities on tiny grids (MODEL.md §4): zero discrete divergence, solve-then-apply,
// adjoint interpolation/spreading under the axisymmetric inner product, force conservation, and the
// second-order accuracy of E² on a manufactured solution.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <thread>

#include "flow/grid.hpp"
#include "flow/ib.hpp"
#include "flow/solver.hpp"

using namespace imcol::flow;

namespace {

LevelGeometry tiny(int nr = 10, int nz = 16, double h = 0.1, double z0 = -0.8) {
  LevelGeometry g;
  g.nr = nr;
  g.nz = nz;
  g.h = h;
  g.z0 = z0;
  return g;
}

std::vector<double> random_field(const LevelGeometry& g, unsigned seed, bool zero_axis = true) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<double> x(g.size());
  for (int i = 0; i <= g.nr; ++i)
    for (int j = 0; j <= g.nz; ++j) x[g.at(i, j)] = (zero_axis && i == 0) ? 0.0 : U(rng);
  return x;
}

/// A partial pass against a full solve on the interior vertices: the largest difference from ref where
/// written(i, j), the size of ref there, and the largest change from before everywhere else.
struct PartialPass {
  double error = 0, scale = 0, untouched = 0;
};
template <class Written>
PartialPass compare_partial(const LevelGeometry& g, const std::vector<double>& x, const std::vector<double>& ref,
                            const std::vector<double>& before, Written written) {
  PartialPass r;
  for (int i = 1; i < g.nr; ++i)
    for (int j = 1; j < g.nz; ++j) {
      const std::size_t p = g.at(i, j);
      if (written(i, j)) {
        r.error = std::max(r.error, std::abs(x[p] - ref[p]));
        r.scale = std::max(r.scale, std::abs(ref[p]));
      } else {
        r.untouched = std::max(r.untouched, std::abs(x[p] - before[p]));
      }
    }
  return r;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

TEST(FlowOps, DivergenceOfStreamfunctionVelocityIsZero) {
  const auto g = tiny();
  const auto psi = random_field(g, 1);
  const FaceField u = face_velocity(g, psi);
  const auto q = cell_outflux(g, u);
  double scale = 0;  // typical face flux
  for (int i = 0; i < g.nr; ++i) scale = std::max(scale, 2 * M_PI * g.r(i + 0.5) * g.h * std::abs(u.uz[i * (g.nz + 1)]));
  std::printf("max |net outflux| = %.3e (face flux scale %.3e)\n", max_abs(q), scale);
  EXPECT_LT(max_abs(q), 1e-14 * scale * 10);
}

TEST(FlowOps, SolveThenApplyReturnsInput) {
  // nz = 20: the split-radix sine transform (nz a multiple of 4); nz = 18: the padded one
  for (int nz : {20, 18}) {
    const auto g = tiny(12, nz, 0.05, -0.5);
    FastSolver fs(g, {{0.0, 1.0}, {1.0, -0.37}, {2.5, -1e-3}});
    for (int op = 0; op < 3; ++op) {
      const double a = op == 0 ? 0.0 : op == 1 ? 1.0 : 2.5, b = op == 0 ? 1.0 : op == 1 ? -0.37 : -1e-3;
      auto x = random_field(g, 10 + op);  // boundary values (outer, top, bottom) are data
      const auto bnd = x;
      const auto f = random_field(g, 20 + op);
      fs.solve(op, f, x);
      std::vector<double> lap;
      apply_stokes_operator(g, x, lap);
      double err = 0, fmax = 0;
      for (int i = 1; i < g.nr; ++i)
        for (int j = 1; j < g.nz; ++j) {
          err = std::max(err, std::abs(a * x[g.at(i, j)] + b * lap[g.at(i, j)] - f[g.at(i, j)]));
          fmax = std::max(fmax, std::abs(f[g.at(i, j)]));
        }
      double bnd_err = 0;
      for (int j = 0; j <= g.nz; ++j) bnd_err = std::max(bnd_err, std::abs(x[g.at(g.nr, j)] - bnd[g.at(g.nr, j)]));
      std::printf("nz %d, op %d: max |(aI + bE²)x − f| / max|f| = %.3e\n", nz, op, err / fmax);
      EXPECT_LT(err / fmax, 1e-10);
      EXPECT_EQ(bnd_err, 0.0);
    }
  }
}

TEST(FlowOps, ChainedSolveInModeSpaceEqualsTwoSolves) {
  // A⁻¹ then P⁻¹ chained in mode space (rechain), with boundary values on both, rows < phys changed in between
  // (as coarsify does) and only the first rows transformed back, against two full solves
  for (int nz : {20, 18}) {
    const auto g = tiny(12, nz, 0.05, -0.5);
    FastSolver fs(g, {{0.0, 1.0}, {1.0, -0.37}});
    const int n = fs.rows(), phys = 4, out_rows = 7;
    fs.prepare_rows(phys);
    const auto f = random_field(g, 51);
    auto x1 = random_field(g, 52), x2 = random_field(g, 53);  // boundary values are data
    const auto x2_before = x2;
    auto changed = random_field(g, 54);
    auto r1 = x1, r2 = x2;  // reference: two solves
    fs.solve(1, f, r1);
    for (int i = 1; i <= phys; ++i)
      for (int j = 3; j < g.nz - 3; ++j) r1[g.at(i, j)] = changed[g.at(i, j)];
    std::vector<double> rhs(g.size());
    for (std::size_t p = 0; p < rhs.size(); ++p) rhs[p] = -r1[p];
    fs.solve(0, rhs, r2);
    fs.forward(1, 1.0, f, x1);  // chained
    fs.back(1, x1, n);
    for (int i = 1; i <= phys; ++i)
      for (int j = 3; j < g.nz - 3; ++j) x1[g.at(i, j)] = changed[g.at(i, j)];
    fs.rechain(0, -1.0, x1, x2, phys);
    fs.back(0, x2, out_rows);
    const auto c = compare_partial(g, x2, r2, x2_before, [&](int i, int) { return i <= out_rows; });
    std::printf("nz %d: chained vs two solves %.2e (scale %.2e)\n", nz, c.error, c.scale);
    EXPECT_LT(c.error, 1e-12 * c.scale);
    EXPECT_EQ(c.untouched, 0.0);
    // a right-hand side zero beyond row phys: forward_rows (those rows from the boundary terms alone) = solve
    auto fz = f;
    for (int i = phys + 1; i < g.nr; ++i)
      for (int j = 0; j <= g.nz; ++j) fz[g.at(i, j)] = 0.0;
    auto y1 = random_field(g, 55), y2 = y1;
    fs.solve(1, fz, y1);
    fs.forward_rows(1, 1.0, fz, y2, phys);
    fs.back(1, y2, n);
    double ey = 0, sy = 0;
    for (std::size_t p = 0; p < g.size(); ++p) {
      ey = std::max(ey, std::abs(y1[p] - y2[p]));
      sy = std::max(sy, std::abs(y1[p]));
    }
    EXPECT_LT(ey, 1e-12 * sy);
  }
}

TEST(FlowOps, BackProlongWritesTheSolveOnTheLinesProlongationReads) {
  // back_prolong (the solver's partial pass on a coarse level): the whole line full_row + 1 and the vertices
  // j = nz/4, 3nz/4 on lines 1..point_rows as a full solve gives them; every other interior vertex left alone
  const auto g = tiny(12, 20, 0.05, -0.5);
  FastSolver fs(g, {{0.0, 1.0}, {1.0, -0.37}});
  const int full_row = 5, point_rows = 7, j1 = g.nz / 4, j3 = 3 * g.nz / 4;
  for (int op = 0; op < 2; ++op) {
    const auto f = random_field(g, 60 + op);
    auto x = random_field(g, 70 + op), ref = x;
    const auto before = x;
    fs.solve(op, f, ref);
    fs.forward(op, 1.0, f, x);
    fs.back_prolong(op, x, full_row, point_rows);
    const auto c = compare_partial(g, x, ref, before, [&](int i, int j) {
      return i == full_row + 1 || (i <= point_rows && (j == j1 || j == j3));
    });
    std::printf("op %d: back_prolong vs solve %.2e (scale %.2e)\n", op, c.error, c.scale);
    EXPECT_LT(c.error, 1e-12 * c.scale);
    EXPECT_EQ(c.untouched, 0.0);
  }
  FastSolver padded(tiny(12, 18, 0.05, -0.5), {{0.0, 1.0}});  // nz not a multiple of 4: no quarter-point sums
  std::vector<double> y(tiny(12, 18, 0.05, -0.5).size(), 0.0);
  EXPECT_THROW(padded.back_prolong(0, y, 0, 1), std::logic_error);
}

TEST(FlowOps, SolveChainEqualsSuccessiveSolves) {
  const auto g = tiny(12, 20, 0.05, -0.5);
  FastSolver fs(g, {{0.0, 1.0}, {1.0, -0.37}});
  const auto f = random_field(g, 31);
  std::vector<double> c1, c2;
  fs.solve_chain({1, 0}, f, {&c1, &c2});
  std::vector<double> x1(g.size(), 0.0), x2(g.size(), 0.0);  // zero boundary values
  fs.solve(1, f, x1);
  fs.solve(0, x1, x2);
  double e1 = 0, e2 = 0, s = 0;
  for (std::size_t p = 0; p < g.size(); ++p) {
    e1 = std::max(e1, std::abs(c1[p] - x1[p]));
    e2 = std::max(e2, std::abs(c2[p] - x2[p]));
    s = std::max(s, std::abs(x2[p]));
  }
  EXPECT_LT(e1, 1e-12 * s);
  EXPECT_LT(e2, 1e-12 * s);
}

TEST(FlowOps, FastSolversPlannedOnSeveralThreadsAgree) {  // FFTW planning is serialised by FastSolver
  const auto g = tiny(16, 24, 0.05, -0.6);
  const auto f = random_field(g, 41);
  std::vector<double> ref(g.size(), 0.0);
  FastSolver(g, {{1.0, -0.2}}, true).solve(0, f, ref);
  std::vector<std::vector<double>> out(4, std::vector<double>(g.size(), 0.0));
  std::vector<std::thread> th;
  for (int t = 0; t < 4; ++t)
    th.emplace_back([&, t] {
      for (int rep = 0; rep < 20; ++rep) {
        FastSolver fs(g, {{1.0, -0.2}});
        fs.solve(0, f, out[t]);
      }
    });
  for (auto& t : th) t.join();
  for (const auto& o : out)
    for (std::size_t p = 0; p < g.size(); ++p) EXPECT_NEAR(o[p], ref[p], 1e-12 * (1 + std::abs(ref[p])));
}

TEST(FlowOps, StokesOperatorIsSecondOrderOnManufacturedSolution) {
  // ψ = r² exp(−r² − z²):  E²ψ = exp(−r² − z²) r² (4r² + 4z² − 10)
  double err_prev = 0;
  for (int n : {16, 32, 64}) {
    const double h = 4.0 / n;
    const auto g = tiny(n, 2 * n, h, -4.0);
    std::vector<double> psi(g.size()), lap;
    for (int i = 0; i <= g.nr; ++i)
      for (int j = 0; j <= g.nz; ++j) {
        const double r = g.r(i), z = g.z(j);
        psi[g.at(i, j)] = r * r * std::exp(-r * r - z * z);
      }
    apply_stokes_operator(g, psi, lap);
    double err = 0;
    for (int i = 1; i < g.nr; ++i)
      for (int j = 1; j < g.nz; ++j) {
        const double r = g.r(i), z = g.z(j);
        err = std::max(err, std::abs(lap[g.at(i, j)] - std::exp(-r * r - z * z) * r * r * (4 * r * r + 4 * z * z - 10)));
      }
    if (err_prev > 0) {
      std::printf("h = %.4f: max error %.3e, observed order %.2f\n", h, err, std::log2(err_prev / err));
      EXPECT_GT(std::log2(err_prev / err), 1.9);
    }
    err_prev = err;
  }
}

TEST(FlowOps, InterpolationAndSpreadingAreAdjointAndConserveForce) {
  const auto g = tiny(16, 32, 0.0625, -1.0);
  BodyPoints p;
  add_sphere_rings(p, 0.3, 0.05, g.h, 1.0, 0);
  ASSERT_GT(p.size(), 10u);
  const auto psi = random_field(g, 3);
  const FaceField u = face_velocity(g, psi);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<double> f(2 * p.size());
  for (double& x : f) x = U(rng);
  const FaceField Hf = spread(g, p, f);
  const FaceField W = face_weights(g);
  double lhs = 0, fz = 0, fr = 0, tz = 0, tr = 0;
  for (std::size_t m = 0; m < u.uz.size(); ++m) {
    lhs += W.uz[m] * u.uz[m] * Hf.uz[m];
    tz += W.uz[m] * Hf.uz[m];
  }
  for (std::size_t m = 0; m < u.ur.size(); ++m) {
    lhs += W.ur[m] * u.ur[m] * Hf.ur[m];
    tr += W.ur[m] * Hf.ur[m];
  }
  const auto Eu = interpolate(g, p, u);
  double rhs = 0;
  for (std::size_t k = 0; k < f.size(); ++k) rhs += f[k] * Eu[k];
  for (std::size_t k = 0; k < p.size(); ++k) {
    fr += f[2 * k];
    fz += f[2 * k + 1];
  }
  std::printf("<u, Hf>_W = %.15e, f.Eu = %.15e; total force z %.3e vs %.3e, r %.3e vs %.3e\n", lhs, rhs, tz, fz, tr, fr);
  EXPECT_NEAR(lhs, rhs, 1e-12 * std::abs(rhs));
  EXPECT_NEAR(tz, fz, 1e-12 * std::max(1.0, std::abs(fz)));
  EXPECT_NEAR(tr, fr, 1e-12 * std::max(1.0, std::abs(fr)));
  // B = E C matches the face route
  const auto B = velocity_at_points(g, p);
  Eigen::Map<const Eigen::VectorXd> ps(psi.data(), static_cast<Eigen::Index>(psi.size()));
  const Eigen::VectorXd Bpsi = B * ps;
  double d = 0;
  for (std::size_t k = 0; k < Eu.size(); ++k) d = std::max(d, std::abs(Bpsi[k] - Eu[k]));
  EXPECT_LT(d, 1e-12 * max_abs(Eu));
}

TEST(FlowOps, DeltaKernelMomentsAndUniformStreamInterpolation) {
  for (double x : {0.0, 0.13, 0.5, 0.77}) {
    double s0 = 0, s1 = 0, s2 = 0;
    for (int i = -3; i <= 3; ++i) {
      const double w = rpb_delta(x - i);
      s0 += w;
      s1 += (x - i) * w;
      s2 += w * w;
    }
    EXPECT_NEAR(s0, 1.0, 1e-14);
    EXPECT_NEAR(s1, 0.0, 1e-14);
    EXPECT_NEAR(s2, 0.5, 1e-14);  // RPB: Σφ² = 1/2 for every shift
  }
  // ψ∞ = ½Ur² gives u_z = U exactly on every face and E²ψ∞ = 0
  const auto g = tiny();
  std::vector<double> psi(g.size()), lap;
  for (int i = 0; i <= g.nr; ++i)
    for (int j = 0; j <= g.nz; ++j) psi[g.at(i, j)] = 0.5 * 1.7 * g.r(i) * g.r(i);
  apply_stokes_operator(g, psi, lap);
  EXPECT_LT(max_abs(lap), 1e-12);
  const auto u = face_velocity(g, psi);
  for (double v : u.uz) EXPECT_NEAR(v, 1.7, 1e-13);
}

TEST(FlowOps, ForceSystemIsNearlySymmetricWithPositiveDefiniteSymmetricPart) {
  // One level: Q = Δt B(−E²)⁻¹(I − θνΔtE²)⁻¹R Bᵀ/(2πh²) is symmetric positive definite (E²/r symmetric).
  // Three levels: the multi-level inverses (full-weighting restriction, cubic boundary interpolation, which are not
  // adjoint) make Q slightly nonsymmetric; it stays positive definite in the sense xᵀQx > 0 (its symmetric part).
  for (int levels : {1, 3}) {
    Settings s;
    s.nu = 0.1;
    s.dt = 0.01;
    s.h = 1.0 / 8;
    s.nr = 12;
    s.nz = 24;
    s.levels = levels;
    Solver solver(s, {{0.5, 0.0, 0.0}});
    const Eigen::MatrixXd Q = solver.force_matrix();
    const Eigen::Index m = Q.rows();
    const double asym = (Q - Q.transpose()).cwiseAbs().maxCoeff() / Q.cwiseAbs().maxCoeff();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (Q + Q.transpose()));
    std::printf("%d level(s): Q %ld x %ld, asymmetry %.2e, eigenvalues of its symmetric part [%.3e, %.3e]\n", levels, (long)m, (long)m,
                asym, es.eigenvalues().minCoeff(), es.eigenvalues().maxCoeff());
    EXPECT_LT(asym, levels == 1 ? 1e-10 : 1e-4);  // measured 1.6e-16 and 9.7e-6
    EXPECT_GT(es.eigenvalues().minCoeff(), 0.0);
  }
}

TEST(FlowOps, LevelTransfersAreExactForSmoothPolynomials) {
  // cubic boundary interpolation and full weighting reproduce ψ = r²(1 + z) (even in r, cubic overall)
  Settings s;
  s.nu = 1;
  s.dt = 1;
  s.h = 0.1;
  s.nr = 8;
  s.nz = 16;
  s.levels = 2;
  Solver solver(s, {{0.2, 0.0, 0.0}});
  const Level& f = solver.levels()[0];
  const Level& c = solver.levels()[1];
  auto fill = [](const LevelGeometry& g) {
    std::vector<double> v(g.size());
    for (int i = 0; i <= g.nr; ++i)
      for (int j = 0; j <= g.nz; ++j) v[g.at(i, j)] = g.r(i) * g.r(i) * (1 + g.z(j));
    return v;
  };
  const auto exact_f = fill(f.g);
  std::vector<double> ff(f.g.size(), 0.0);
  Solver::prolong_boundary(c, fill(c.g), f, ff);
  double e = 0;
  for (int i = 0; i <= f.g.nr; ++i) e = std::max({e, std::abs(ff[f.g.at(i, 0)] - exact_f[f.g.at(i, 0)]), std::abs(ff[f.g.at(i, f.g.nz)] - exact_f[f.g.at(i, f.g.nz)])});
  for (int j = 0; j <= f.g.nz; ++j) e = std::max(e, std::abs(ff[f.g.at(f.g.nr, j)] - exact_f[f.g.at(f.g.nr, j)]));
  EXPECT_LT(e, 1e-13);
  std::vector<double> fc = fill(c.g), fc2(c.g.size(), 0.0);
  Solver::restrict_interior(f, exact_f, c, fc2);
  // full weighting of r²(1+z) is r²(1+z) + h²(1+z)/2 exactly
  double er = 0;
  for (int I = 1; I < f.g.nr / 2; ++I)
    for (int J = f.g.nz / 4 + 1; J < 3 * f.g.nz / 4; ++J)
      er = std::max(er, std::abs(fc2[c.g.at(I, J)] - (fc[c.g.at(I, J)] + 0.5 * f.g.h * f.g.h * (1 + c.g.z(J)))));
  EXPECT_LT(er, 1e-13);
}
