#include "flow/solver.hpp"

#include <algorithm>
#include <cmath>
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
  if (!(s.cg_tol > 0) || s.cg_max_iter < 1) throw std::invalid_argument("flow: cg_tol must be > 0, cg_max_iter >= 1");
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
    lv_.push_back(std::move(L));
  }
  build_points(sph_);
}

std::size_t Solver::bytes() const {
  std::size_t b = 0;
  for (const auto& L : lv_) b += 3 * L.g.size() * sizeof(double) + L.fast->bytes();
  b += static_cast<std::size_t>(B_.nonZeros()) * (sizeof(double) + sizeof(int));
  if (chol_) b += static_cast<std::size_t>(chol_->matrixLLT().size()) * sizeof(double);
  return b;
}

void Solver::build_points(const std::vector<SphereState>& sp) {
  const LevelGeometry& g = lv_[0].g;
  pts_ = BodyPoints{};
  for (std::size_t k = 0; k < sp.size(); ++k) {
    const auto& b = sp[k];
    const double margin = 3 * g.h;
    if (!(b.radius > 0)) throw std::invalid_argument("flow: sphere radius must be > 0");
    if (b.z - b.radius < g.z0 + margin || b.z + b.radius > g.z(g.nz) - margin || b.radius > g.r(g.nr) - margin)
      throw std::runtime_error("flow: sphere " + std::to_string(k + 1) + " leaves the finest grid (keep 3 cells clear)");
    add_sphere_rings(pts_, b.radius, b.z, g.h, s_.ring_spacing, static_cast<int>(k));
  }
  B_ = velocity_at_points(g, pts_);
  for (std::size_t l = 1; l < lv_.size(); ++l) lv_[l].B = velocity_at_points(lv_[l].g, pts_);
}

void Solver::nonlinear(const Level& L, double u_inf, std::vector<double>& out) {
  const LevelGeometry& g = L.g;
  const int nr = g.nr, nz = g.nz, W = nz + 1;
  const double h = g.h;
  // face velocities: uz at (i+½, j) [i < nr], ur at (i, j+½) [j < nz], ω at vertices
  thread_local std::vector<double> uz, ur, om;
  uz.assign(g.size(), 0.0);
  ur.assign(g.size(), 0.0);
  om.assign(g.size(), 0.0);
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
  out.assign(g.size(), 0.0);
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
  for (int I = 1; I < f.nr / 2; ++I)
    for (int J = off + 1; J < off + f.nz / 2; ++J) {
      const int i = 2 * I, j = 2 * (J - off);
      auto F = [&](int di, int dj) { return ff[f.at(i + di, j + dj)]; };
      fc[c.at(I, J)] = (4 * F(0, 0) + 2 * (F(1, 0) + F(-1, 0) + F(0, 1) + F(0, -1)) + F(1, 1) + F(1, -1) + F(-1, 1) + F(-1, -1)) / 16.0;
    }
}

Eigen::VectorXd Solver::apply_Q(const Eigen::VectorXd& g, std::vector<double>* eta_c, std::vector<double>* psi_c) {
  Level& L = lv_[0];
  const LevelGeometry& G = L.g;
  work_.resize(G.size());
  Eigen::Map<Eigen::VectorXd> s(work_.data(), static_cast<Eigen::Index>(work_.size()));
  s.noalias() = B_.transpose() * g;
  const double scale = s_.dt / (2 * M_PI * G.h * G.h);
  for (int i = 0; i <= G.nr; ++i)
    for (int j = 0; j <= G.nz; ++j) work_[G.at(i, j)] *= (i == 0 || i == G.nr || j == 0 || j == G.nz) ? 0.0 : scale * G.r(i);
  std::vector<double>& x = psi_c ? *psi_c : xq_;
  L.fast->solve_chain({1, 0}, work_, {eta_c, &x});
  for (double& v : x) v = -v;
  Eigen::Map<const Eigen::VectorXd> px(x.data(), static_cast<Eigen::Index>(x.size()));
  return B_ * px;
}

StepInfo Solver::step(const std::vector<SphereState>& next) {
  if (next.size() != sph_.size()) throw std::invalid_argument("flow: sphere count changed");
  const int NL = static_cast<int>(lv_.size());
  const double dt = s_.dt, nu = s_.nu, th = s_.theta;
  // 1. advection terms at t^n, each level
  thread_local std::vector<std::vector<double>> nl;
  nl.resize(NL);
  for (int l = 0; l < NL; ++l) nonlinear(lv_[l], s_.u_inf, nl[l]);
  // 2. vorticity predictor, coarsest to finest (boundary values at t^{n+1} from the coarser level)
  std::vector<double>& lap = work2_;
  std::vector<double>& rv = work3_;
  for (int l = NL - 1; l >= 0; --l) {
    Level& L = lv_[l];
    const double ab_new = n_ == 0 ? 1.0 : 1.5, ab_old = n_ == 0 ? 0.0 : -0.5;
    apply_stokes_operator(L.g, L.eta, lap);
    rv.resize(L.g.size());
    for (std::size_t p = 0; p < rv.size(); ++p) rv[p] = L.eta[p] + dt * ((1 - th) * nu * lap[p] + ab_new * nl[l][p] + ab_old * L.nl_old[p]);
    std::swap(L.nl_old, nl[l]);
    if (l > 0 && g_.size() == L.B.rows()) {  // lagged body force on the coarser levels
      work_.resize(L.g.size());
      Eigen::Map<Eigen::VectorXd> sp(work_.data(), static_cast<Eigen::Index>(work_.size()));
      sp.noalias() = L.B.transpose() * g_;
      const double sc = dt / (2 * M_PI * L.g.h * L.g.h);
      for (int i = 1; i < L.g.nr; ++i)
        for (int j = 1; j < L.g.nz; ++j) rv[L.g.at(i, j)] += sc * L.g.r(i) * sp[static_cast<Eigen::Index>(L.g.at(i, j))];
    }
    if (l + 1 < NL) prolong_boundary(lv_[l + 1], lv_[l + 1].eta, L, L.eta);
    L.fast->solve(1, rv, L.eta);
  }
  // 3. (the coarser levels keep their own predictor, which carries the lagged body force)
  // 4. streamfunction, coarsest to finest
  for (int l = NL - 1; l >= 0; --l) {
    Level& L = lv_[l];
    if (l + 1 < NL) prolong_boundary(lv_[l + 1], lv_[l + 1].psi, L, L.psi);
    rv.resize(L.eta.size());
    for (std::size_t p = 0; p < rv.size(); ++p) rv[p] = -L.eta[p];
    L.fast->solve(0, rv, L.psi);
  }
  // 5. body forces on the finest level
  StepInfo info;
  std::vector<double> zs;
  for (const auto& b : next) zs.push_back(b.z);
  bool moved = false;
  for (std::size_t k = 0; k < next.size(); ++k) moved = moved || next[k].z != sph_[k].z;
  if (moved || pts_.size() == 0) build_points(next);
  Level& F = lv_[0];
  const Eigen::Index m = static_cast<Eigen::Index>(2 * pts_.size());
  Eigen::VectorXd rhs(m);
  {
    Eigen::Map<const Eigen::VectorXd> ps(F.psi.data(), static_cast<Eigen::Index>(F.psi.size()));
    Eigen::VectorXd u = B_ * ps;
    for (std::size_t k = 0; k < pts_.size(); ++k) {
      rhs[2 * k] = -u[2 * k];
      rhs[2 * k + 1] = next[pts_.body[k]].u - s_.u_inf - u[2 * k + 1];
    }
  }
  if (g_.size() != m) g_ = Eigen::VectorXd::Zero(m);
  const bool use_direct = s_.direct_when_fixed && !moved;
  if (use_direct) {
    if (!chol_ || fixed_z_ != zs) {
      Eigen::MatrixXd Q(m, m);
      for (Eigen::Index c = 0; c < m; ++c) Q.col(c) = apply_Q(Eigen::VectorXd::Unit(m, c));
      Q = 0.5 * (Q + Q.transpose()).eval();
      chol_ = std::make_unique<Eigen::LLT<Eigen::MatrixXd>>(Q);
      if (chol_->info() != Eigen::Success) throw std::runtime_error("flow: force system is not positive definite");
      fixed_z_ = zs;
    }
    g_ = chol_->solve(rhs);
  } else {  // conjugate gradients, warm start; preconditioner: each sphere's own block of Q, factorised once
    if (prec_size_ != m) {  // at the first configuration (the rings move rigidly with their sphere)
      Eigen::MatrixXd Q0(m, m);
      for (Eigen::Index c = 0; c < m; ++c) Q0.col(c) = apply_Q(Eigen::VectorXd::Unit(m, c));
      prec_.clear();
      for (std::size_t k = 0; k < pts_.size();) {
        std::size_t e = k;
        while (e < pts_.size() && pts_.body[e] == pts_.body[k]) ++e;
        const Eigen::Index o = static_cast<Eigen::Index>(2 * k), n = static_cast<Eigen::Index>(2 * (e - k));
        Eigen::MatrixXd blk = 0.5 * (Q0.block(o, o, n, n) + Q0.block(o, o, n, n).transpose());
        prec_.push_back({o, n, Eigen::LLT<Eigen::MatrixXd>(blk)});
        k = e;
      }
      prec_size_ = m;
    }
    auto precondition = [&](const Eigen::VectorXd& r) {
      Eigen::VectorXd z(r.size());
      for (const auto& b : prec_) z.segment(b.offset, b.size) = b.llt.solve(r.segment(b.offset, b.size));
      return z;
    };
    Eigen::VectorXd r = rhs - apply_Q(g_);
    Eigen::VectorXd z = precondition(r);
    Eigen::VectorXd p = z;
    double rz = r.dot(z);
    const double bn = std::max(rhs.norm(), 1e-300);
    int it = 0;
    double rn = r.norm();
    while (rn > s_.cg_tol * bn) {
      if (++it > s_.cg_max_iter)
        throw SolverError("flow: CG did not converge in " + std::to_string(s_.cg_max_iter) + " iterations (relative residual " +
                          std::to_string(rn / bn) + ", tolerance " + std::to_string(s_.cg_tol) + ")");
      const Eigen::VectorXd Ap = apply_Q(p);
      const double alpha = rz / p.dot(Ap);
      g_ += alpha * p;
      r -= alpha * Ap;
      z = precondition(r);
      const double rz2 = r.dot(z);
      p = z + (rz2 / rz) * p;
      rz = rz2;
      rn = r.norm();
    }
    info.cg_iterations = it;
    info.cg_residual = rn / bn;
  }
  std::vector<double>& eta_c = eta_c_;
  std::vector<double>& psi_c = psi_c_;
  apply_Q(g_, &eta_c, &psi_c);
  for (std::size_t p = 0; p < F.eta.size(); ++p) {
    F.eta[p] += eta_c[p];
    F.psi[p] += psi_c[p];
  }
  for (int l = 0; l + 1 < NL; ++l) restrict_interior(lv_[l], lv_[l].eta, lv_[l + 1], lv_[l + 1].eta);
  {
    Eigen::Map<const Eigen::VectorXd> ps(F.psi.data(), static_cast<Eigen::Index>(F.psi.size()));
    Eigen::VectorXd u = B_ * ps;
    for (std::size_t k = 0; k < pts_.size(); ++k) {
      info.slip = std::max(info.slip, std::abs(u[2 * k]));
      info.slip = std::max(info.slip, std::abs(u[2 * k + 1] + s_.u_inf - next[pts_.body[k]].u));
    }
  }
  // 6. forces on the spheres
  info.force.assign(next.size(), 0.0);
  info.internal.assign(next.size(), 0.0);
  for (std::size_t k = 0; k < pts_.size(); ++k) info.force[pts_.body[k]] -= s_.density * g_[2 * k + 1];
  for (std::size_t b = 0; b < next.size(); ++b) {
    const double V = 4.0 / 3.0 * M_PI * std::pow(next[b].radius, 3);
    info.internal[b] = s_.density * V * (next[b].u - sph_[b].u) / dt;
    info.force[b] += info.internal[b];
  }
  sph_ = next;
  t_ += dt;
  ++n_;
  return info;
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
