// SPDX-License-Identifier: BSD-3-Clause
#include "flow/fields.hpp"

#include "flow/pressure.hpp"

namespace imcol::flow {

namespace {

/// ψ, ω, u_r, u_z at every vertex of level l, seen from frame f, and that level's pressure p.
LevelFields fields_of(const Solver& s, std::size_t l, const SnapshotFrame& f, std::vector<double> p) {
  const Level& L = s.levels()[l];
  const double u_inf = s.settings().u_inf + f.u_frame;  // the uniform stream as seen from the frame
  const auto& g = L.g;
  LevelFields out{g, f.z_shift, {}};
  const std::size_t n = g.size();
  std::vector<double> psi(n), om(n), ur(n), uz(n);
  auto uzf = [&](int i, int j) { return (L.psi[g.at(i + 1, j)] - L.psi[g.at(i, j)]) / (g.h * g.r(i + 0.5)) + u_inf; };
  auto urf = [&](int i, int j) { return i == 0 ? 0.0 : -(L.psi[g.at(i, j + 1)] - L.psi[g.at(i, j)]) / (g.h * g.r(i)); };
  for (int i = 0; i <= g.nr; ++i)
    for (int j = 0; j <= g.nz; ++j) {
      const std::size_t k = g.at(i, j);
      const double r = g.r(i);
      psi[k] = L.psi[k] + 0.5 * u_inf * r * r;
      om[k] = i == 0 ? 0.0 : L.eta[k] / r;
      if (i == 0) uz[k] = (9 * uzf(0, j) - uzf(1, j)) / 8;
      else if (i == g.nr) uz[k] = uzf(i - 1, j);
      else uz[k] = 0.5 * (uzf(i - 1, j) + uzf(i, j));
      if (j == 0) ur[k] = urf(i, 0);
      else if (j == g.nz) ur[k] = urf(i, j - 1);
      else ur[k] = 0.5 * (urf(i, j - 1) + urf(i, j));
    }
  // One line per field: the CSV gains a column, the VTK files an array.
  out.fields.push_back({"psi", "stream_function_m3_s", -1, std::move(psi)});
  out.fields.push_back({"omega", "vorticity_1_s", -1, std::move(om)});
  out.fields.push_back({"u_r", "velocity_m_s", 0, std::move(ur)});
  out.fields.push_back({"u_z", "velocity_m_s", 1, std::move(uz)});
  out.fields.push_back({"p", "pressure_Pa", -1, std::move(p)});
  return out;
}

}  // namespace

const PointField* LevelFields::find(const std::string& column) const {
  for (const auto& f : fields)
    if (f.column == column) return &f;
  return nullptr;
}

std::vector<LevelFields> level_fields(const Solver& s, const SnapshotFrame& f) {
  std::vector<LevelFields> out;
  out.reserve(s.levels().size());
  auto p = pressure(s);  // p − p∞: the same in every frame (flow/pressure.hpp)
  for (std::size_t l = 0; l < s.levels().size(); ++l) out.push_back(fields_of(s, l, f, std::move(p[l])));
  return out;
}

}  // namespace imcol::flow
