// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Axisymmetric incompressible Navier–Stokes around spheres on the axis by the immersed-boundary projection
// method in streamfunction (nullspace) form: Taira & Colonius, J. Comput. Phys. 225 (2007); Colonius & Taira,
// Comput. Methods Appl. Mech. Eng. 197 (2008). Our own implementation of MODEL.md §4.
//
// Unknowns per level: η = rω at vertices (m/s) and the disturbance streamfunction ψ (m³/s), E²ψ = −η; the
// total streamfunction is ψ + ½U∞r² (a uniform stream U∞ along +z carries no vorticity). Vorticity transport
//   ∂η/∂t = −r[∂z(u_z ω) + ∂r(u_r ω)] + ν E²η + (force term),
// viscous term θ-implicit (θ = ½: Crank–Nicolson), advection Adams–Bashforth-2 (Euler on the first step; the step may
// change between steps, set_dt).
//
// Levels (Colonius & Taira 2008, §3.3): ℓ = 0 finest (spacing h), level ℓ has spacing 2^ℓ h and the same nr × nz
// cells, all centred on z_center. Every elliptic solve is multi-level: the right-hand side of each finer level
// replaces the coarser one's where they overlap (full weighting, "coarsify"), the coarsest level is solved with
// zero far field, then each finer level with boundary values interpolated (cubic) from the next coarser one.
// Call these A⁻¹ (for I − θνΔt E²) and P⁻¹ (for −E²). One step:
//   η* = A⁻¹[η^n + Δt((1−θ)νE²η^n + AB2 advection)],  ψ* = P⁻¹ η*,
//   Q g = U_b − U∞e_z − Bψ*_0,   Q g = B [P⁻¹ A⁻¹ S g]_0,   S g = Δt R Bᵀ g /(2πh²) on the finest level,
//   η^{n+1} = η* + A⁻¹ S g,  ψ^{n+1} = ψ* + P⁻¹A⁻¹ S g   (on every level: no lagged force on the coarse levels).
// The body forces g (ring totals, m⁴/s² = N per kg/m³) are the Lagrange multipliers of no-slip at the ring
// points (B = E C: velocity at the points from the finest ψ). Q is close to, but not exactly, symmetric (the level
// transfers are not adjoint), so it is LU-factorised when the bodies have not moved (bodies that stop after moving:
// once GMRES has spent as many applications of Q there as the LU has columns) and solved by restarted GMRES
// otherwise (relative residual krylov_tol; right-preconditioned by each sphere's own block of Q, factorised for
// the sphere's sub-cell offset on the finest grid in one of flow.preconditioner_bins bins (centred on the offset of
// the sphere's first block, so that a sphere at constant speed revisits the bins' centres), each built the first
// time the sphere is there and reused: the rings' pattern relative to the grid repeats when a sphere moves by whole cells and the
// multi-level Q is nearly translation invariant; warm start: each sphere's ring forces extrapolated linearly in time
// from its last two steps in the same offset bin, since the forces follow the rings' sub-cell offset (from the last
// two steps alone they leave a residual of 0.4–4 times the right-hand side, from the same offset 0.5–5 %); the wall's,
// and a sphere's before it has a step in the bin, from the last two steps). Only the first
// block of each sphere radius is built column by column; the later ones are it plus the change of Q probed at every
// block_probe_stride-th ring point (Curtis, Powell & Reid, IMA J. Appl. Math. 13 (1974): the change between two
// offsets is concentrated near the diagonal, where the spreading and interpolation stencils overlap).
// Force on sphere s (N, along +z): F_s = −ρ Σ_{k∈s} g_z,k + ρ V_s (U_s^{n+1} − u_in,s^n)/Δt, the second term the
// momentum change of the fluid inside the sphere. Convention: before the first step the fluid inside moves with
// the initial flow (ψ = 0, so u_in = U∞, the stream); after every step no-slip makes it move with the sphere
// (u_in = U_s). A sphere prescribed at U from t = 0 in fluid at rest therefore gets ρVU/Δt on step 1, and the
// step-1 impulse is ρVU (fluid inside) + ½ρVU (added mass) + viscous, as for a real impulsive start.
//
// Wall (Settings::wall_z): a plane no-slip wall normal to the axis made of immersed points, a thin plate at z = z_w
// (fluid on both sides; a sphere on one side sees a no-slip plane). Rings of points (u_r = 0, u_z = wall_velocity)
// on every level, each in its own level's spacing: the finest level's from r = ½h out to R₀ − 2.5h (R_ℓ = nr·2^ℓh
// the level's radius), level ℓ ≥ 1's from R_{ℓ−1} + 2^ℓh (outside the finer level, so that coarsify never
// overwrites their source) out to R_ℓ − 2.5·2^ℓh (so that the plate edge's vorticity source lands on interior
// vertices that the restriction also carries down); the coarsest level's zero far field (ψ = 0 at r = R_{L−1})
// closes it. So the plate spans the whole domain, with a gap of 2.25 coarse cells between the rings of adjacent
// levels (the plate's force there is 1–9 % off the sphere's: docs/flow-kernel.md).
// Coarse rings spread and interpolate on their own level (B_ℓ from that level's ψ); the force system grows by the
// wall's unknowns (ordering: sphere points, then the wall level by level). The wall's own block of Q never changes:
// it is LU-factorised once (set_dt keeps it, scaled) and preconditions GMRES for moving spheres next to each
// sphere's block.
#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <functional>
#include <memory>
#include <optional>
#include <utility>
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
  double krylov_tol = 1e-10;      // GMRES: relative residual ‖Qg − b‖ ≤ krylov_tol ‖b‖
  int krylov_max_iter = 1000;     // GMRES: iteration limit (exceeded -> SolverError)
  int krylov_restart = 60;        // GMRES: Krylov vectors kept before a restart
  double ring_spacing = 1.0;  // arc spacing of the body rings, units of h
  bool direct_when_fixed = true;  // LU of Q while the bodies stay put
  int preconditioner_bins = 16;   // GMRES: sub-cell offsets per finest cell with their own preconditioner block
  bool warm_start_by_offset = true;  // GMRES warm start of a sphere's ring forces from its last steps at the same
                                     // sub-cell offset bin (false: from the last two steps, whatever their offsets)
  int block_probe_stride = 12;    // GMRES: a sphere's later preconditioner blocks are the first one of its radius plus
                                  // the change probed at every stride-th ring point (2 × stride applications of Q);
                                  // 0: every block column by column (2 per ring point)
  bool measure_plans = false;     // FFTW_MEASURE instead of FFTW_ESTIMATE
  // Optional plane no-slip wall z = wall_z normal to the axis (immersed points, see "Wall" above). Its surface moves
  // along +z at wall_velocity (normally 0; the plate itself stays at wall_z). No sphere may cross the plane.
  std::optional<double> wall_z;
  double wall_velocity = 0;       // m/s
};

/// One sphere on the axis at one instant.
struct SphereState {
  double radius = 0;  // m
  double z = 0;       // centre, m
  double u = 0;       // velocity along +z, m/s
};

struct StepInfo {
  std::vector<double> force;     // N on each sphere along +z (ring forces + internal fluid)
  double wall_force = 0;         // N on the wall along +z (both faces of the plate; 0 without a wall)
  std::vector<double> internal;  // N, the internal-fluid part ρ V dU/dt
  int krylov_iterations = 0;         // GMRES iterations, 0 with the direct solve
  double krylov_residual = 0;        // relative
  double slip = 0;               // max |u − U_b| at the body points after the step, m/s
};

struct Level {
  LevelGeometry g;
  std::unique_ptr<FastSolver> fast;  // ops: 0 = E² (Poisson), 1 = I − θνΔt E² (viscous)
  std::vector<double> eta, psi, nl_old;
  std::vector<double> rhs, src, etac, psic;  // scratch: right-hand sides, force source, corrections
  std::vector<double> eta_modes;             // the predictor's η* in mode space (before coarsify)
};

/// The change of the viscous factor θνΔΔt/h² beyond which a preconditioner block built for another step is rebuilt
/// (gondret_st100, factor 0.03 → 0.25: rebuilt at 0.05, 8.9 GMRES iterations a step and 1.5 s in the kernel; kept
/// and scaled, 9.1 and 0.94 s).
inline constexpr double kBlockViscousChange = 1.0;

class Solver {
 public:
  Solver(const Settings& s, std::vector<SphereState> spheres);
  /// Advances one step; `next` are the spheres at t + dt (same count and radii). Returns the forces at t + dt.
  /// Throws SolverError if GMRES fails or the flow diverges (a force, the slip or the vorticity not finite); the
  /// solver is then mid-step and must not be stepped again.
  StepInfo step(const std::vector<SphereState>& next);

  /// Sets the uniform stream U∞ for the coming steps: a frame translating at −U∞ (MODEL.md §5). The vorticity is
  /// the same in every translating frame; the force in the frame misses the frame's buoyancy-like ρ V a_frame.
  void set_stream(double u_inf) { s_.u_inf = u_inf; }
  /// Sets the wall's surface velocity (along +z) for the coming steps; with a wall, set_stream and set_wall_velocity
  /// move together (a translating frame moves the wall's surface and the far fluid alike).
  void set_wall_velocity(double u) { s_.wall_velocity = u; }
  /// Sets the step Δt (s) for the coming steps: the viscous operator is refactorised, AB2 takes the ratio of the new
  /// step to the last (η^{n+1} = … + Δt_n((1 + r/2) N^n − (r/2) N^{n−1}), r = Δt_n/Δt_{n−1}), the LU of Q is rebuilt
  /// when next used, and the preconditioner blocks are kept, scaled by the ratio of the steps (Q = Δt × an operator
  /// that depends on Δt only through (I − θνΔt E²)⁻¹): a block is rebuilt when θν|Δt − Δt_block|/h² exceeds
  /// kBlockViscousChange.
  void set_dt(double dt);
  double time() const { return t_; }
  long steps() const { return n_; }
  long preconditioner_blocks_built() const { return prec_builds_; }  // GMRES preconditioner blocks factorised so far
  long q_applications() const { return q_applications_; }  // applications of Q so far (GMRES, blocks, LU columns)
  /// Called after each column of a force-system block built (an LU of Q or a preconditioner block: each column one
  /// application of Q) with the columns done and the block's size: a progress display for long builds.
  void set_block_progress(std::function<void(long, long)> f) { block_progress_ = std::move(f); }
  const Settings& settings() const { return s_; }
  const std::vector<Level>& levels() const { return lv_; }
  const std::vector<SphereState>& spheres() const { return sph_; }
  const BodyPoints& points() const { return pts_; }
  /// The wall's points on level ℓ (empty without a wall); their positions are in metres on that level.
  const std::vector<BodyPoints>& wall_points() const { return wall_pts_; }
  std::size_t wall_unknowns() const { return 2 * wall_count_; }
  /// The last step's point forces (m⁴/s², kinematic): (r, z) of each sphere point, then of each wall point by level.
  const Eigen::VectorXd& point_forces() const { return g_; }
  /// Axial velocity on the axis of the finest level (extrapolated from r = h/2, 3h/2), at z_j, m/s.
  std::vector<double> axis_velocity() const;
  /// The fluid's advective Courant number on the finest level after the last step: max (|u_r| + |u_z|) Δt/h over its
  /// faces, velocities relative to the grid (the stream included). The explicit AB2 advection breaks near 1.
  double max_courant() const;
  /// Recirculation length behind sphere s (downstream of its rear, in the stream direction), m; 0 if none.
  double wake_length(int s) const;
  std::size_t bytes() const;

  // Operator pieces, public for the identity tests.
  static void nonlinear(const Level& L, double u_inf, std::vector<double>& out);
  static void prolong_boundary(const Level& coarse, const std::vector<double>& fc, const Level& fine, std::vector<double>& ff);
  static void restrict_interior(const Level& fine, const std::vector<double>& ff, const Level& coarse, std::vector<double>& fc);
  /// The dense Q (see above) for the current body points, column by column: one application of apply_Q_into per
  /// unknown (2 per sphere and wall point).
  Eigen::MatrixXd force_matrix();
  /// base + the change Q − base probed on Q's diagonal block at offset o (size base.rows(): one sphere's ring points
  /// in order, r and z): 2 × stride applications of Q, each of the sum of the unit vectors of one component at every
  /// stride-th point; each row of the result is credited to the column of the probed point nearest to it. Exact
  /// (up to rounding) when stride ≥ the sphere's points.
  Eigen::MatrixXd corrected_block_of_Q(Eigen::Index o, const Eigen::MatrixXd& base, int stride);

 private:
  // Passes of a step. The predictor η* = A⁻¹rhs (full), ψ* = P⁻¹η* only on the lines the body points and the finer
  // levels' boundary values read; Q g likewise (A⁻¹ on the coarsest level only on those lines); the step ends with
  // η = η* + A⁻¹Sg, ψ = P⁻¹η (full), the same as ψ* + P⁻¹A⁻¹Sg up to rounding. P⁻¹ starts from A⁻¹'s modes on the
  // lines that coarsify leaves alone (no transform pair between the two solves there).
  // The parts of step().
  void explicit_rhs();  // Level::rhs ← the explicit part of the vorticity equation (AB2 advection, (1 − θ) viscous)
  void set_force_rhs(const std::vector<SphereState>& next);  // target_, rhs_ = target_ − Bψ*; g_ sized
  void solve_direct(const std::vector<SphereState>& next);   // g_ by the LU of Q (refactorised when the spheres move)
  bool use_direct(const std::vector<SphereState>& next, bool moved);  // this step by the LU of Q, not GMRES
  bool lu_current(const std::vector<SphereState>& next) const;        // the LU is Q's for these positions
  void solve_gmres(const std::vector<SphereState>& next, StepInfo& info);  // g_ by GMRES; its counts into info
  void warm_start();         // g_ ← the forces extrapolated to this step (see "warm start" above)
  void keep_offset_forces();  // each sphere's ring forces of this step, by its offset bin, for later warm starts
  void build_preconditioner(const std::vector<SphereState>& next);          // prec_: per-sphere blocks of Q
  void sphere_forces(const std::vector<SphereState>& next, StepInfo& info);  // info.force, internal, wall_force
  void build_points(const std::vector<SphereState>& sp);
  void build_wall();
  void plan_rows();    // the partial line counts per level, and their FFTW plans
  void update_rows();  // the partial line counts per level
  /// Velocities at all points (sphere points from the finest ψ, then wall points from their level's ψ) into u.
  void point_velocity(std::vector<double> Level::*psi, Eigen::VectorXd& u) const;
  void check_finite(const StepInfo& info) const;  // throws SolverError naming the quantity and the time
  void coarsify(std::vector<double> Level::*field);  // fine-to-coarse full weighting, finest first
  void spread_source(const Eigen::VectorXd& g);      // Level::src ← S g on every level
  /// eta ← A⁻¹ rhs on all levels (rhs coarsified first); partial: the coarsest level's lines only as far as needed.
  /// With rhs = src only the lines src_rows_ are transformed (the source vanishes beyond them).
  void pass_viscous(std::vector<double> Level::*rhs, std::vector<double> Level::*eta, bool partial);
  /// psi ← P⁻¹ eta on all levels (eta coarsified first), from the modes left by pass_viscous (plus eta_modes when
  /// add_saved); partial: only the lines read by the body points and the finer levels.
  void pass_streamfunction(std::vector<double> Level::*eta, std::vector<double> Level::*psi, bool partial, bool add_saved);
  void apply_Q_into(const Eigen::VectorXd& g, Eigen::VectorXd& out);  // partial passes
  Eigen::MatrixXd diagonal_block_of_Q(Eigen::Index o, Eigen::Index n);  // Q's rows and columns o..o+n−1, n applications
  /// The end of the step for forces g: etac ← η* + A⁻¹Sg, psic ← P⁻¹ of it (full); u_ ← velocities at the points.
  void final_pass(const Eigen::VectorXd& g);
  /// Solves Q g_ = b (warm start g_); returns iterations and the true relative residual. On return final_pass(g_)
  /// is current (its residual is the true one).
  std::pair<int, double> gmres(const Eigen::VectorXd& b);
  void precondition(const Eigen::Ref<const Eigen::VectorXd>& r, Eigen::VectorXd& z) const;
  Settings s_;
  std::vector<Level> lv_;
  std::vector<SphereState> sph_;
  BodyPoints pts_;
  PointRows B_;                 // velocity at the sphere points from the finest ψ
  Eigen::VectorXd g_, g_prev_;  // ring forces of the last two steps (warm start)
  using BlockLU = Eigen::PartialPivLU<Eigen::MatrixXd>;
  /// scale: Δt_block/Δt; forces: a sphere's ring forces at its last two steps in this block's offset bin (the wall's
  /// block: none).
  struct OffsetForces { Eigen::VectorXd last, before; double t_last = 0, t_before = 0; };
  struct Block { Eigen::Index offset, size; std::shared_ptr<BlockLU> lu; double scale; OffsetForces* forces; };
  struct CachedBlock { std::shared_ptr<BlockLU> lu; double dt = 0; };  // a block of Q and the step it was built for
  bool close_step(double dt_block) const;  // a block built for dt_block serves Δt (scaled): kBlockViscousChange
  bool block_current(const CachedBlock& c, Eigen::Index n) const;    // built, of size n, for a step close to Δt
  /// A sphere's block of Q at offset o, size n: column by column the first time for this radius (it becomes the
  /// reference), else the reference scaled to Δt and corrected by probing (block_probe_stride).
  std::shared_ptr<BlockLU> sphere_block(Eigen::Index o, Eigen::Index n, double radius);
  struct ReferenceBlock { double radius = 0; Eigen::MatrixXd q; double dt = 0; };
  std::vector<ReferenceBlock> ref_blocks_;  // per sphere radius: its first block of Q built column by column
  long q_applications_ = 0;
  std::vector<Block> prec_;            // GMRES preconditioner of this step: per-sphere blocks of Q
  std::vector<std::vector<CachedBlock>> prec_cache_;  // [sphere][offset bin]
  std::vector<double> prec_origin_;    // per sphere: the sub-cell offset of its first block, the centre of bin 0
  std::vector<std::vector<OffsetForces>> offset_forces_;  // [sphere][offset bin]: the warm start's forces
  long prec_builds_ = 0;
  std::vector<BodyPoints> wall_pts_;  // per level
  std::vector<PointRows> Bw_;         // per level: velocity at its wall points
  std::size_t wall_count_ = 0;        // wall points over all levels
  std::function<void(long, long)> block_progress_;
  CachedBlock wall_block_;            // the wall's own block of Q (GMRES preconditioner), built once per step size
  std::vector<double> fixed_z_;  // sphere positions of the factorised Q
  double lu_dt_ = 0;             // the step of the factorised Q
  double dt_last_ = 0;           // the last step taken, s (AB2's ratio)
  bool ever_moved_ = false;      // the bodies moved relative to the grid in some step
  long still_work_ = 0;          // applications of Q by GMRES since the bodies last moved
  std::unique_ptr<Eigen::PartialPivLU<Eigen::MatrixXd>> lu_;
  std::vector<double> u_in_;  // velocity of the fluid inside each sphere at t^n (see the convention above)
  double t_ = 0;
  long n_ = 0;
  int coarse_rows_ = 0, prolong_rows_ = 0;  // rows coarsify writes (levels ≥ 1); rows prolong_boundary reads
  std::vector<int> psi_rows_;               // per level: rows of ψ read by the points and the finer level
  std::vector<int> src_rows_;               // per level: rows where the force source S g can be nonzero
  std::vector<double> nl_, eta_sq_;  // eta_sq_: Σ η² per level after the step (check_finite)
  // step and GMRES workspace, sized on first use
  Eigen::VectorXd rhs_, target_, u_, r_, w_, z_, t1_, y_, cs_, sn_, e_;
  Eigen::MatrixXd V_, H_;
};

}  // namespace imcol::flow
