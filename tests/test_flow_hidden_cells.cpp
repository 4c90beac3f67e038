// SPDX-License-Identifier: BSD-3-Clause
// The flow fields' solids and hidden cells (flow/bodies.hpp, flow/hidden_cells.hpp) on hand-made levels.
#include <gtest/gtest.h>

#include <cmath>

#include "flow/bodies.hpp"
#include "flow/hidden_cells.hpp"

using namespace imcol::flow;

namespace {

/// Two levels: level 0 (h = 0.1) spans r ∈ [0, 0.4], z ∈ [−0.4, 0.4]; level 1 (h = 0.2) r ∈ [0, 1.6], z ∈ [−1.6, 1.6];
/// both shifted by z_shift into the lab.
std::vector<LevelFields> two_levels_for_hidden_cells(double z_shift) {
  LevelFields fine{{4, 8, 0.1, -0.4}, z_shift, {}};
  LevelFields coarse{{8, 16, 0.2, -1.6}, z_shift, {}};
  return {fine, coarse};
}

}  // namespace

TEST(FlowHiddenCells, GapsOfAWallAndAPair) {
  SnapshotBodies wall{{{0.05, -0.1, 0.2}}, {{0.05, -0.2, 0.0}}, 0.0};
  EXPECT_DOUBLE_EQ(wall.gap(), 0.05);         // the trajectory's sphere: 0.1 − 0.05 from the wall
  EXPECT_DOUBLE_EQ(wall.kernel_gap(), 0.15);  // the kernel's, held farther
  EXPECT_DOUBLE_EQ(wall.diameter(), 0.1);
  SnapshotBodies pair{{{0.05, -0.1, 0.2}, {0.1, 0.2, -0.2}}, {{0.05, -0.1, 0.2}, {0.1, 0.2, -0.2}}, std::nullopt};
  EXPECT_DOUBLE_EQ(pair.gap(), 0.3 - 0.15);
  SnapshotBodies alone{{{0.05, 0.0, 0.0}}, {{0.05, 0.0, 0.0}}, std::nullopt};
  EXPECT_TRUE(std::isinf(alone.gap()));
}

TEST(FlowHiddenCells, InsideEitherSphereOrBeyondTheWall) {
  const SnapshotBodies b{{{0.05, -0.1, 0.2}}, {{0.05, -0.3, 0.0}}, 0.0};
  EXPECT_TRUE(b.inside_solid(0.0, -0.1));     // the trajectory's sphere
  EXPECT_TRUE(b.inside_solid(0.04, -0.3));    // the kernel's
  EXPECT_FALSE(b.inside_solid(0.0, -0.2));    // between them
  EXPECT_FALSE(b.inside_solid(0.05, -0.1));   // on the surface: not strictly inside
  EXPECT_TRUE(b.inside_solid(1.0, 1e-9));     // beyond the wall (the spheres are below it)
  EXPECT_FALSE(b.inside_solid(1.0, -1e-9));
  const SnapshotBodies above{{{0.05, 0.5, 0.0}}, {{0.05, 0.5, 0.0}}, 0.0};  // a sphere above its wall
  EXPECT_TRUE(above.inside_solid(0.0, -0.01));
  EXPECT_FALSE(above.inside_solid(0.0, 0.01));
}

TEST(FlowHiddenCells, CoveredAndSolidCellsAreHidden) {
  const double shift = 10.0;  // the levels in the lab; the bodies are in the lab too
  const auto levels = two_levels_for_hidden_cells(shift);
  const SnapshotBodies none{{{0.01, shift + 1.0, 0.0}}, {{0.01, shift + 1.0, 0.0}}, std::nullopt};  // no cell centre inside
  const CellFlags f0 = cell_flags(levels, 0, none), f1 = cell_flags(levels, 1, none);
  ASSERT_EQ(f0.ghost.size(), 32u);
  ASSERT_EQ(f1.ghost.size(), 128u);
  for (std::size_t c = 0; c < f0.ghost.size(); ++c) EXPECT_EQ(f0.ghost[c], 0) << c;  // the finest level: nothing covers it
  int covered = 0;
  for (std::size_t c = 0; c < f1.ghost.size(); ++c) {
    covered += f1.finer[c];
    EXPECT_EQ(f1.ghost[c], f1.finer[c] ? kHiddenCell : 0) << c;
  }
  EXPECT_EQ(covered, 2 * 4);  // level 0's 0.4 × 0.8 is 2 × 4 coarse cells
  // A wall at z = shift + 0.07 with the sphere below: level 0's cells above it (centres 0.15, 0.25, 0.35) are hidden,
  // and level 0's cells whose centre is in the sphere of radius 0.12 at z = shift − 0.2.
  const SnapshotBodies wall{{{0.12, shift - 0.2, 0.0}}, {{0.12, shift - 0.2, 0.0}}, shift + 0.07};
  const CellFlags w = cell_flags(levels, 0, wall);
  int hidden = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 8; ++j) {
      const double rc = 0.1 * (i + 0.5), zc = -0.4 + 0.1 * (j + 0.5);
      const bool solid = zc > 0.07 || rc * rc + (zc + 0.2) * (zc + 0.2) < 0.12 * 0.12;
      EXPECT_EQ(w.ghost[static_cast<std::size_t>(i * 8 + j)], solid ? kHiddenCell : 0) << i << ", " << j;
      hidden += solid;
    }
  EXPECT_EQ(hidden, 4 * 3 + 2);  // three rows beyond the wall; two cells (r = 0.05, z = −0.25, −0.15) in the sphere
}
