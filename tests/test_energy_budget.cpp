// SPDX-License-Identifier: BSD-3-Clause
// The energy budget of a collision (run/energy_budget.hpp, docs/energy.md): the quadrature beside the solver is exact
// for a quadratic integrand, the work of the forces accounts for the change of kinetic energy to the solver's
// tolerance in every phase, and a dry collision loses 1 − e_dry² of its impact energy in the contact.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "integrators/integrator.hpp"
#include "run/simulate.hpp"
#include "tests/scene_text.hpp"

using namespace imcol;

namespace {

std::string budget_scene(const std::string& name) { return data_dir() + "/scenes/" + name + ".toml"; }

/// y' = −y with one quadrature q' = t² (q = t³/3): Simpson's rule and the cubic Hermite samples are exact for it.
class QuadraticWork : public DynamicalSystem {
 public:
  std::size_t size() const override { return 1; }
  std::vector<std::string> component_names() const override { return {"y"}; }
  std::vector<double> absolute_tolerances(double atol) const override { return {atol}; }
  void initial_state(std::span<double> y) const override { y[0] = 1; }
  void rhs(double, std::span<const double> y, std::span<double> ydot) override { ydot[0] = -y[0]; }
  void residual(double, std::span<const double> y, std::span<const double> yp, std::span<double> r) override { r[0] = yp[0] + y[0]; }
  std::vector<RootSpec> roots() const override { return {{"y = 0.5", -1}}; }
  void root_values(double, std::span<const double> y, std::span<double> g) override { g[0] = y[0] - 0.5; }
  EventAction on_roots(std::span<const std::size_t>, double, std::span<double>) override { return EventAction::reinit; }
  double stop_time() const override { return 2.0; }
  double max_step(double, std::span<const double>) const override { return 0.05; }
  std::size_t quadrature_size() const override { return 1; }
  void quadrature_rhs(double t, std::span<const double>, std::span<double> w) override { w[0] = t * t; }
};

struct QuadratureSamples : Observer {
  double q = 0;
  std::vector<std::pair<double, double>> seen;  // (t, q)
  void quadratures(std::span<const double> v) override { q = v[0]; }
  void sample(double t, std::span<const double>, bool) override { seen.emplace_back(t, q); }
};

/// Every phase of the first contact's budget closes within `tol` of the impact kinetic energy.
void expect_closes(const nlohmann::ordered_json& s, double tol, const std::string& what) {
  SCOPED_TRACE(what);
  const auto& b = s["energy_budget"];
  ASSERT_TRUE(b.is_object()) << s.dump().substr(0, 300);
  ASSERT_GT(b["impact_kinetic_energy_J"].get<double>(), 0);
  ASSERT_GE(b["phases"].size(), 3u);
  for (const auto& p : b["phases"]) {
    EXPECT_LE(std::abs(p["closure_per_impact_energy"].get<double>()), tol) << p["phase"];
    // The dissipations add up to the loss of kinetic energy (spheres and added mass) over the phase.
    const auto& ke = p["kinetic_energy_J"];
    const double loss = ke["spheres"][0].get<double>() + ke["added_mass"][0].get<double>() - ke["spheres"][1].get<double>() -
                        ke["added_mass"][1].get<double>();
    double sum = 0;
    for (const auto& [k, v] : p["dissipated_J"].items()) sum += v.get<double>();
    EXPECT_NEAR(sum - p["closure_J"].get<double>(), loss, 1e-12 * b["impact_kinetic_energy_J"].get<double>()) << p["phase"];
  }
}

double dissipated(const nlohmann::ordered_json& s, const std::string& phase, const std::string& force) {
  for (const auto& p : s["energy_budget"]["phases"])
    if (p["phase"] == phase) return p["dissipated_per_impact_energy"][force].get<double>();
  ADD_FAILURE() << "no phase " << phase;
  return NAN;
}

}  // namespace

TEST(EnergyBudget, TheQuadratureBesideTheSolverIsExactForAQuadraticIntegrand) {
  QuadraticWork sys;
  QuadratureSamples obs;
  IntegratorSettings st;
  st.output_dt = 0.013;  // samples inside the steps: the Hermite interpolant
  st.rtol = 1e-6;
  for (auto method : {IntegratorMethod::cvode, IntegratorMethod::ida}) {
    obs.seen.clear();
    st.method = method;
    integrate(sys, st, obs);
    ASSERT_GT(obs.seen.size(), 100u);
    for (const auto& [t, q] : obs.seen) EXPECT_NEAR(q, t * t * t / 3, 1e-13) << "t = " << t;
    EXPECT_NEAR(obs.seen.back().first, 2.0, 1e-12);
  }
}

TEST(EnergyBudget, WorkOfTheForcesAccountsForTheKineticEnergyToTheSolversTolerance) {
  const std::vector<Override> tight = {{"solver.rtol", "1e-10"}, {"solver.atol", "1e-12"}};
  auto with = [&](std::vector<Override> ov) {
    ov.insert(ov.end(), tight.begin(), tight.end());
    return ov;
  };
  expect_closes(simulate(load_scene(budget_scene("default"), tight)).summary_json, 1e-6, "default, cvode");
  expect_closes(simulate(load_scene(budget_scene("default"), with({{"solver.integrator", "\"ida\""}}))).summary_json, 1e-6, "default, ida");
  expect_closes(simulate(load_scene(budget_scene("seed_run2"), tight)).summary_json, 1e-6, "seed_run2 (a pair)");
  expect_closes(simulate(load_scene(budget_scene("seed_run2"), with({{"contact.law", "\"hertz\""}}))).summary_json, 1e-6,
                "seed_run2, hertz");
  expect_closes(simulate(load_scene(budget_scene("bouncing_steel"), with({{"measure.bounces", "\"first\""}}))).summary_json, 1e-6,
                "bouncing_steel (gravity)");
  expect_closes(simulate(load_scene(budget_scene("steel_glass_rough"), tight)).summary_json, 1e-6,
                "steel_glass_rough (the film ends at the roughness height)");
}

TEST(EnergyBudget, TheBudgetDoesNotTouchTheSolutionAndCanBeLeftOut) {
  const auto with = simulate(load_scene(budget_scene("default"))).summary_json;
  const auto without = simulate(load_scene(budget_scene("default"), {{"measure.energy_budget", "false"}})).summary_json;
  EXPECT_TRUE(with["energy_budget"].is_object());
  EXPECT_TRUE(without["energy_budget"].is_null());
  // The quadratures take no part in the error test: the same steps, the same e to the last digit.
  EXPECT_EQ(with["e"].get<double>(), without["e"].get<double>());
  EXPECT_EQ(with["solver"]["steps"].get<long>(), without["solver"]["steps"].get<long>());
}

TEST(EnergyBudget, ADryCollisionLosesOneMinusEDrySquaredInTheContactAndNothingElsewhere) {
  const auto s = simulate(load_scene(budget_scene("dry_steel_steel"))).summary_json;
  expect_closes(s, 1e-7, "dry");
  // Equal spheres, the target at rest: the relative motion holds half the kinetic energy, and loses 1 − e_dry² of it.
  const double e_dry = s["contact"]["e_dry"].get<double>();
  EXPECT_NEAR(dissipated(s, "contact", "contact"), 0.5 * (1 - e_dry * e_dry), 1e-6);
  EXPECT_NEAR(dissipated(s, "approach", "contact"), 0.0, 1e-12);
  EXPECT_NEAR(dissipated(s, "rebound", "contact"), 0.0, 1e-12);
}

TEST(EnergyBudget, AHertzPairAboveEDryIsExplainedByTheAddedMassNotByIntegrationError) {
  // gg3462 (glass pair in a glycerol-water mixture) with the Hertz law: e_instant exceeds e_dry at any tolerance.
  const auto s = simulate(load_scene(budget_scene("gg3462"), {{"contact.law", "\"hertz\""}, {"measure.e", "\"instant\""},
                                                              {"solver.rtol", "1e-10"}, {"solver.atol", "1e-12"}}))
                     .summary_json;
  ASSERT_GT(s["e"].get<double>(), s["contact"]["e_dry"].get<double>());
  expect_closes(s, 1e-6, "gg3462, hertz");
  std::string said;
  for (const auto& w : s["warnings"])
    if (w.get<std::string>().find("exceeds the dry restitution") != std::string::npos) said = w.get<std::string>();
  EXPECT_NE(said.find("added mass"), std::string::npos) << said;
  EXPECT_EQ(said.find("integration error"), std::string::npos) << said;
  EXPECT_EQ(said.find("energy was created"), std::string::npos) << said;
}
