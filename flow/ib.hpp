// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Immersed-boundary transfer operators on the finest level (MODEL.md §4).
//
// Velocities live on faces: u_z at (r_{i+½}, z_j), u_r at (r_i, z_{j+½}); the streamfunction gives them as
//   u = Cψ:  u_z = (ψ_{i+1,j} − ψ_ij)/(h r_{i+½}),   u_r = −(ψ_{i,j+1} − ψ_ij)/(h r_i),
// so the volume flux out of every cell, 2π[Δψ across its faces], is exactly zero.
// Axisymmetric inner product: ⟨u, v⟩_W = Σ_f W_f u_f v_f with the face volume W_f = 2π r_f h² (m³).
// Interpolation to a ring body point k uses the Roma–Peskin–Berger (J. Comput. Phys. 153, 1999) kernel φ with
// the axisymmetric weight, normalised so that a constant is interpolated exactly:
//   E_kf = φ((r_f − r_k)/h) φ((z_f − z_k)/h) W_f / n_k,   n_k = Σ_f φ φ W_f  (≈ 2π r_k h² off the axis),
// and spreading is its adjoint, H = W⁻¹ Eᵀ: a ring force g_k (total over the ring, N/ρ = m⁴/s²) becomes the
// force density (H g)_f = Σ_k E_kf g_k / W_f. Hence ⟨u, H g⟩_W = g · E u and Σ_f W_f (H g)_f = Σ_k g_k.
#include <Eigen/SparseCore>

#include <vector>

#include "flow/grid.hpp"

namespace imcol::flow {

/// Roma–Peskin–Berger regularised delta, support |x| < 1.5 (x in cells); Σ_i φ(x − i) = 1, Σ_i (x − i) φ(x − i) = 0.
double rpb_delta(double x);

/// Ring-shaped body points (components: 0 = r, 1 = z).
struct BodyPoints {
  std::vector<double> r, z;
  std::vector<double> ds;  // arc length of each ring's element (m)
  std::vector<int> body;   // which sphere each point belongs to
  std::size_t size() const { return r.size(); }
};

/// Rings on a sphere of radius a centred on the axis at z = zc: polar angles θ_k = (k + ½)π/N with
/// N = ceil(π a / (spacing·h)), so the arc spacing is at most spacing·h and no point sits on the axis.
void add_sphere_rings(BodyPoints& pts, double a, double zc, double h, double spacing, int body_id);

/// Face arrays of one level: uz is nr × (nz+1) (index i(nz+1)+j), ur is (nr+1) × nz (index i·nz+j).
struct FaceField {
  std::vector<double> uz, ur;
};
FaceField face_velocity(const LevelGeometry& g, const std::vector<double>& psi);  // u = Cψ
FaceField face_weights(const LevelGeometry& g);                                    // W_f (m³)
/// Net volume flux out of each cell (i+½, j+½), size nr × nz (m³/s).
std::vector<double> cell_outflux(const LevelGeometry& g, const FaceField& u);

/// Sparse rows of E: entry (2k + c, face) for component c of point k; faces indexed as in FaceField.
struct Stencil {
  std::vector<int> face;
  std::vector<double> w;
};
Stencil interp_stencil(const LevelGeometry& g, double r, double z, int comp);

std::vector<double> interpolate(const LevelGeometry& g, const BodyPoints& p, const FaceField& u);  // E u
FaceField spread(const LevelGeometry& g, const BodyPoints& p, const std::vector<double>& f);       // H f

/// B = E C as a sparse matrix acting on full-size vertex arrays (2N × (nr+1)(nz+1)).
Eigen::SparseMatrix<double, Eigen::RowMajor> velocity_at_points(const LevelGeometry& g, const BodyPoints& p);

/// The same B in compressed rows (columns sorted and merged per row), rebuilt in place: once its capacities suffice
/// (the same points moved), rebuilding allocates nothing.
struct PointRows {
  std::vector<int> start, col;  // row k: entries start[k] .. start[k+1]−1
  std::vector<double> val;
  int rows() const { return start.empty() ? 0 : static_cast<int>(start.size()) - 1; }
  int max_line(const LevelGeometry& g) const;  // largest radial index i of a vertex used (0 if none)
  void apply(const double* psi, double* u) const;            // u = B ψ
  void apply_transpose_add(const double* f, double* s) const;  // s += Bᵀ f
};
void velocity_rows(const LevelGeometry& g, const BodyPoints& p, PointRows& out);

}  // namespace imcol::flow
