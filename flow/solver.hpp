#pragma once
// Axisymmetric incompressible Navier–Stokes around spheres on the axis by the immersed-boundary projection
// method in streamfunction (nullspace) form: Taira & Colonius, J. Comput. Phys. 225 (2007); Colonius & Taira,
// Comput. Methods Appl. Mech. Eng. 197 (2008). Our own implementation of MODEL.md §4.
//
// Unknowns per level: η = rω at vertices (m/s) and the disturbance streamfunction ψ (m³/s), E²ψ = −η; the
// total streamfunction is ψ + ½U∞r² (a uniform stream U∞ along +z carries no vorticity). Vorticity transport
//   ∂η/∂t = −r[∂z(u_z ω) + ∂r(u_r ω)] + ν E²η + (force term),
// viscous term θ-implicit (θ = ½: Crank–Nicolson), advection Adams–Bashforth-2 (Euler on the first step).
// The body forces g (ring totals, m⁴/s² = N per kg/m³) are the Lagrange multipliers of no-slip at the ring
// points: with B = E C (velocity at the points from ψ) and the force term Δt R Bᵀg/(2πh²) in η,
//   Q g = U_b − U∞e_z − Bψ*,   Q = Δt B (−E²)⁻¹ (I − θνΔt E²)⁻¹ R Bᵀ /(2πh²)   (symmetric positive definite),
// solved by Cholesky of the dense Q when the bodies have not moved, by conjugate gradients otherwise (relative
// residual cg_tol; preconditioned by each sphere's own block of Q at the first configuration, factorised once).
// Levels: ℓ = 0 finest (spacing h), level ℓ has spacing 2^ℓ h and the same nr × nz cells, all centred on
// z_center; the coarsest has η = ψ = 0 on its outer boundary, each finer level takes its boundary values from
// the next coarser one (cubic interpolation), and its interior replaces the coarser level's interior (full weighting).
// Force on sphere s (N, along +z): F_s = −ρ Σ_{k∈s} g_z,k + ρ V_s dU_s/dt (the second term: the fluid inside).
#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

#include "flow/grid.hpp"
#include "flow/ib.hpp"

namespace imcol::flow {

struct Settings {
  double nu = 0;              // kinematic viscosity, m²/s
  double density = 1;         // kg/m³ (forces are reported in N = ρ × kinematic force)
  double dt = 0;              // time step, s
  double theta = 0.5;         // implicit weight of the viscous term (0.5 = Crank–Nicolson, 1 = backward Euler)
  double h = 0;               // finest grid spacing, m
  int nr = 0, nz = 0;         // cells per level (nr even, nz a multiple of 4)
  int levels = 1;             // nested levels
  double z_center = 0;        // z of the centre of all levels, m
  double u_inf = 0;           // uniform stream along +z, m/s
  double cg_tol = 1e-10;      // CG: relative residual ‖Qg − b‖ ≤ cg_tol ‖b‖
  int cg_max_iter = 1000;     // CG: iteration limit (exceeded -> std::runtime_error)
  double ring_spacing = 1.0;  // arc spacing of the body rings, units of h
  bool direct_when_fixed = true;  // Cholesky of Q while the bodies stay put
  bool measure_plans = false;     // FFTW_MEASURE instead of FFTW_ESTIMATE
};

/// One sphere on the axis at one instant.
struct SphereState {
  double radius = 0;  // m
  double z = 0;       // centre, m
  double u = 0;       // velocity along +z, m/s
};

struct StepInfo {
  std::vector<double> force;     // N on each sphere along +z (ring forces + internal fluid)
  std::vector<double> internal;  // N, the internal-fluid part ρ V dU/dt
  int cg_iterations = 0;         // 0 with the direct solve
  double cg_residual = 0;        // relative
  double slip = 0;               // max |u − U_b| at the body points after the step, m/s
};

struct Level {
  LevelGeometry g;
  std::unique_ptr<FastSolver> fast;  // ops: 0 = E² (Poisson), 1 = I − θνΔt E² (viscous)
  std::vector<double> eta, psi, nl_old;
  Eigen::SparseMatrix<double, Eigen::RowMajor> B;  // velocity at the body points (levels >= 1: for spreading)
};

class Solver {
 public:
  Solver(const Settings& s, std::vector<SphereState> spheres);
  /// Advances one step; `next` are the spheres at t + dt (same count and radii). Returns the forces at t + dt.
  StepInfo step(const std::vector<SphereState>& next);

  double time() const { return t_; }
  long steps() const { return n_; }
  const Settings& settings() const { return s_; }
  const std::vector<Level>& levels() const { return lv_; }
  const std::vector<SphereState>& spheres() const { return sph_; }
  const BodyPoints& points() const { return pts_; }
  /// Axial velocity on the axis of the finest level (extrapolated from r = h/2, 3h/2), at z_j, m/s.
  std::vector<double> axis_velocity() const;
  /// Recirculation length behind sphere s (downstream of its rear, in the stream direction), m; 0 if none.
  double wake_length(int s) const;
  std::size_t bytes() const;

  // Operator pieces, public for the identity tests.
  static void nonlinear(const Level& L, double u_inf, std::vector<double>& out);
  static void prolong_boundary(const Level& coarse, const std::vector<double>& fc, const Level& fine, std::vector<double>& ff);
  static void restrict_interior(const Level& fine, const std::vector<double>& ff, const Level& coarse, std::vector<double>& fc);
  /// Q g (see above) for the current body points; also returns the corrections if asked.
  Eigen::VectorXd apply_Q(const Eigen::VectorXd& g, std::vector<double>* eta_c = nullptr, std::vector<double>* psi_c = nullptr);

 private:
  void build_points(const std::vector<SphereState>& sp);
  Settings s_;
  std::vector<Level> lv_;
  std::vector<SphereState> sph_;
  BodyPoints pts_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> B_;
  Eigen::VectorXd g_;     // last ring forces (warm start)
  struct Block { Eigen::Index offset, size; Eigen::LLT<Eigen::MatrixXd> llt; };
  std::vector<Block> prec_;  // CG preconditioner: per-sphere blocks of Q at the first configuration
  Eigen::Index prec_size_ = -1;
  std::vector<double> fixed_z_;  // sphere positions of the factorised Q
  std::unique_ptr<Eigen::LLT<Eigen::MatrixXd>> chol_;
  double t_ = 0;
  long n_ = 0;
  std::vector<double> work_, work2_, work3_, xq_, eta_c_, psi_c_;
};

}  // namespace imcol::flow
