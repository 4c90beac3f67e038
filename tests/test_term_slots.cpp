// SPDX-License-Identifier: BSD-3-Clause
// The force terms' slots (model/force_term.hpp): the registration order is the summation order, the model's force
// and mass-matrix sums are the sums of the slots in that order (bit for bit), and a term's states are its own.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "core/scene.hpp"
#include "model/collision_model.hpp"

namespace {

using namespace imcol;
using model::ForceKind;

std::string slots_scene(const std::string& name) { return std::string(IMCOL_DATA_DIR) + "/scenes/" + name; }

/// The forces and masses of each term at y, before the model moves any acceleration part: each term's add().
model::Evaluation raw_slots(const model::CollisionModel& m, double t, std::span<const double> y) {
  model::Evaluation ev = m.kinematic_state(y);
  const model::TermInput in{t, y, m.phase() != model::Phase::approach,
                            m.phase() == model::Phase::loading || m.phase() == model::Phase::unloading};
  for (const auto& term : m.terms()) term->add(in, ev);
  return ev;
}

/// States along the approach: the initial one, then the gap shrunk toward contact with the speed changed.
std::vector<std::vector<double>> slot_states(const model::CollisionModel& m) {
  std::vector<double> y0(m.size());
  m.initial_state(y0);
  std::vector<std::vector<double>> ys{y0};
  for (double f : {0.3, 0.05, 0.011}) {
    auto y = y0;
    y[0] *= f;
    y[1] *= 1 + f;
    ys.push_back(y);
  }
  return ys;
}

TEST(TermSlots, TheRegistrationOrderIsTheSummationOrder) {
  const std::string all = R"(["history", "gravity", "elastic", "added_mass", "lubrication", "drag"])";  // listed backwards
  const model::CollisionModel m(load_scene(slots_scene("default.toml"), {{"effects", all}}));
  const std::vector<ForceKind> order = {ForceKind::drag, ForceKind::lubrication, ForceKind::added_mass,
                                        ForceKind::contact, ForceKind::gravity, ForceKind::history};
  ASSERT_EQ(m.terms().size(), order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    EXPECT_EQ(m.terms()[i]->properties().kind, order[i]) << i;
    EXPECT_EQ(m.terms()[i]->slot(), i);
    EXPECT_EQ(m.kind_slots()[static_cast<std::size_t>(order[i])], std::vector<std::size_t>{i});
  }
  EXPECT_TRUE(m.kind_slots()[static_cast<std::size_t>(ForceKind::simulated)].empty());
}

TEST(TermSlots, TheAccelerationIsTheSumOfTheSlotsInRegistrationOrderExactly) {
  const std::vector<Override> all = {{"effects", R"(["drag", "lubrication", "added_mass", "elastic", "gravity", "history"])"}};
  const std::vector<std::pair<const char*, std::vector<Override>>> runs = {
      {"default.toml", {}}, {"default.toml", all}, {"hard/unequal_small_target.toml", {}}, {"hard/unequal_small_target.toml", all}};
  for (const auto& [name, overrides] : runs) {
    model::CollisionModel m(load_scene(slots_scene(name), overrides));
    for (const auto& y : slot_states(m)) {
      const auto ev = raw_slots(m, 0.0, y);
      std::vector<double> ydot(m.size());
      m.rhs(0.0, y, ydot);
      // The expression the model had before slots: by name, drag + lubrication + added mass + contact + gravity +
      // history, and m_p + added mass + history mass + A on the diagonal.
      const auto& ks = m.kind_slots();
      const auto of = [&](const model::SphereForces& f, ForceKind k) {
        const auto& s = ks[static_cast<std::size_t>(k)];
        return s.empty() ? 0.0 : f.term[s.front()];
      };
      const auto mass_of = [&](const model::SphereForces& f, ForceKind k) {
        const auto& s = ks[static_cast<std::size_t>(k)];
        return s.empty() ? 0.0 : f.mass[s.front()];
      };
      std::array<double, 2> g{}, slot_sum{};
      model::Evaluation named = ev;
      for (std::size_t k = 0; k < m.n_spheres(); ++k) {
        const auto& f = ev.f[k];
        g[k] = of(f, ForceKind::drag) + of(f, ForceKind::lubrication) + of(f, ForceKind::added_mass) + of(f, ForceKind::contact) +
               of(f, ForceKind::gravity) + of(f, ForceKind::history) + f.simulated;
        slot_sum[k] = f.term[0];
        for (std::size_t s = 1; s < m.terms().size(); ++s) slot_sum[k] += f.term[s];
        slot_sum[k] += f.simulated;
        named.m_eff[k] = m.mass(static_cast<int>(k)) + mass_of(f, ForceKind::added_mass) + mass_of(f, ForceKind::history) + ev.m_pair;
      }
      EXPECT_EQ(g[0], slot_sum[0]) << name;
      EXPECT_EQ(g[1], slot_sum[1]) << name;
      named.m_couple = ev.m_couple;
      const auto acc = named.accelerations(g, m.n_spheres());
      EXPECT_EQ(ydot[1], acc[0]) << name;
      if (m.n_spheres() == 2) {
        EXPECT_EQ(ydot[3], acc[1]) << name;
      }
    }
  }
}

TEST(TermSlots, AStatefulTermOwnsItsSliceOfTheState) {
  const Scene sc = load_scene(slots_scene("default.toml"), {{"history.evaluator", "\"soe\""}});
  const model::CollisionModel m(sc);
  std::size_t states = 0;
  for (const auto& term : m.terms()) states += term->states();
  ASSERT_GT(states, 0u);
  EXPECT_EQ(m.size(), m.core_size() + states);
  const auto names = m.component_names();
  ASSERT_EQ(names.size(), m.size());
  EXPECT_EQ(names[m.core_size()], "mem1_0");
  EXPECT_EQ(m.absolute_tolerances(1e-8).size(), m.size());
  // Without states (soe-step keeps its memory outside the integrator's state) the model is its core alone.
  const model::CollisionModel lean(load_scene(slots_scene("default.toml")));
  EXPECT_EQ(lean.size(), lean.core_size());
}

}  // namespace
