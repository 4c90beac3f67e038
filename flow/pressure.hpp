// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The pressure of the flow kernel's current state (the kernel itself has none: it eliminates it with the
// streamfunction). Computed on demand for outputs, never in the time loop.
//
// Equation. With the stagnation variable B = p/ρ + ½|u|² the momentum equation reads
//   ∂u/∂t − u × ω = −∇B + ν∇²u + f,
// and with ∇·u = 0 the time derivative and the viscous term (−ν∇×ω) are divergence-free, so
//   ∇²B = ∇·(u × ω) + ∇·f,   axisymmetric (ω = ω e_θ):  u × ω = ω u_r e_z − ω u_z e_r,
//   ∇²B = (1/r)∂r(r ∂r B) + ∂zz B,  ∂r B = 0 on the axis.
// f is the immersed-boundary force density on the fluid (m/s²): the last step's point forces
// (Solver::point_forces) spread with the kernel's own delta, H g (flow/ib.hpp), on every level with that level's
// spacing: all points inside the level (the sphere points, the wall points of that level and of the finer ones).
// It carries the pressure jump across the sphere surfaces and the plate.
//
// Discretisation: B at cell centres (r_{i+½}, z_{j+½}), the dual of the kernel's vertex ψ — the MAC layout of the
// kernel's face velocities u = Cψ. The divergence is the kernel's cell volume flux (cell_outflux) over the cell
// volume 2π r_{i+½} h², the gradient its W-adjoint, so ∇²_h = D G is the kernel's own pressure operator and the
// source is D of the face field F + H g, where F_z(i+½, j) = ω ū_r and F_r(i, j+½) = −ω ū_z with the averages of
// Solver::nonlinear: the kernel's vorticity advection is exactly r × curl_h F and its force source r × curl_h(H g),
// and D C = 0 exactly, so the discarded ∂u/∂t and viscous terms drop out to rounding, not to O(h²) (with B at
// vertices they would not: their divergence on the vertex dual cells leaves an O(1) error in the body's layer).
// Fast solve per level: a DST-II in z (Dirichlet at the faces z_0, z_nz: ghost = 2b − B) and one tridiagonal
// system in r per mode (no flux through the axis, Dirichlet at r = R, ghost again). Multi-level: every level
// solves with its own source (its own u, ω and all the forces inside it spread with its own delta), the coarsest with B = ½U∞² on
// its boundary (p = p∞ there), each finer one with boundary values from the next coarser by tensor cubic
// interpolation of the cell values (even in r across the axis). Not the kernel's "finer source replaces coarser":
// the source is a divergence, and summing the fine cells of a coarse one keeps its total but moves each fine cell's
// share to the coarse centre, which changes the dipole moment of the thin layer H g (its far field) at O(1): at
// 16 cells/D that put p 19 % off at r = 3a, against 4 % with each level's own spreading (the RPB delta keeps the
// force's total and first moments on every level). Vertex values (Level::psi's layout) average the four cells around each vertex (two
// on the axis; boundary vertices the adjacent boundary values); p = ρ(B − ½|u|²) with |u|² the cell-centred face
// average, averaged to the vertex in the same way.
//
// Frames. p is a scalar: p − p∞ is the same at the same physical point in the kernel's frame and in the lab, also
// when the kernel's frame accelerates (coupled runs set U∞(t) each step): the frame's fictitious force −ρ a_frame is
// uniform, so divergence-free, and p → p∞ far away in every frame; the kernel's forces f already are those of its
// frame (see Solver::set_stream). So SnapshotFrame only shifts the positions (z + z_shift). What is frame-dependent is
// B and the dynamic pressure ½ρ|u|² (u is the kernel frame's velocity here); and an accelerating frame's pressure
// has a uniform gradient −ρ a_frame inside the spheres (the fluid there moves with the frame).
//
// Inside the spheres (and within ~1.5 h of their surfaces, the delta's width) the pressure is not physical: the
// fluid there moves rigidly with the sphere and the jump across the surface is smeared over three cells. Mask it
// when plotting; read surface pressures a few cells outside, or extrapolate from there.
#include <functional>
#include <vector>

#include "flow/grid.hpp"
#include "flow/solver.hpp"

namespace imcol::flow {

/// A cell-centred scalar on one level and its Dirichlet boundary values.
struct CellField {
  std::vector<double> cells;   // nr × nz, index i·nz + j, at (r_{i+½}, z_{j+½})
  std::vector<double> bottom;  // nr: at (r_{i+½}, z_0)
  std::vector<double> top;     // nr: at (r_{i+½}, z_nz)
  std::vector<double> outer;   // nz: at (R, z_{j+½}), R = nr h
};

/// Solves (1/r)∂r(r∂r B) + ∂zz B = rhs on nested levels (as Solver's: level ℓ + 1 twice as coarse, centred
/// together; rhs[ℓ] cell-centred, nr × nz), with B = far(r, z) on the coarsest level's boundary.
std::vector<CellField> solve_axisymmetric_poisson(const std::vector<LevelGeometry>& levels, std::vector<std::vector<double>> rhs,
                                                  const std::function<double(double, double)>& far);

/// Vertex values (Level::psi's layout, (nr+1)(nz+1)) of a cell field: the mean of the cells around each vertex.
std::vector<double> cell_to_vertex(const LevelGeometry& g, const CellField& c);

/// The cell-centred source D(u × ω + H g)/V of one level (m/s²/m = 1/s²) from the solver's state on that level.
std::vector<double> stagnation_source(const Solver& s, int level);

/// p − p∞ (Pa) at every vertex of every level (layout of Level::psi), from the solver's current state. Valid in the
/// kernel's frame and, at the shifted positions, in the lab (see "Frames" above). Not physical inside the spheres.
std::vector<std::vector<double>> pressure(const Solver& s);

}  // namespace imcol::flow
