// SPDX-License-Identifier: BSD-3-Clause
#include "flow/snapshot.hpp"

#include <iomanip>
#include <sstream>

#include "core/number_text.hpp"
#include "flow/pressure.hpp"

namespace imcol::flow {

namespace {

void write_level(std::string& os, int l, const Level& L, const std::vector<double>& p, double u_inf, double z_shift) {
  // u_inf: the uniform stream as seen from the frame the fields are written in
  const auto& g = L.g;
  auto uzf = [&](int i, int j) { return (L.psi[g.at(i + 1, j)] - L.psi[g.at(i, j)]) / (g.h * g.r(i + 0.5)) + u_inf; };
  auto urf = [&](int i, int j) { return i == 0 ? 0.0 : -(L.psi[g.at(i, j + 1)] - L.psi[g.at(i, j)]) / (g.h * g.r(i)); };
  for (int i = 0; i <= g.nr; ++i)
    for (int j = 0; j <= g.nz; ++j) {
      const double r = g.r(i), z = g.z(j) + z_shift;
      const double psi = L.psi[g.at(i, j)] + 0.5 * u_inf * r * r;
      const double om = i == 0 ? 0.0 : L.eta[g.at(i, j)] / r;
      double uz, ur;
      if (i == 0) uz = (9 * uzf(0, j) - uzf(1, j)) / 8;
      else if (i == g.nr) uz = uzf(i - 1, j);
      else uz = 0.5 * (uzf(i - 1, j) + uzf(i, j));
      if (j == 0) ur = urf(i, 0);
      else if (j == g.nz) ur = urf(i, j - 1);
      else ur = 0.5 * (urf(i, j - 1) + urf(i, j));
      os += std::to_string(l);
      for (double v : {r, z, psi, om, ur, uz, p[g.at(i, j)]}) {
        os += ',';
        append_number(os, v, 9);
      }
      os += '\n';
    }
}

}  // namespace

std::string snapshot_csv(const Solver& s, const SnapshotFrame& f, const std::string& label) {
  std::ostringstream os;
  os << std::setprecision(9);
  os << "# " << (label.empty() ? std::string("t = ") : label + " t = ") << s.time() + f.t_shift
     << " s; level 0 is the finest; psi is the total Stokes streamfunction (m^3/s); z_shift = " << f.z_shift
     << " m; spheres (z, d) =";
  for (const auto& b : s.spheres()) os << " " << b.z + f.z_shift << " " << 2 * b.radius;
  os << "\n";
  os << "level,r,z,psi,omega,u_r,u_z,p\n";
  std::string out = os.str();
  const auto p = pressure(s);  // the same in the lab: a scalar, relative to the far field
  for (std::size_t l = 0; l < s.levels().size(); ++l)
    write_level(out, static_cast<int>(l), s.levels()[l], p[l], s.settings().u_inf + f.u_frame, f.z_shift);
  return out;
}

}  // namespace imcol::flow
