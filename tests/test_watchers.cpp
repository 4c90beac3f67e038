// SPDX-License-Identifier: BSD-3-Clause
// The seam between the model's events and the rules in run/ (model/watcher.hpp): the model alone arms only its own
// roots; a watcher's root fires under its kind and name, and its stop time ends the run.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "core/scene.hpp"
#include "integrators/integrator.hpp"
#include "model/collision_model.hpp"
#include "run/watch.hpp"

namespace {

using namespace imcol;

std::string scene_path(const std::string& name) { return std::string(IMCOL_DATA_DIR) + "/scenes/" + name; }

std::vector<std::string> root_names(const model::CollisionModel& m) {
  std::vector<std::string> names;
  for (const auto& r : m.roots()) names.push_back(r.name);
  return names;
}

TEST(Watchers, TheModelAloneArmsOnlyItsContactRootsAndTheWatchersFollowThem) {
  const Scene sc = load_scene(scene_path("default.toml"));
  model::CollisionModel model(sc);
  const auto alone = root_names(model);
  ASSERT_FALSE(alone.empty());
  EXPECT_EQ(alone.front(), "gap=delta_ss (in)");
  for (const auto& n : alone) EXPECT_EQ(n.find("instant"), std::string::npos) << n;
  run::Watch watch(model, sc);
  const auto watched = root_names(model);
  // The model's contact root, then the watchers' (stopped approach, instant gap), then the model's other roots.
  ASSERT_EQ(watched.size(), alone.size() + 2);
  EXPECT_EQ(watched[0], alone[0]);
  EXPECT_EQ(watched[1], "u_rel=stall_fraction*U_rel0 (approach stopped)");
  EXPECT_EQ(watched[2], "gap=instant_gap (in)");
  for (std::size_t i = 1; i < alone.size(); ++i) EXPECT_EQ(watched[i + 2], alone[i]);
}

/// Arms one inward crossing of half the initial gap and ends the run there.
class HalfGap : public model::EventWatcher {
 public:
  explicit HalfGap(double gap) : gap_(gap) {}
  void roots(std::vector<model::WatchedRoot>& out) const override {
    if (!t_) out.push_back({model::EventKind::measure_out, "gap=half the initial gap (in)", model::WatchedRoot::Of::gap, gap_, -1, true});
  }
  std::optional<model::Declared> on_event(const model::EventRecord& e) override {
    if (e.kind == model::EventKind::measure_out) t_ = e.t;
    return std::nullopt;
  }
  double stop_time() const override { return t_.value_or(std::numeric_limits<double>::infinity()); }
  std::optional<double> t_;
  double gap_;
};

TEST(Watchers, AWatchersRootFiresUnderItsKindAndNameAndItsStopTimeEndsTheRun) {
  const Scene sc = load_scene(scene_path("default.toml"));
  model::CollisionModel model(sc);
  HalfGap half(0.5 * model.initial_gap());
  model.watch(half);
  struct : Observer {
    void sample(double t, std::span<const double>, bool) override { last = t; }
    double last = -1;
  } obs;
  IntegratorSettings st;
  st.output_dt = sc.output.dt;
  integrate(model, st, obs);
  ASSERT_TRUE(half.t_);
  ASSERT_FALSE(model.events().empty());
  const auto& e = model.events().back();
  EXPECT_EQ(e.kind, model::EventKind::measure_out);
  EXPECT_EQ(e.name, "gap=half the initial gap (in)");
  EXPECT_NEAR(e.gap, 0.5 * model.initial_gap(), 1e-6 * model.initial_gap());
  EXPECT_EQ(model.stop_time(), *half.t_);
  EXPECT_EQ(obs.last, *half.t_);  // the run ended at the watcher's event, long before t_end
  EXPECT_LT(*half.t_, sc.solver.t_end);
  EXPECT_FALSE(model.t_contact());
}

}  // namespace
