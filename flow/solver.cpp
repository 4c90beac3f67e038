// SPDX-License-Identifier: BSD-3-Clause
#include "flow/solver.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"

namespace imcol::flow {

namespace {
double cubic_mid(double a, double b, double c, double d) { return (-a + 9 * b + 9 * c - d) / 16.0; }
}  // namespace

Solver::Solver(const Settings& s, std::vector<SphereState> spheres) : s_(s), sph_(std::move(spheres)) {
  if (!(s.nu > 0) || !(s.dt > 0) || !(s.h > 0) || !(s.density > 0)) throw std::invalid_argument("flow: nu, dt, h, density must be > 0");
  if (s.nr < 4 || s.nr % 2 || s.nz < 8 || s.nz % 4) throw std::invalid_argument("flow: nr must be even >= 4, nz a multiple of 4 >= 8");
  if (s.levels < 1) throw std::invalid_argument("flow: levels must be >= 1");
  if (!(s.theta >= 0.5 && s.theta <= 1)) throw std::invalid_argument("flow: theta must be in [0.5, 1]");
  if (s.preconditioner_bins < 1) throw std::invalid_argument("flow: preconditioner_bins must be >= 1");
  if (s.block_probe_stride < 0) throw std::invalid_argument("flow: block_probe_stride must be >= 0");
  if (!(s.krylov_tol > 0) || s.krylov_max_iter < 1) throw std::invalid_argument("flow: krylov_tol must be > 0, krylov_max_iter >= 1");
  for (int l = 0; l < s.levels; ++l) {
    Level L;
    L.g.nr = s.nr;
    L.g.nz = s.nz;
    L.g.h = s.h * std::ldexp(1.0, l);
    L.g.z0 = s.z_center - 0.5 * s.nz * L.g.h;
    L.fast = std::make_unique<FastSolver>(L.g, std::vector<FastSolver::Op>{{0.0, 1.0}, {1.0, -s.theta * s.nu * s.dt}}, s.measure_plans);
    L.eta.assign(L.g.size(), 0.0);
    L.psi.assign(L.g.size(), 0.0);
    L.nl_old.assign(L.g.size(), 0.0);
    for (auto* v : {&L.rhs, &L.src, &L.etac, &L.psic}) v->assign(L.g.size(), 0.0);
    lv_.push_back(std::move(L));
  }
  // before the first step the fluid (inside the spheres too) moves with the initial flow: ψ = 0, velocity U∞
  u_in_.assign(sph_.size(), s.u_inf);
  build_wall();
  build_points(sph_);
  plan_rows();
}

void Solver::update_rows() {
  const int nr = s_.nr, rows = nr - 1;
  coarse_rows_ = nr / 2 - 1;   // restrict_interior writes lines 1..nr/2 − 1
  prolong_rows_ = nr / 2 + 1;  // prolong_boundary reads coarse lines up to nr/2 + 1
  psi_rows_.assign(lv_.size(), 1);
  src_rows_.assign(lv_.size(), 1);
  for (std::size_t l = 0; l < lv_.size(); ++l) {
    int points = l == 0 ? B_.max_line(lv_[0].g) : 0;  // the last line the level's rings read and spread onto
    if (l < Bw_.size()) points = std::max(points, Bw_[l].max_line(lv_[l].g));
    // ψ: also the lines the finer level's boundary values read; the source: coarsify fills rows < coarse_rows
    psi_rows_[l] = std::min(std::max(points, l > 0 ? prolong_rows_ : 1), rows);
    src_rows_[l] = std::min(std::max(points, l > 0 ? coarse_rows_ : 1), rows);
  }
}

void Solver::plan_rows() {
  update_rows();
  for (std::size_t l = 0; l < lv_.size(); ++l) {
    FastSolver& F = *lv_[l].fast;
    F.prepare_rows(psi_rows_[l]);
    F.prepare_rows(src_rows_[l]);
    if (l > 0) F.prepare_rows(coarse_rows_);
    if (l + 1 == lv_.size() && l > 0) F.prepare_rows(prolong_rows_);
  }
}

std::size_t Solver::bytes() const {
  std::size_t b = 0;
  for (const auto& L : lv_) b += 7 * L.g.size() * sizeof(double) + L.fast->bytes();
  b += B_.val.size() * (sizeof(double) + sizeof(int));
  if (lu_) b += static_cast<std::size_t>(lu_->matrixLU().size()) * sizeof(double);
  for (const auto& B : Bw_) b += B.val.size() * (sizeof(double) + sizeof(int));
  for (const auto& L : lv_) b += L.eta_modes.size() * sizeof(double);
  if (wall_block_.lu) b += static_cast<std::size_t>(wall_block_.lu->matrixLU().size()) * sizeof(double);
  for (const auto& bins : prec_cache_)
    for (const auto& blk : bins)
      if (blk.lu) b += static_cast<std::size_t>(blk.lu->matrixLU().size()) * sizeof(double);
  for (const auto& r : ref_blocks_) b += static_cast<std::size_t>(r.q.size()) * sizeof(double);
  return b;
}

void Solver::build_points(const std::vector<SphereState>& sp) {
  const LevelGeometry& g = lv_[0].g;
  pts_.r.clear();  // keeps the capacities: rebuilding the same spheres' points allocates nothing
  pts_.z.clear();
  pts_.ds.clear();
  pts_.body.clear();
  for (std::size_t k = 0; k < sp.size(); ++k) {
    const auto& b = sp[k];
    const double margin = 3 * g.h;
    if (!(b.radius > 0)) throw std::invalid_argument("flow: sphere radius must be > 0");
    if (b.z - b.radius < g.z0 + margin || b.z + b.radius > g.z(g.nz) - margin || b.radius > g.r(g.nr) - margin)
      throw std::runtime_error("flow: sphere " + std::to_string(k + 1) + " leaves the finest grid (keep 3 cells clear)");
    if (s_.wall_z && std::abs(b.z - *s_.wall_z) <= b.radius)
      throw std::runtime_error("flow: sphere " + std::to_string(k + 1) + " touches or crosses the wall at z = " + std::to_string(*s_.wall_z));
    add_sphere_rings(pts_, b.radius, b.z, g.h, s_.ring_spacing, static_cast<int>(k));
  }
  velocity_rows(g, pts_, B_);
  if (!psi_rows_.empty()) update_rows();  // the same rows while the radii stay (plans are made in the constructor)
}

void Solver::build_wall() {
  wall_pts_.assign(lv_.size(), BodyPoints{});
  Bw_.clear();
  wall_count_ = 0;
  if (!s_.wall_z) return;
  const double zw = *s_.wall_z;
  if (!std::isfinite(zw)) throw std::invalid_argument("flow: wall_z must be finite");
  for (std::size_t l = 0; l < lv_.size(); ++l) {
    const LevelGeometry& g = lv_[l].g;
    if (zw < g.z0 + 3 * g.h || zw > g.z(g.nz) - 3 * g.h)
      throw std::invalid_argument("flow: the wall z = " + std::to_string(zw) + " must lie inside the finest level, 3 cells clear");
    // finest level from the axis out; each coarser level outside the finer one (its source is never overwritten by
    // coarsify: restrict_interior writes coarse vertices I < nr/2 only, and the stencil of a ring at r ≥ (nr/2 + 1)H
    // touches vertices I ≥ nr/2); each level's out to R − 2.5H, where a ring's stencil still ends on interior
    // vertices (i ≤ nr − 1) that the full weighting carries to the coarser level: with rings closer to the edge the
    // plate's edge vorticity was dropped and a uniform pressure jump across it became nearly invisible (a spurious
    // uniform load, 6 times the sphere's force)
    const double sp = s_.ring_spacing * g.h;
    double r = l == 0 ? 0.5 * sp : (g.nr / 2 + 1) * g.h;
    const double rmax = g.r(g.nr) - 2.5 * g.h;
    auto& P = wall_pts_[l];
    for (; r <= rmax * (1 + 1e-12); r += sp) {
      P.r.push_back(r);
      P.z.push_back(zw);
      P.ds.push_back(sp);
      P.body.push_back(-1);
    }
    Bw_.emplace_back();
    velocity_rows(g, P, Bw_.back());
    wall_count_ += P.size();
  }
}

void Solver::point_velocity(std::vector<double> Level::*psi, Eigen::VectorXd& u) const {
  const Eigen::Index ns = static_cast<Eigen::Index>(2 * pts_.size());
  u.resize(ns + static_cast<Eigen::Index>(2 * wall_count_));
  B_.apply((lv_[0].*psi).data(), u.data());
  Eigen::Index o = ns;
  for (std::size_t l = 0; l < Bw_.size(); ++l) {
    Bw_[l].apply((lv_[l].*psi).data(), u.data() + o);
    o += Bw_[l].rows();
  }
}

void Solver::nonlinear(const Level& L, double u_inf, std::vector<double>& out) {
  const LevelGeometry& g = L.g;
  const int nr = g.nr, nz = g.nz, W = nz + 1;
  const double h = g.h;
  // face velocities: uz at (i+½, j) [i < nr], ur at (i, j+½) [j < nz], ω at vertices. Scratch kept per thread:
  // sized once, then only the entries read below are written (ur, ω on the axis are 0)
  thread_local std::vector<double> uz, ur, om;
  if (uz.size() < g.size()) {
    uz.resize(g.size());
    ur.resize(g.size());
    om.resize(g.size());
  }
  std::fill_n(ur.begin(), W, 0.0);
  std::fill_n(om.begin(), W, 0.0);
  const double* psi = L.psi.data();
  for (int i = 0; i < nr; ++i) {
    const double c = 1.0 / (h * g.r(i + 0.5));
    for (int j = 0; j <= nz; ++j) uz[i * W + j] = (psi[(i + 1) * W + j] - psi[i * W + j]) * c + u_inf;
  }
  for (int i = 1; i <= nr; ++i) {
    const double c = -1.0 / (h * g.r(i)), ir = 1.0 / g.r(i);
    for (int j = 0; j < nz; ++j) ur[i * W + j] = (psi[i * W + j + 1] - psi[i * W + j]) * c;
    for (int j = 0; j <= nz; ++j) om[i * W + j] = L.eta[i * W + j] * ir;
  }
  if (out.size() != g.size()) out.assign(g.size(), 0.0);
  std::fill_n(out.begin(), W, 0.0);  // boundary: axis, outer line, bottom and top
  std::fill_n(out.begin() + static_cast<std::ptrdiff_t>(nr) * W, W, 0.0);
  for (int i = 1; i < nr; ++i) {
    const double f = -g.r(i) / h;
    const double* uzm = &uz[(i - 1) * W];
    const double* uz0 = &uz[i * W];
    const double* urm = &ur[(i - 1) * W];
    const double* ur0 = &ur[i * W];
    const double* urp = &ur[(i + 1) * W];
    const double* omm = &om[(i - 1) * W];
    const double* om0 = &om[i * W];
    const double* omp = &om[(i + 1) * W];
    double* o = &out[i * W];
    for (int j = 1; j < nz; ++j) {
      const double uzu = 0.25 * (uzm[j] + uz0[j] + uzm[j + 1] + uz0[j + 1]);
      const double uzd = 0.25 * (uzm[j - 1] + uz0[j - 1] + uzm[j] + uz0[j]);
      const double uro = 0.25 * (ur0[j - 1] + ur0[j] + urp[j - 1] + urp[j]);
      const double uri = 0.25 * (urm[j - 1] + urm[j] + ur0[j - 1] + ur0[j]);
      const double fz = uzu * 0.5 * (om0[j] + om0[j + 1]) - uzd * 0.5 * (om0[j] + om0[j - 1]);
      const double fr = uro * 0.5 * (om0[j] + omp[j]) - uri * 0.5 * (om0[j] + omm[j]);
      o[j] = f * (fz + fr);
    }
    o[0] = o[nz] = 0.0;
  }
}

void Solver::prolong_boundary(const Level& coarse, const std::vector<double>& fc, const Level& fine, std::vector<double>& ff) {
  const LevelGeometry &c = coarse.g, &f = fine.g;
  const int off = f.nz / 4;
  auto C = [&](int I, int J) { return fc[c.at(std::abs(I), J)]; };  // even in r across the axis
  for (int jf : {0, f.nz}) {                                         // bottom and top lines, all i
    const int J = jf / 2 + off;
    for (int i = 0; i <= f.nr; ++i)
      ff[f.at(i, jf)] = (i % 2 == 0) ? C(i / 2, J) : cubic_mid(C((i - 1) / 2 - 1, J), C((i - 1) / 2, J), C((i + 1) / 2, J), C((i + 1) / 2 + 1, J));
  }
  const int I = f.nr / 2;  // outer line, all j
  for (int j = 0; j <= f.nz; ++j) {
    const int J = j / 2 + off;
    ff[f.at(f.nr, j)] = (j % 2 == 0) ? C(I, J) : cubic_mid(C(I, J - 1), C(I, J), C(I, J + 1), C(I, J + 2));
  }
}

void Solver::restrict_interior(const Level& fine, const std::vector<double>& ff, const Level& coarse, std::vector<double>& fc) {
  const LevelGeometry &c = coarse.g, &f = fine.g;
  const int off = f.nz / 4;
  for (int I = 1; I < f.nr / 2; ++I) {
    const int i = 2 * I;
    const double* fm = &ff[f.at(i - 1, 0)];
    const double* f0 = &ff[f.at(i, 0)];
    const double* fp = &ff[f.at(i + 1, 0)];
    double* out = &fc[c.at(I, 0)];
    for (int J = off + 1; J < off + f.nz / 2; ++J) {
      const int j = 2 * (J - off);
      out[J] = (4 * f0[j] + 2 * (fp[j] + fm[j] + f0[j + 1] + f0[j - 1]) + fp[j + 1] + fp[j - 1] + fm[j + 1] + fm[j - 1]) / 16.0;
    }
  }
}

void Solver::coarsify(std::vector<double> Level::*field) {
  for (std::size_t l = 0; l + 1 < lv_.size(); ++l) restrict_interior(lv_[l], lv_[l].*field, lv_[l + 1], lv_[l + 1].*field);
}

void Solver::pass_viscous(std::vector<double> Level::*rhs, std::vector<double> Level::*eta, bool partial) {
  coarsify(rhs);
  const int NL = static_cast<int>(lv_.size());
  for (int l = NL - 1; l >= 0; --l) {
    Level& L = lv_[l];
    if (l + 1 < NL) prolong_boundary(lv_[l + 1], lv_[l + 1].*eta, L, L.*eta);
    if (rhs == &Level::src)  // zero beyond src_rows_
      L.fast->forward_rows(1, 1.0, L.*rhs, L.*eta, src_rows_[l]);
    else
      L.fast->forward(1, 1.0, L.*rhs, L.*eta);
    // the coarsest level feeds only the next finer level's boundary values and its own coarsified rows
    const int rows = partial && l == NL - 1 ? (NL > 1 ? prolong_rows_ : 0) : L.fast->rows();
    L.fast->back(1, L.*eta, rows);
  }
}

void Solver::pass_streamfunction(std::vector<double> Level::*eta, std::vector<double> Level::*psi, bool partial, bool add_saved) {
  coarsify(eta);
  const int NL = static_cast<int>(lv_.size());
  for (int l = NL - 1; l >= 0; --l) {
    Level& L = lv_[l];
    if (l + 1 < NL) prolong_boundary(lv_[l + 1], lv_[l + 1].*psi, L, L.*psi);
    if (add_saved) L.fast->add_modes(L.eta_modes);
    // E²ψ = −η: from the modes of η where coarsify left η alone, transformed afresh on the coarsified rows
    L.fast->rechain(0, -1.0, L.*eta, L.*psi, l > 0 ? coarse_rows_ : 0);
    if (partial && l > 0 && psi_rows_[l] <= prolong_rows_)  // read only by the finer level's boundary values
      L.fast->back_prolong(0, L.*psi, s_.nr / 2 - 1, prolong_rows_);
    else
      L.fast->back(0, L.*psi, partial ? psi_rows_[l] : L.fast->rows());
  }
}

void Solver::spread_source(const Eigen::VectorXd& g) {
  // source on the finest level: Δt R Bᵀg/(2πh²) at interior vertices; restricted onto every coarser level
  // (with a wall: each level's wall rings spread onto their own level too, outside the finer level)
  const Eigen::Index ns = static_cast<Eigen::Index>(2 * pts_.size());
  Eigen::Index o = ns;
  for (std::size_t l = 0; l < lv_.size(); ++l) {
    Level& L = lv_[l];
    const LevelGeometry& G = L.g;
    const bool has = l == 0 || l < Bw_.size();
    if (!has) continue;  // filled by coarsify (zero outside the finer level, never written)
    std::fill(L.src.begin(), L.src.end(), 0.0);
    if (l == 0) B_.apply_transpose_add(g.data(), L.src.data());
    if (l < Bw_.size()) {
      Bw_[l].apply_transpose_add(g.data() + o, L.src.data());
      o += Bw_[l].rows();
    }
    // The axis and each line's ends are zeroed; Bᵀg reaches lines up to src_rows_[l] only, the lines beyond stay
    // the zeros of the fill.
    std::fill_n(&L.src[G.at(0, 0)], G.nz + 1, 0.0);
    const double scale = s_.dt / (2 * M_PI * G.h * G.h);
    for (int i = 1; i <= src_rows_[l]; ++i) {
      double* row = &L.src[G.at(i, 0)];
      const double c = scale * G.r(i);
      row[0] = row[G.nz] = 0.0;
      for (int j = 1; j < G.nz; ++j) row[j] *= c;
    }
  }
}

void Solver::apply_Q_into(const Eigen::VectorXd& g, Eigen::VectorXd& out) {
  ++q_applications_;
  spread_source(g);
  pass_viscous(&Level::src, &Level::etac, true);
  pass_streamfunction(&Level::etac, &Level::psic, true, false);
  point_velocity(&Level::psic, out);
}

void Solver::final_pass(const Eigen::VectorXd& g) {
  spread_source(g);
  pass_viscous(&Level::src, &Level::etac, false);
  eta_sq_.resize(lv_.size());
  for (std::size_t l = 0; l < lv_.size(); ++l) {  // η = η* + ηc, and Σ η² for check_finite
    Level& L = lv_[l];
    double sum = 0;
    for (std::size_t p = 0; p < L.eta.size(); ++p) {
      L.etac[p] += L.eta[p];
      sum += L.etac[p] * L.etac[p];
    }
    eta_sq_[l] = sum;
  }
  pass_streamfunction(&Level::etac, &Level::psic, false, true);
  point_velocity(&Level::psic, u_);
}

Eigen::MatrixXd Solver::force_matrix() { return diagonal_block_of_Q(0, static_cast<Eigen::Index>(2 * (pts_.size() + wall_count_))); }

Eigen::MatrixXd Solver::diagonal_block_of_Q(Eigen::Index o, Eigen::Index n) {
  const Eigen::Index m = static_cast<Eigen::Index>(2 * (pts_.size() + wall_count_));
  Eigen::MatrixXd blk(n, n);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(m), q;
  for (Eigen::Index c = 0; c < n; ++c) {
    e[o + c] = 1.0;
    apply_Q_into(e, q);
    blk.col(c) = q.segment(o, n);
    e[o + c] = 0.0;
    if (block_progress_) block_progress_(static_cast<long>(c + 1), static_cast<long>(n));
  }
  return blk;
}

Eigen::MatrixXd Solver::corrected_block_of_Q(Eigen::Index o, const Eigen::MatrixXd& base, int stride) {
  const Eigen::Index n = base.rows(), np = n / 2;
  const Eigen::Index m = static_cast<Eigen::Index>(2 * (pts_.size() + wall_count_));
  if (stride < 1 || n % 2 != 0 || base.cols() != n || o < 0 || o + n > m)
    throw std::invalid_argument("flow: corrected_block_of_Q needs stride >= 1 and a square block of whole points inside Q");
  const Eigen::Index sd = std::min<Eigen::Index>(stride, np);
  Eigen::MatrixXd blk = base;
  Eigen::VectorXd e = Eigen::VectorXd::Zero(m), el(n), q;
  long done = 0;
  for (int comp = 0; comp < 2; ++comp)
    for (Eigen::Index c = 0; c < sd; ++c) {
      e.setZero();
      el.setZero();
      for (Eigen::Index k = c; k < np; k += sd) e[o + 2 * k + comp] = el[2 * k + comp] = 1.0;
      apply_Q_into(e, q);
      const Eigen::VectorXd d = q.segment(o, n) - base * el;  // the change, summed over this probe's points
      const Eigen::Index last = c + sd * ((np - 1 - c) / sd);
      for (Eigen::Index i = 0; i < np; ++i) {
        const double near = std::round(static_cast<double>(i - c) / static_cast<double>(sd));
        const Eigen::Index k = std::clamp(c + sd * static_cast<Eigen::Index>(near), c, last);
        blk(2 * i, 2 * k + comp) += d[2 * i];
        blk(2 * i + 1, 2 * k + comp) += d[2 * i + 1];
      }
      if (block_progress_) block_progress_(++done, static_cast<long>(2 * sd));
    }
  return blk;
}

void Solver::explicit_rhs() {
  // The explicit part of the vorticity equation on every level (advection AB2, viscous (1 − θ)); the finer levels'
  // right-hand sides replace the coarser ones where they overlap in pass_viscous (coarsify).
  const double dt = s_.dt, nu = s_.nu, th = s_.theta;
  for (Level& L : lv_) {
    nonlinear(L, s_.u_inf, nl_);
    const double r = n_ == 0 ? 0.0 : dt / dt_last_;  // 1 at a constant step: 1.5, −0.5
    const double ab_new = 1 + 0.5 * r, ab_old = -0.5 * r;
    // interior only (the solves and coarsify read no boundary values of rhs)
    const double* eta = L.eta.data();
    const double* nn = nl_.data();
    const double* no = L.nl_old.data();
    double* rr = L.rhs.data();
    for_each_stokes(L.g, L.eta, [&](std::size_t p, double lap) {
      rr[p] = eta[p] + dt * ((1 - th) * nu * lap + ab_new * nn[p] + ab_old * no[p]);
    });
    std::swap(L.nl_old, nl_);
  }
}

void Solver::set_force_rhs(const std::vector<SphereState>& next) {
  const Eigen::Index ns = static_cast<Eigen::Index>(2 * pts_.size());
  const Eigen::Index m = ns + static_cast<Eigen::Index>(2 * wall_count_);
  target_.resize(m);
  rhs_.resize(m);
  for (Eigen::Index k = 0; k < m / 2; ++k) {
    target_[2 * k] = 0.0;
    target_[2 * k + 1] = (k < ns / 2 ? next[pts_.body[k]].u : s_.wall_velocity) - s_.u_inf;
  }
  point_velocity(&Level::psi, u_);
  rhs_ = target_ - u_;
  if (g_.size() != m) {
    g_ = Eigen::VectorXd::Zero(m);
    g_prev_.resize(0);
  }
}

bool Solver::use_direct(const std::vector<SphereState>& next, bool moved) {
  // Bodies still from the start: the LU at once. Bodies that stopped after moving (a sphere held at the smallest
  // gap): GMRES until the work it spent there would have built the LU (one application of Q per column).
  ever_moved_ = ever_moved_ || moved;
  if (moved) still_work_ = 0;
  if (!s_.direct_when_fixed || moved) return false;
  if (!ever_moved_ || lu_current(next)) return true;
  return still_work_ >= static_cast<long>(2 * (pts_.size() + wall_count_));
}

bool Solver::lu_current(const std::vector<SphereState>& next) const {
  bool same_z = lu_ && lu_dt_ == s_.dt && fixed_z_.size() == next.size();
  for (std::size_t k = 0; same_z && k < next.size(); ++k) same_z = fixed_z_[k] == next[k].z;
  return same_z;
}

void Solver::solve_direct(const std::vector<SphereState>& next) {
  if (!lu_current(next)) {
    lu_ = std::make_unique<Eigen::PartialPivLU<Eigen::MatrixXd>>(force_matrix());
    lu_dt_ = s_.dt;
    fixed_z_.resize(next.size());
    for (std::size_t k = 0; k < next.size(); ++k) fixed_z_[k] = next[k].z;
  }
  g_prev_ = g_;  // keeps a later GMRES warm start current
  g_ = lu_->solve(rhs_);
  final_pass(g_);
}

void Solver::build_preconditioner(const std::vector<SphereState>& next) {
  // Each sphere's own block of Q, factorised for its sub-cell offset on the finest grid (one of preconditioner_bins
  // bins centred on the offset of the sphere's first block, each built the first time a sphere is there): the rings'
  // pattern relative to the grid repeats when a sphere moves by whole cells, and the multi-level Q is nearly
  // translation invariant.
  prec_.clear();
  const LevelGeometry& G = lv_[0].g;
  const int bins = s_.preconditioner_bins;
  if (prec_cache_.size() < next.size()) prec_cache_.resize(next.size());
  if (prec_origin_.size() < next.size()) prec_origin_.resize(next.size(), std::nan(""));
  if (offset_forces_.size() < next.size()) offset_forces_.resize(next.size());
  for (std::size_t k = 0; k < pts_.size();) {
    std::size_t e = k;
    while (e < pts_.size() && pts_.body[e] == pts_.body[k]) ++e;
    const int b = pts_.body[k];
    const Eigen::Index o = static_cast<Eigen::Index>(2 * k), n = static_cast<Eigen::Index>(2 * (e - k));
    const double x = (next[b].z - G.z0) / G.h;
    if (std::isnan(prec_origin_[b])) prec_origin_[b] = x - std::floor(x);
    const double u = x - prec_origin_[b];  // offset from the first block's
    const int bin = static_cast<int>(std::lround((u - std::floor(u)) * bins)) % bins;
    auto& slot = prec_cache_[b];
    if (slot.size() != static_cast<std::size_t>(bins)) slot.assign(bins, {});
    if (!block_current(slot[bin], n)) {
      slot[bin] = {sphere_block(o, n, next[b].radius), s_.dt};
      ++prec_builds_;
    }
    auto& forces = offset_forces_[b];
    if (forces.size() != static_cast<std::size_t>(bins)) forces.assign(bins, {});
    prec_.push_back({o, n, slot[bin].lu, slot[bin].dt / s_.dt, &forces[bin]});
    k = e;
  }
  if (wall_count_ > 0) {  // the wall's own block: it never moves, so one factorisation serves the run (set_dt: scaled)
    const Eigen::Index ns = static_cast<Eigen::Index>(2 * pts_.size());
    const Eigen::Index nw = static_cast<Eigen::Index>(2 * wall_count_);
    if (!block_current(wall_block_, nw)) {
      wall_block_ = {std::make_shared<BlockLU>(diagonal_block_of_Q(ns, nw)), s_.dt};
      ++prec_builds_;
    }
    prec_.push_back({ns, nw, wall_block_.lu, wall_block_.dt / s_.dt, nullptr});
  }
}

bool Solver::close_step(double dt_block) const {
  const double h = lv_[0].g.h;
  return s_.theta * s_.nu * std::abs(s_.dt - dt_block) / (h * h) <= kBlockViscousChange;
}

bool Solver::block_current(const CachedBlock& c, Eigen::Index n) const { return c.lu && c.lu->rows() == n && close_step(c.dt); }

std::shared_ptr<Solver::BlockLU> Solver::sphere_block(Eigen::Index o, Eigen::Index n, double radius) {
  auto ref = std::find_if(ref_blocks_.begin(), ref_blocks_.end(), [&](const ReferenceBlock& r) { return r.radius == radius; });
  if (s_.block_probe_stride > 0 && ref != ref_blocks_.end() && ref->q.rows() == n && close_step(ref->dt))
    return std::make_shared<BlockLU>(corrected_block_of_Q(o, ref->q * (s_.dt / ref->dt), s_.block_probe_stride));
  Eigen::MatrixXd q = diagonal_block_of_Q(o, n);
  auto lu = std::make_shared<BlockLU>(q);
  if (ref == ref_blocks_.end()) ref = ref_blocks_.insert(ref_blocks_.end(), ReferenceBlock{radius, {}, 0});
  *ref = {radius, std::move(q), s_.dt};
  return lu;
}

void Solver::set_dt(double dt) {
  if (!(dt > 0) || !std::isfinite(dt)) throw std::invalid_argument("flow: dt must be > 0");
  if (dt == s_.dt) return;
  s_.dt = dt;
  for (Level& L : lv_) L.fast->set_op(1, {1.0, -s_.theta * s_.nu * dt});
}

void Solver::solve_gmres(const std::vector<SphereState>& next, StepInfo& info) {
  build_preconditioner(next);
  warm_start();
  const auto [it, res] = gmres(rhs_);
  keep_offset_forces();
  info.krylov_iterations = it;
  info.krylov_residual = res;
}

void Solver::warm_start() {
  if (g_prev_.size() == g_.size()) {  // linear extrapolation of the last two steps' forces
    t1_ = g_;
    g_ = 2 * g_ - g_prev_;
    g_prev_.swap(t1_);
  } else {
    g_prev_ = g_;
  }
  if (!s_.warm_start_by_offset) return;
  const double t_new = t_ + s_.dt;
  for (const auto& blk : prec_) {
    if (!blk.forces || blk.forces->last.size() != blk.size) continue;  // the wall's block, or a bin not yet visited
    const OffsetForces& f = *blk.forces;
    // Linear in time through the bin's last two steps while they are no further apart than this one from the last
    // (a sphere at constant speed: equally spaced); else the last alone.
    const double ratio = f.t_last > f.t_before ? (t_new - f.t_last) / (f.t_last - f.t_before) : -1;
    auto seg = g_.segment(blk.offset, blk.size);
    if (f.before.size() == blk.size && ratio >= 0 && ratio <= 1.5)
      seg = f.last + (f.last - f.before) * ratio;
    else
      seg = f.last;
  }
}

void Solver::keep_offset_forces() {
  if (!s_.warm_start_by_offset) return;
  for (const auto& blk : prec_) {
    if (!blk.forces) continue;
    OffsetForces& f = *blk.forces;
    f.before.swap(f.last);
    f.t_before = f.t_last;
    f.last = g_.segment(blk.offset, blk.size);
    f.t_last = t_ + s_.dt;
  }
}

void Solver::sphere_forces(const std::vector<SphereState>& next, StepInfo& info) {
  // Ring forces + the momentum change of the fluid inside (from u_in to U^{n+1}).
  const Eigen::Index ns = static_cast<Eigen::Index>(2 * pts_.size()), m = g_.size();
  info.force.assign(next.size(), 0.0);
  info.internal.assign(next.size(), 0.0);
  for (std::size_t k = 0; k < pts_.size(); ++k) info.force[pts_.body[k]] -= s_.density * g_[2 * k + 1];
  for (Eigen::Index k = ns / 2; k < m / 2; ++k) info.wall_force -= s_.density * g_[2 * k + 1];
  for (std::size_t b = 0; b < next.size(); ++b) {
    const double V = 4.0 / 3.0 * M_PI * std::pow(next[b].radius, 3);
    info.internal[b] = s_.density * V * (next[b].u - u_in_[b]) / s_.dt;
    info.force[b] += info.internal[b];
    u_in_[b] = next[b].u;  // no-slip: the fluid inside now moves with the sphere
  }
}

StepInfo Solver::step(const std::vector<SphereState>& next) {
  if (next.size() != sph_.size()) throw std::invalid_argument("flow: sphere count changed");
  if (s_.wall_z && s_.u_inf != s_.wall_velocity)
    throw std::invalid_argument("flow: with a wall the far fluid must move with it (u_inf = wall_velocity): a stream cannot cross the plate");
  // 1. explicit part of the vorticity equation on every level
  explicit_rhs();
  // 2–3. vorticity predictor η* (its modes kept for the end of the step) and ψ* where the points read it
  pass_viscous(&Level::rhs, &Level::eta, false);
  for (auto& L : lv_) L.fast->save_modes(L.eta_modes);
  pass_streamfunction(&Level::eta, &Level::psi, true, false);
  // 4. body forces: Q g = U_b − U∞ e_z − Bψ*, Q the multi-level operator of apply_Q_into; LU while the spheres
  //    stand still (direct_when_fixed), else GMRES, warm start, right-preconditioned by each sphere's own block of Q
  StepInfo info;
  bool moved = false;
  for (std::size_t k = 0; k < next.size(); ++k) moved = moved || next[k].z != sph_[k].z;
  if (moved || pts_.size() == 0) build_points(next);
  set_force_rhs(next);
  if (use_direct(next, moved)) {
    solve_direct(next);
  } else {
    solve_gmres(next, info);
    if (!moved) still_work_ += info.krylov_iterations + 3;  // applications of Q: the iterations, warm start, passes
  }
  // final_pass(g_) is current: η = η* + A⁻¹Sg and ψ = P⁻¹η on every level, u_ the velocities at the points
  for (auto& L : lv_) {
    L.eta.swap(L.etac);
    L.psi.swap(L.psic);
  }
  for (Eigen::Index k = 0; k < g_.size() / 2; ++k) {
    info.slip = std::max(info.slip, std::abs(u_[2 * k]));
    info.slip = std::max(info.slip, std::abs(u_[2 * k + 1] - target_[2 * k + 1]));
  }
  // 5. forces on the spheres
  sphere_forces(next, info);
  sph_ = next;
  t_ += s_.dt;
  dt_last_ = s_.dt;
  ++n_;
  check_finite(info);
  return info;
}

void Solver::check_finite(const StepInfo& info) const {
  auto fail = [&](const std::string& what) {
    std::ostringstream os;
    os << std::scientific << std::setprecision(4) << "flow diverged at t = " << t_ << " s (step " << n_ << "): " << what
       << " (lower the flow time step, refine the grid, or check the scene)";
    throw SolverError(os.str());
  };
  for (std::size_t b = 0; b < info.force.size(); ++b)
    if (!std::isfinite(info.force[b])) fail("the force on sphere " + std::to_string(b + 1) + " is not finite");
  if (!std::isfinite(info.wall_force)) fail("the force on the wall is not finite");
  if (!std::isfinite(info.slip)) fail("the slip velocity at the body points is not finite");
  for (std::size_t l = 0; l < lv_.size(); ++l) {
    if (!std::isfinite(eta_sq_[l])) fail("the vorticity on level " + std::to_string(l) + " is not finite");
  }
}

void Solver::precondition(const Eigen::Ref<const Eigen::VectorXd>& r, Eigen::VectorXd& z) const {
  z.resize(r.size());
  for (const auto& blk : prec_) z.segment(blk.offset, blk.size) = blk.scale * blk.lu->solve(r.segment(blk.offset, blk.size));
}

// One piece: the restarts, the Arnoldi process and the Givens updates share H_, e_, the basis and the counts.
std::pair<int, double> Solver::gmres(const Eigen::VectorXd& b) {
  // Restarted GMRES (Saad & Schultz 1986) on Q g = b with right preconditioning M⁻¹ = per-sphere block
  // inverses. Convergence is judged on the true residual ‖b − Qg‖/‖b‖, recomputed at every restart and
  // after the Givens estimate says converged: there as target − Bψ of the step's end (final_pass), which is
  // b − Qg up to rounding, so that a converged g needs no further solve.
  const int restart = s_.krylov_restart;
  const Eigen::Index n = b.size();
  const double bn = std::max(b.norm(), 1e-300);
  if (V_.rows() != n || V_.cols() != restart + 1) {
    V_.resize(n, restart + 1);
    H_.resize(restart + 1, restart);
    cs_.resize(restart);
    sn_.resize(restart);
    e_.resize(restart + 1);
    y_.resize(restart);
  }
  int it = 0;
  bool first = true;
  for (;;) {
    if (first) {  // warm start: Q g from the partial passes; the final pass follows convergence
      apply_Q_into(g_, w_);
      r_ = b - w_;
      first = false;
    } else {
      final_pass(g_);
      r_ = target_ - u_;
    }
    const double beta = r_.norm(), rel = beta / bn;
    if (rel <= s_.krylov_tol) {
      if (it == 0) final_pass(g_);  // the warm start was good enough
      return {it, rel};
    }
    if (it >= s_.krylov_max_iter) {
      std::ostringstream os;
      os << std::scientific << std::setprecision(3) << "flow: GMRES did not converge in " << it
         << " iterations: true relative residual " << rel << " > flow.krylov_tol = " << s_.krylov_tol
         << " (raise flow.krylov_max_iter or flow.krylov_restart, or loosen flow.krylov_tol)";
      throw SolverError(os.str());
    }
    H_.setZero();
    e_.setZero();
    V_.col(0) = r_ / beta;
    e_[0] = beta;
    int k = 0;  // columns of the Krylov basis in use
    while (k < restart && it < s_.krylov_max_iter) {
      ++it;
      precondition(V_.col(k), z_);
      apply_Q_into(z_, w_);
      for (int i = 0; i <= k; ++i) {  // modified Gram–Schmidt
        H_(i, k) = V_.col(i).dot(w_);
        w_ -= H_(i, k) * V_.col(i);
      }
      H_(k + 1, k) = w_.norm();
      if (H_(k + 1, k) > 0) V_.col(k + 1) = w_ / H_(k + 1, k);
      for (int i = 0; i < k; ++i) {  // apply the previous Givens rotations
        const double t = cs_[i] * H_(i, k) + sn_[i] * H_(i + 1, k);
        H_(i + 1, k) = -sn_[i] * H_(i, k) + cs_[i] * H_(i + 1, k);
        H_(i, k) = t;
      }
      const double d = std::hypot(H_(k, k), H_(k + 1, k));
      if (d == 0) break;  // breakdown: the basis so far holds the solution
      cs_[k] = H_(k, k) / d;
      sn_[k] = H_(k + 1, k) / d;
      H_(k, k) = d;
      H_(k + 1, k) = 0;
      e_[k + 1] = -sn_[k] * e_[k];
      e_[k] = cs_[k] * e_[k];
      ++k;
      if (std::abs(e_[k]) / bn <= s_.krylov_tol) break;  // estimate converged: the true residual decides above
    }
    if (k == 0) {
      std::ostringstream os;
      os << std::scientific << std::setprecision(3) << "flow: GMRES broke down at relative residual " << rel
         << " (check flow.krylov_tol and flow.krylov_restart)";
      throw SolverError(os.str());
    }
    y_.head(k) = e_.head(k);
    H_.topLeftCorner(k, k).triangularView<Eigen::Upper>().solveInPlace(y_.head(k));
    t1_.noalias() = V_.leftCols(k) * y_.head(k);
    precondition(t1_, z_);
    g_ += z_;
  }
}

std::vector<double> Solver::axis_velocity() const {
  const Level& L = lv_[0];
  const LevelGeometry& g = L.g;
  std::vector<double> u(g.nz + 1);
  for (int j = 0; j <= g.nz; ++j) {
    const double u1 = L.psi[g.at(1, j)] / (g.h * g.r(0.5));
    const double u2 = (L.psi[g.at(2, j)] - L.psi[g.at(1, j)]) / (g.h * g.r(1.5));
    u[j] = (9 * u1 - u2) / 8 + s_.u_inf;  // quadratic in r (u_z is even in r)
  }
  return u;
}

double Solver::max_courant() const {
  const Level& L = lv_[0];
  const LevelGeometry& g = L.g;
  const double* psi = L.psi.data();
  double m = 0;
  for (int i = 1; i < g.nr; ++i) {
    const double* p0 = psi + g.at(i, 0);
    const double* p1 = psi + g.at(i + 1, 0);
    const double cz = 1.0 / (g.h * g.r(i + 0.5)), cr = 1.0 / (g.h * g.r(i));
    for (int j = 0; j < g.nz; ++j) {
      const double uz = (p1[j] - p0[j]) * cz + s_.u_inf, ur = (p0[j + 1] - p0[j]) * cr;
      m = std::max(m, std::abs(uz) + std::abs(ur));
    }
  }
  return m * s_.dt / g.h;
}

double Solver::wake_length(int s) const {
  const LevelGeometry& g = lv_[0].g;
  const auto u = axis_velocity();
  const int dir = s_.u_inf >= 0 ? 1 : -1;
  const double rear = sph_[s].z + dir * sph_[s].radius;
  // first vertex at least h/2 downstream of the rear, then walk while the axial velocity is reversed
  int j = dir > 0 ? static_cast<int>(std::ceil((rear + 0.5 * g.h - g.z0) / g.h)) : static_cast<int>(std::floor((rear - 0.5 * g.h - g.z0) / g.h));
  if (j < 0 || j > g.nz || dir * u[j] >= 0) return 0.0;
  for (; j + dir >= 0 && j + dir <= g.nz; j += dir) {
    const double v0 = dir * u[j], v1 = dir * u[j + dir];
    if (v1 >= 0) {
      const double zc = g.z(j) + dir * g.h * (-v0) / (v1 - v0);
      return std::abs(zc - rear);
    }
  }
  return std::abs(g.z(j) - rear);  // reversed up to the grid's end
}

}  // namespace imcol::flow
