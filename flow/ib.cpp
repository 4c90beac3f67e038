// SPDX-License-Identifier: BSD-3-Clause
#include "flow/ib.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace imcol::flow {

double rpb_delta(double x) {
  const double a = std::abs(x);
  if (a <= 0.5) return (1.0 + std::sqrt(1.0 - 3.0 * a * a)) / 3.0;
  if (a <= 1.5) return (5.0 - 3.0 * a - std::sqrt(std::max(0.0, 1.0 - 3.0 * (1.0 - a) * (1.0 - a)))) / 6.0;
  return 0.0;
}

void add_sphere_rings(BodyPoints& pts, double a, double zc, double h, double spacing, int body_id) {
  const int n = std::max(2, static_cast<int>(std::ceil(M_PI * a / (spacing * h))));
  for (int k = 0; k < n; ++k) {
    const double th = (k + 0.5) * M_PI / n;
    pts.r.push_back(a * std::sin(th));
    pts.z.push_back(zc - a * std::cos(th));
    pts.ds.push_back(M_PI * a / n);
    pts.body.push_back(body_id);
  }
}

FaceField face_velocity(const LevelGeometry& g, const std::vector<double>& psi) {
  FaceField u;
  u.uz.assign(static_cast<std::size_t>(g.nr) * (g.nz + 1), 0.0);
  u.ur.assign(static_cast<std::size_t>(g.nr + 1) * g.nz, 0.0);
  for (int i = 0; i < g.nr; ++i)
    for (int j = 0; j <= g.nz; ++j)
      u.uz[static_cast<std::size_t>(i) * (g.nz + 1) + j] = (psi[g.at(i + 1, j)] - psi[g.at(i, j)]) / (g.h * g.r(i + 0.5));
  for (int i = 1; i <= g.nr; ++i)
    for (int j = 0; j < g.nz; ++j)
      u.ur[static_cast<std::size_t>(i) * g.nz + j] = -(psi[g.at(i, j + 1)] - psi[g.at(i, j)]) / (g.h * g.r(i));
  return u;
}

FaceField face_weights(const LevelGeometry& g) {
  FaceField w;
  w.uz.assign(static_cast<std::size_t>(g.nr) * (g.nz + 1), 0.0);
  w.ur.assign(static_cast<std::size_t>(g.nr + 1) * g.nz, 0.0);
  const double h2 = g.h * g.h;
  for (int i = 0; i < g.nr; ++i)
    for (int j = 0; j <= g.nz; ++j) w.uz[static_cast<std::size_t>(i) * (g.nz + 1) + j] = 2 * M_PI * g.r(i + 0.5) * h2;
  for (int i = 0; i <= g.nr; ++i)
    for (int j = 0; j < g.nz; ++j) w.ur[static_cast<std::size_t>(i) * g.nz + j] = 2 * M_PI * g.r(i) * h2;
  return w;
}

std::vector<double> cell_outflux(const LevelGeometry& g, const FaceField& u) {
  std::vector<double> q(static_cast<std::size_t>(g.nr) * g.nz);
  for (int i = 0; i < g.nr; ++i)
    for (int j = 0; j < g.nz; ++j) {
      const double az = 2 * M_PI * g.r(i + 0.5) * g.h;  // annulus area π(r_{i+1}² − r_i²)
      const double out_z = az * (u.uz[static_cast<std::size_t>(i) * (g.nz + 1) + j + 1] - u.uz[static_cast<std::size_t>(i) * (g.nz + 1) + j]);
      const double out_r = 2 * M_PI * g.h * (g.r(i + 1) * u.ur[static_cast<std::size_t>(i + 1) * g.nz + j] - g.r(i) * u.ur[static_cast<std::size_t>(i) * g.nz + j]);
      q[static_cast<std::size_t>(i) * g.nz + j] = out_z + out_r;
    }
  return q;
}

namespace {
// stencil of one face component at (r, z): up to 4 × 4 faces; returns the count
int stencil_fixed(const LevelGeometry& g, double r, double z, int comp, int* face, double* wt) {
  const double xr = r / g.h, xz = (z - g.z0) / g.h;
  // face centre offsets: comp 1 (u_z): r at i+½, z at j; comp 0 (u_r): r at i, z at j+½
  const double orr = comp == 1 ? 0.5 : 0.0, ozz = comp == 1 ? 0.0 : 0.5;
  const int i0 = static_cast<int>(std::ceil(xr - orr - 1.5)), i1 = static_cast<int>(std::floor(xr - orr + 1.5));
  const int j0 = static_cast<int>(std::ceil(xz - ozz - 1.5)), j1 = static_cast<int>(std::floor(xz - ozz + 1.5));
  const int imin = comp == 1 ? 0 : 1, imax = comp == 1 ? g.nr - 1 : g.nr;
  const int jmax = comp == 1 ? g.nz : g.nz - 1;
  if (j0 < 0 || j1 > jmax || i1 > imax) throw std::runtime_error("body point too close to the finest grid's boundary");
  double norm = 0;
  int n = 0;
  for (int i = std::max(i0, imin); i <= i1; ++i)
    for (int j = j0; j <= j1; ++j) {
      const double w = rpb_delta(i + orr - xr) * rpb_delta(j + ozz - xz) * 2 * M_PI * g.r(i + orr) * g.h * g.h;
      if (w == 0) continue;
      face[n] = comp == 1 ? i * (g.nz + 1) + j : i * g.nz + j;
      wt[n++] = w;
      norm += w;
    }
  if (!(norm > 0)) throw std::runtime_error("empty interpolation stencil");
  for (int k = 0; k < n; ++k) wt[k] /= norm;
  return n;
}
}  // namespace

Stencil interp_stencil(const LevelGeometry& g, double r, double z, int comp) {
  int face[16];
  double w[16];
  const int n = stencil_fixed(g, r, z, comp, face, w);
  return {std::vector<int>(face, face + n), std::vector<double>(w, w + n)};
}

std::vector<double> interpolate(const LevelGeometry& g, const BodyPoints& p, const FaceField& u) {
  std::vector<double> out(2 * p.size(), 0.0);
  for (std::size_t k = 0; k < p.size(); ++k)
    for (int c = 0; c < 2; ++c) {
      const Stencil s = interp_stencil(g, p.r[k], p.z[k], c);
      const auto& field = c == 1 ? u.uz : u.ur;
      double v = 0;
      for (std::size_t m = 0; m < s.face.size(); ++m) v += s.w[m] * field[s.face[m]];
      out[2 * k + c] = v;
    }
  return out;
}

FaceField spread(const LevelGeometry& g, const BodyPoints& p, const std::vector<double>& f) {
  FaceField out;
  out.uz.assign(static_cast<std::size_t>(g.nr) * (g.nz + 1), 0.0);
  out.ur.assign(static_cast<std::size_t>(g.nr + 1) * g.nz, 0.0);
  const FaceField W = face_weights(g);
  for (std::size_t k = 0; k < p.size(); ++k)
    for (int c = 0; c < 2; ++c) {
      const Stencil s = interp_stencil(g, p.r[k], p.z[k], c);
      auto& field = c == 1 ? out.uz : out.ur;
      const auto& wf = c == 1 ? W.uz : W.ur;
      for (std::size_t m = 0; m < s.face.size(); ++m) field[s.face[m]] += s.w[m] * f[2 * k + c] / wf[s.face[m]];
    }
  return out;
}

void velocity_rows(const LevelGeometry& g, const BodyPoints& p, PointRows& out) {
  out.start.assign(1, 0);
  out.col.clear();
  out.val.clear();
  int face[16];
  double sw[16];
  for (std::size_t k = 0; k < p.size(); ++k)
    for (int c = 0; c < 2; ++c) {
      const int n = stencil_fixed(g, p.r[k], p.z[k], c, face, sw);
      const std::size_t row0 = out.col.size();
      auto add = [&](int col, double w) {  // merge duplicate columns in insertion order, keep columns sorted
        std::size_t e = row0;
        while (e < out.col.size() && out.col[e] < col) ++e;
        if (e < out.col.size() && out.col[e] == col) {
          out.val[e] += w;
          return;
        }
        out.col.insert(out.col.begin() + static_cast<std::ptrdiff_t>(e), col);
        out.val.insert(out.val.begin() + static_cast<std::ptrdiff_t>(e), w);
      };
      for (int m = 0; m < n; ++m) {
        const int f = face[m];
        if (c == 1) {  // u_z face (i+½, j)
          const int i = f / (g.nz + 1), j = f % (g.nz + 1);
          const double w = sw[m] / (g.h * g.r(i + 0.5));
          add(static_cast<int>(g.at(i + 1, j)), w);
          if (i > 0) add(static_cast<int>(g.at(i, j)), -w);  // ψ = 0 on the axis
        } else {       // u_r face (i, j+½)
          const int i = f / g.nz, j = f % g.nz;
          const double w = sw[m] / (g.h * g.r(i));
          add(static_cast<int>(g.at(i, j + 1)), -w);
          add(static_cast<int>(g.at(i, j)), w);
        }
      }
      out.start.push_back(static_cast<int>(out.col.size()));
    }
}

int PointRows::max_line(const LevelGeometry& g) const {
  int m = 0;
  for (int c : col) m = std::max(m, c / (g.nz + 1));
  return m;
}

void PointRows::apply(const double* psi, double* u) const {
  for (int k = 0; k < rows(); ++k) {
    double v = 0;
    for (int e = start[k]; e < start[k + 1]; ++e) v += val[e] * psi[col[e]];
    u[k] = v;
  }
}

void PointRows::apply_transpose_add(const double* f, double* s) const {
  for (int k = 0; k < rows(); ++k)
    for (int e = start[k]; e < start[k + 1]; ++e) s[col[e]] += val[e] * f[k];
}

Eigen::SparseMatrix<double, Eigen::RowMajor> velocity_at_points(const LevelGeometry& g, const BodyPoints& p) {
  PointRows rows;
  velocity_rows(g, p, rows);
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < rows.rows(); ++k)
    for (int e = rows.start[k]; e < rows.start[k + 1]; ++e) t.emplace_back(k, rows.col[e], rows.val[e]);
  Eigen::SparseMatrix<double, Eigen::RowMajor> B(static_cast<int>(2 * p.size()), static_cast<int>(g.size()));
  B.setFromTriplets(t.begin(), t.end());
  return B;
}

}  // namespace imcol::flow
