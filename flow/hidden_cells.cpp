// SPDX-License-Identifier: BSD-3-Clause
#include "flow/hidden_cells.hpp"

namespace imcol::flow {

CellFlags cell_flags(const std::vector<LevelFields>& levels, std::size_t level, const SnapshotBodies& bodies) {
  const LevelFields& L = levels[level];
  const auto& g = L.g;
  const std::size_t nc = static_cast<std::size_t>(g.nr) * g.nz;
  CellFlags out{std::vector<std::uint8_t>(nc, 0), std::vector<std::uint8_t>(nc, 0)};
  const LevelGeometry* fg = level > 0 ? &levels[level - 1].g : nullptr;
  std::size_t c = 0;
  for (int i = 0; i < g.nr; ++i)
    for (int j = 0; j < g.nz; ++j, ++c) {
      const double rc = g.r(i + 0.5), zc = g.z(j + 0.5);  // the centre in the kernel's frame (the levels share it)
      if (fg) out.finer[c] = rc < fg->r(fg->nr) && zc > fg->z0 && zc < fg->z(fg->nz);
      if (out.finer[c] || bodies.inside_solid(rc, zc + L.z_shift)) out.ghost[c] = kHiddenCell;
    }
  return out;
}

}  // namespace imcol::flow
