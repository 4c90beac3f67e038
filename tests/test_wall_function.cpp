// SPDX-License-Identifier: BSD-3-Clause
// The added mass's wall function W(δ**) (model/wall_function.hpp, MODEL.md §2.2): continued linearly below dw_floor
// for every scene whose model evaluates W near contact, so that the mass matrix stays continuous there.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/scene.hpp"
#include "model/pair.hpp"
#include "model/wall_function.hpp"
#include "scene_text.hpp"

using namespace imcol;

namespace {

/// W just above and just below the floor, and the floor's own value.
void expect_continuous_at_floor(const std::string& effects) {
  const Scene sc = parse_scene("effects = " + effects + "\n" + test::basic_wall_scene(), "test.toml");
  const model::PairGeometry p(sc);
  const model::WallFunction w(sc, p);
  const double floor_gap = w.dw_floor() * p.a_star;
  const double above = w.W(floor_gap * (1 + 1e-9)), below = w.W(floor_gap * (1 - 1e-9));
  EXPECT_GT(below, 0.0) << effects;
  EXPECT_NEAR(below, above, 1e-6 * above) << effects;
  // Linear below the floor with the slope it has there: W keeps rising toward contact.
  EXPECT_GT(w.W(0.5 * floor_gap), below) << effects;
}

}  // namespace

TEST(WallFunction, ContinuousAtTheFloorWithTheAddedMassEffect) { expect_continuous_at_floor(R"(["drag", "lubrication", "added_mass", "elastic"])"); }

// The flow blend's implicit added-mass estimate (flow.added_mass_estimate, on by default) evaluates W without the
// added_mass effect: W used to drop to 0 below the floor, a jump in the mass matrix near contact.
TEST(WallFunction, ContinuousAtTheFloorForTheFlowBlendsEstimate) { expect_continuous_at_floor(R"(["drag", "elastic", "flow"])"); }
