// SPDX-License-Identifier: BSD-3-Clause
#include "flow/snapshot.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "core/number_text.hpp"
#include "flow/bodies.hpp"

namespace imcol::flow {

namespace {

void write_level(std::string& os, int l, const LevelFields& L) {
  const auto& g = L.g;
  std::vector<std::string> z_text(g.nz + 1);  // ",z" of each line j, the same on every line i
  for (int j = 0; j <= g.nz; ++j) {
    z_text[j] += ',';
    append_number(z_text[j], L.z(j), 9);
  }
  for (int i = 0; i <= g.nr; ++i) {
    std::string head = std::to_string(l);  // "level,r"
    head += ',';
    append_number(head, L.r(i), 9);
    for (int j = 0; j <= g.nz; ++j) {
      const std::size_t k = g.at(i, j);
      os += head;
      os += z_text[j];
      for (const auto& f : L.fields) {
        os += ',';
        append_number(os, f.values[k], 9);
      }
      os += '\n';
    }
  }
}

/// The comment line's tail: the spheres where the trajectory has them and the true surface gap (with a wall or a pair).
void append_trajectory(std::ostream& os, const SnapshotBodies& b) {
  os << "; trajectory spheres (z, d) =";
  for (const auto& sp : b.spheres) os << " " << sp.z << " " << 2 * sp.radius;
  if (std::isfinite(b.gap())) os << "; gap = " << b.gap() << " m = " << b.gap() / b.diameter() << " D";
}

}  // namespace

std::string snapshot_csv(const Solver& s, const SnapshotFrame& f, const std::string& label) {
  return snapshot_csv(s, level_fields(s, f), f, label);
}

std::string snapshot_csv(const Solver& s, const std::vector<LevelFields>& levels, const SnapshotFrame& f, const std::string& label) {
  std::ostringstream os;
  os << std::setprecision(9);
  os << "# " << (label.empty() ? std::string("t = ") : label + " t = ") << s.time() + f.t_shift
     << " s; level 0 is the finest; psi is the total Stokes streamfunction (m^3/s); z_shift = " << f.z_shift
     << " m; spheres (z, d) =";
  for (const auto& b : s.spheres()) os << " " << b.z + f.z_shift << " " << 2 * b.radius;
  append_trajectory(os, snapshot_bodies(s, f));
  os << "\n";
  os << "level,r,z";
  if (!levels.empty())
    for (const auto& fld : levels.front().fields) os << ',' << fld.column;
  os << "\n";
  std::string out = os.str();
  // Room for every line up front (17 bytes a number at 9 digits, "-d.dddddddde-ddd,"): no reallocation and copy as it grows.
  std::size_t bytes = out.size();
  for (const auto& L : levels) bytes += std::size_t(L.g.nr + 1) * std::size_t(L.g.nz + 1) * (4 + 17 * (2 + L.fields.size()));
  out.reserve(bytes);
  for (std::size_t l = 0; l < levels.size(); ++l) write_level(out, static_cast<int>(l), levels[l]);
  return out;
}

}  // namespace imcol::flow
