// SPDX-License-Identifier: BSD-3-Clause
// Coupled model (flow kernel supplies f_SIM, MODEL.md (6.10), §5): free spheres against the standard drag curve and the
// reduced-order model with Basset history, stability for light spheres, a coarse pair collision, scene checks.
// Coarse grids only: the full validations are commands (imcol validate seed --flow; docs/coupling.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "run/event_kind.hpp"
#include "run/simulate.hpp"
#include "run/watch.hpp"
#include "model/collision_model.hpp"
#include "core/errors.hpp"
#include "coupling/divergence_watch.hpp"
#include "coupling/step_rule.hpp"
#include "integrators/integrator.hpp"
#include "core/scene.hpp"
#include "flow/flow_scene.hpp"

using namespace imcol;

namespace {

std::string scene_path(const std::string& name) { return std::string(IMCOL_DATA_DIR) + "/scenes/" + name; }

std::size_t column(const RunResult& r, const std::string& name) {
  for (std::size_t i = 0; i < r.columns.size(); ++i)
    if (r.columns[i] == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

/// Terminal speed on the standard drag curve: (ρp − ρf) g V = ½ ρf U² C_D(Re) π a², by fixed-point iteration.
double standard_terminal_speed(double D, double rho_p, double rho_f, double mu, double g) {
  double U = 0.1;
  for (int k = 0; k < 200; ++k) {
    const double Re = rho_f * U * D / mu;
    U = std::sqrt(4.0 / 3.0 * D * std::abs(rho_p - rho_f) * g / (rho_f * flow::standard_drag_coefficient(Re)));
  }
  return U;
}


/// The message of the SolverError the scene's run must end with (empty, with a test failure, if it does not).
std::string solver_error_of(const Scene& sc) {
  try {
    simulate(sc);
  } catch (const SolverError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the run was accepted";
  return {};
}
}  // namespace

TEST(Coupling, FreeFallReachesTheStandardDragCurveTerminalSpeed) {
  // Re ≈ 20, density ratio 2, 24 cells/D: within 3 % of the standard curve (the kernel's C_D is +2–4 % at this grid).
  const Scene sc = load_scene(scene_path("coupled/free_fall_re20.toml"));
  const RunResult r = simulate(sc);
  const double U = standard_terminal_speed(0.01, 2000, 1000, sc.fluid->viscosity, 9.81);
  const std::size_t iu = column(r, "u1");
  const double u_end = -r.rows.back()[iu];
  EXPECT_NEAR(u_end / U, 1.0, 0.03) << "terminal " << u_end << " m/s, standard curve " << U << " m/s";
  // A monotone approach: no oscillation from the explicit part of the coupling.
  for (std::size_t k = 1; k < r.rows.size(); ++k) ASSERT_LE(r.rows[k][iu], r.rows[k - 1][iu] + 1e-9) << "at t = " << r.rows[k][0];
  EXPECT_EQ(r.summary_json["flow"]["steps"].get<long>(), 600);
  EXPECT_GT(r.summary_json["flow"]["ms_per_step"].get<double>(), 0.0);
}

TEST(Coupling, LightSphereIsStableOnlyWithTheImplicitAddedMass) {
  // Density ratio 0.5: the fluid's inertia exceeds the sphere's. With the model's added mass implicit and removed from
  // f_SIM the rise is smooth; with f_SIM used explicitly the coupling is unstable and the run fails (exit 3).
  std::vector<Override> ov = {{"solver.t_end", "0.2"}};
  const RunResult r = simulate(load_scene(scene_path("coupled/free_rise_ratio0.5.toml"), ov));
  const std::size_t iu = column(r, "u1");
  for (std::size_t k = 1; k < r.rows.size(); ++k) {
    ASSERT_TRUE(std::isfinite(r.rows[k][iu]));
    ASSERT_GE(r.rows[k][iu], r.rows[k - 1][iu] - 1e-9) << "at t = " << r.rows[k][0];
  }
  EXPECT_GT(r.rows.back()[iu], 0.1);  // rising, toward 0.155 m/s
  ov.push_back({"flow.added_mass_estimate", "false"});
  EXPECT_THROW(simulate(load_scene(scene_path("coupled/free_rise_ratio0.5.toml"), ov)), SolverError);
}

TEST(Coupling, SlightlyDenserSphereSettlesSmoothly) {
  // Density ratio 1.2: added mass ½ of the fluid's is 0.42 of the sphere's mass.
  const Scene sc = load_scene(scene_path("coupled/free_fall_ratio1.2.toml"), {{"solver.t_end", "0.6"}});
  const RunResult r = simulate(sc);
  const std::size_t iu = column(r, "u1"), ia = column(r, "a1");
  // At t = 0 the acceleration is the buoyant weight over the mass with added mass: −g (ρp − ρf)/(ρp + ½ρf).
  EXPECT_NEAR(r.rows.front()[ia], -9.81 * 200 / 1700, 1e-6);
  for (std::size_t k = 1; k < r.rows.size(); ++k) ASSERT_LE(r.rows[k][iu], r.rows[k - 1][iu] + 1e-9);
  const double U = standard_terminal_speed(0.01, 1200, 1000, sc.fluid->viscosity, 9.81);
  EXPECT_GT(-r.rows.back()[iu] / U, 0.9);
  EXPECT_LT(-r.rows.back()[iu] / U, 1.03);
}

TEST(Coupling, SmallReTransientFollowsTheReducedModelWithBassetHistory) {
  // Re = 0.055: the coupled transient against Stokes drag + added mass + Basset history (reduced-order model). At
  // 16 cells/D the kernel's steady Stokes drag is 6.4 % high (flow verification), so the curves may differ by that
  // much; the slow approach (0.8 U_t after 20 relaxation times, where an exponential would be at 1.0) is the memory.
  const std::string path = scene_path("coupled/free_fall_stokes.toml");
  const RunResult c = simulate(load_scene(path));
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  text = text.substr(0, text.find("[flow]")) + text.substr(text.find("[solver]"));
  const RunResult r = simulate(parse_scene(text, "reduced.toml", {{"effects", R"(["gravity","drag","added_mass","history"])"}}));
  const double Ut = 1000 * 9.81 * 1e-6 / (18 * 0.1);
  std::map<long, double> ur;
  for (const auto& row : r.rows) ur[std::lround(row[0] * 1e6)] = row[2];
  double worst = 0;
  int compared = 0;
  for (const auto& row : c.rows) {
    auto it = ur.find(std::lround(row[0] * 1e6));
    if (it == ur.end()) continue;
    worst = std::max(worst, std::abs(row[2] - it->second) / Ut);
    ++compared;
  }
  EXPECT_GT(compared, 100);
  EXPECT_LT(worst, 0.064);
  const double u_end = -c.rows.back()[2] / Ut;
  EXPECT_GT(u_end, 0.7);
  EXPECT_LT(u_end, 0.9);
}

TEST(Coupling, PairCollisionMovesTheTargetBeforeContact) {
  // Seed run 4 (St_B ≈ 22) on a coarse grid: the liquid between the spheres pushes the target before they touch.
  const Scene sc = load_scene(scene_path("seed_run4.toml"),
                              {{"effects", R"(["drag","lubrication","added_mass","elastic","flow"])"}, {"flow.cells_per_diameter", "16"}});
  const RunResult r = simulate(sc);
  const auto& s = r.summary_json;
  ASSERT_FALSE(s["e"].is_null());
  EXPECT_GT(s["e"].get<double>(), 0.0);
  EXPECT_LT(s["e"].get<double>(), 0.97);
  EXPECT_GT(s["velocities_m_s"]["U_i2"].get<double>(), 0.01 * 0.113);  // the target moves before contact
  const std::size_t iH = column(r, "H"), ig = column(r, "gap");
  for (const auto& row : r.rows) {
    ASSERT_GE(row[iH], 0.0);
    ASSERT_LE(row[iH], 1.0);
    if (row[ig] >= 2 * 0.1 * 0.0127) {
      ASSERT_EQ(row[iH], 0.0);
    }
    if (row[ig] <= 0) {
      ASSERT_EQ(row[iH], 1.0);
    }
  }
  bool edge = false;
  for (const auto& ev : s["events"]) edge = edge || ev["event"].get<std::string>().find("blend edge") != std::string::npos;
  EXPECT_TRUE(edge);
  EXPECT_GT(s["flow"]["steps"].get<long>(), 10);
  EXPECT_GT(s["flow"]["flow_share"].get<double>(), 0.0);
}

TEST(Coupling, FlowSceneKeysAreChecked) {
  const std::string base = R"(effects = ["drag","elastic","flow"]
[fluid]
density = 1000.0
viscosity = 0.01
[[sphere]]
material = "steel"
diameter = 0.01
position = 0.0
velocity = 0.1
[[sphere]]
material = "steel"
diameter = 0.01
position = 0.013
)";
  auto error_of = [&](const std::string& text) {
    try {
      parse_scene(text, "s.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error_of(base), "accepted");
  EXPECT_NE(error_of(base + "[flow]\ncells = 3\n").find("s.toml:15: key 'flow.cells': unknown key"), std::string::npos);
  EXPECT_NE(error_of(base + "[flow]\ncfl = 2.0\n").find("flow.cfl"), std::string::npos);
  EXPECT_NE(error_of(base + "[flow]\ncells_per_diameter = 2\n").find("flow.cells_per_diameter"), std::string::npos);
  EXPECT_NE(error_of(base + "[flow]\nstart = \"warm\"\n").find("flow.start"), std::string::npos);
  EXPECT_NE(error_of(base + "[flow]\ndt = 0.001\ncfl = 0.3\n").find("either dt or cfl"), std::string::npos);
  EXPECT_NE(error_of(base + "[flow]\ntau_p_fraction = 0.0\n").find("s.toml:15: key 'flow.tau_p_fraction'"), std::string::npos);
  EXPECT_NE(error_of(base + "[flow]\ndt = 0.001\ntau_p_fraction = 0.3\n").find("either dt or tau_p_fraction"), std::string::npos);
  std::string no_effect = base;
  no_effect.replace(no_effect.find(",\"flow\""), 7, "");
  EXPECT_NE(error_of(no_effect + "[flow]\nlevels = 3\n").find("needs the 'flow' effect"), std::string::npos);
  std::string wall = R"(effects = ["drag","elastic","flow"]
[fluid]
density = 1000.0
viscosity = 0.01
[[sphere]]
material = "steel"
diameter = 0.01
position = 0.0
velocity = 0.1
[wall]
material = "glass"
position = 0.02
)";
  EXPECT_EQ(error_of(wall), "accepted");  // the flow kernel has a wall
}

TEST(Coupling, DevelopedStartHasItsBoundaryLayerAtTimeZero) {
  // Impulsive: the fluid starts at rest one flow step before t = 0, so the early drag is the impulsive start's
  // (Stokes + Basset ~ 1/sqrt(t)); developed: 1 D of travel before t = 0, so the drag at t = 0 is nearly steady.
  auto first_and_last = [](const std::string& start) {
    const Scene sc = load_scene(scene_path("seed_run4.toml"), {{"effects", R"(["drag","lubrication","added_mass","elastic","flow"])"},
                                                               {"flow.cells_per_diameter", "16"},
                                                               {"flow.start", "\"" + start + "\""},
                                                               {"solver.t_end", "0.01"}});
    const RunResult r = simulate(sc);
    const std::size_t i = column(r, "f_sim1");
    EXPECT_EQ(r.summary_json["flow"]["start"].get<std::string>(), start);
    return std::make_pair(r.rows[1][i], r.rows.back()[i]);
  };
  const auto [imp0, imp1] = first_and_last("impulsive");
  const auto [dev0, dev1] = first_and_last("developed");
  EXPECT_LT(dev0, 0.0);
  EXPECT_GT(imp0 / dev0, 1.5);                 // the impulsive start's drag is far larger at first
  EXPECT_NEAR(dev0 / dev1, 1.0, 0.2);          // the developed one is close to its value 10 ms later
  EXPECT_GT(std::abs(imp0), 1.2 * std::abs(imp1));  // and the impulsive one decays
}

TEST(Coupling, CvodeAndIdaAgreeInACoupledRun) {
  // The same flow steps and f_SIM; the two integrators differ only by their own error (rtol 1e-8).
  auto e_of = [](const std::string& integrator) {
    const Scene sc = load_scene(scene_path("coupled/gg3462.toml"),
                                {{"flow.cells_per_diameter", "16"}, {"flow.fields", "false"}, {"solver.integrator", "\"" + integrator + "\""}});
    return simulate(sc).summary_json["e"].get<double>();
  };
  EXPECT_NEAR(e_of("cvode"), e_of("ida"), 1e-6);
}

TEST(Coupling, MirroredCollisionGivesTheSameRestitution) {
  // Equal spheres: the target moving at −U onto the impact sphere at rest is the mirror image of the scene
  // (the frame, the start-up and the kernel's grid are built from the pair, not from sphere 1).
  auto e_of = [](std::vector<Override> ov) {
    ov.push_back({"flow.cells_per_diameter", "16"});
    ov.push_back({"flow.fields", "false"});
    ov.push_back({"flow.krylov_tol", "1e-8"});  // the mirror, not the force solve's ~1e-6 in e at the default 1e-4
    return simulate(load_scene(scene_path("coupled/gg3462.toml"), ov)).summary_json["e"].get<double>();
  };
  const double e = e_of({});
  const double mirrored = e_of({{"sphere[0].velocity", "0.0"}, {"sphere[1].velocity", "-0.110"}});
  EXPECT_NEAR(mirrored, e, 1e-6);
  EXPECT_GT(e, 0.5);
}

TEST(Coupling, SphereWallCollisionWithTheKernelsWall) {
  // The default scene (steel onto a wall) with the flow kernel and its no-slip wall, coarse: the coupled e stays
  // close to the reduced-order one (the blend gives f_THR the last 0.2 D) and below e_dry.
  const RunResult c = simulate(load_scene(scene_path("default.toml"), {{"effects", R"(["drag","lubrication","added_mass","history","elastic","flow"])"},
                                                                      {"flow.cells_per_diameter", "16"}, {"flow.fields", "false"}}));
  const RunResult r = simulate(load_scene(scene_path("default.toml")));
  const double e = c.summary_json["e"].get<double>();
  EXPECT_GT(e, 0.5);
  EXPECT_LT(e, c.summary_json["contact"]["e_dry"].get<double>());
  EXPECT_NEAR(e, r.summary_json["e"].get<double>(), 0.05);
  const std::size_t iH = column(c, "H");
  EXPECT_EQ(c.rows.front()[iH], 0.0);  // the sphere starts 0.5 D from the wall: beyond 2 delta_sl
  EXPECT_GT(c.summary_json["flow"]["steps"].get<long>(), 10);
}

TEST(Coupling, AFlowDivergenceEndsTheRunNamingTheFlowCoupling) {
  // gondret_st742 (Re ≈ 966, 16 cells/D) at the old default cfl 0.5: the kernel's AB2 advection diverges while the flow
  // develops, and its force would launch the sphere (it reached the wall at 4e7 m/s). The run must end with a
  // SolverError (exit 3) that names the flow coupling and flow.cfl, not contact.delta_ss.
  const std::vector<Override> ov = {{"flow.cfl", "0.5"}, {"flow.fields", "false"}, {"measure.bounces", "\"first\""}};
  const std::string m = solver_error_of(load_scene(scene_path("coupled/gondret_st742.toml"), ov));
  EXPECT_NE(m.find("the flow coupling diverged"), std::string::npos) << m;
  EXPECT_NE(m.find("flow.cfl"), std::string::npos) << m;
  EXPECT_EQ(m.find("delta_ss"), std::string::npos) << m;
}

TEST(Coupling, TheDefaultFlowStepIsStableAtReynolds1000) {
  // The same scene with the default step (cfl(Re, N) = 0.5 √(5600/(Re N)) = 0.30 here): a sane first bounce, the
  // spheres' kinetic energy never beyond what the initial motion and gravity supply, the fluid's Courant number < 1.5.
  const RunResult r = simulate(load_scene(scene_path("coupled/gondret_st742.toml"), {{"flow.fields", "false"}, {"measure.bounces", "\"first\""}}));
  const auto& s = r.summary_json;
  const double Re = 920.0 * 1.0467 * 0.005 / 0.005;
  EXPECT_NEAR(s["flow"]["cfl"].get<double>(), 0.5 * std::sqrt(5600 / (Re * 16)), 1e-9);
  const double e = s["e"].get<double>();
  EXPECT_GT(e, 0.5);
  EXPECT_LT(e, s["contact"]["e_dry"].get<double>());
  EXPECT_LE(s["flow"]["max_energy_ratio"].get<double>(), 1.0);
  EXPECT_LT(s["flow"]["max_courant"].get<double>(), 1.5);
}

TEST(Coupling, TheSpeedJumpCheckKnowsSolidContactByTheEventKind) {
  // The first rebound's measurement root "gap=max(at_gap, delta_ss+fit_distance) (out)" names delta_ss but is no
  // contact: the speed-jump check goes by the event's kind, not its name.
  const Scene sc = load_scene(scene_path("default.toml"));
  model::CollisionModel model(sc);
  run::Watch watch(model, sc);  // the first rebound's measurement root is a watcher's
  struct : Observer {
    void sample(double, std::span<const double>, bool) override {}
  } quiet;
  integrate(model, IntegratorSettings{}, quiet);
  int in = 0, out = 0, measure = 0;
  for (const auto& ev : model.events()) {
    if (run::kind_of(ev) == run::EventKind::contact_in) {
      ++in;
      EXPECT_EQ(ev.name, "gap=delta_ss (in)");
    }
    if (run::kind_of(ev) == run::EventKind::contact_out) {
      ++out;
      EXPECT_EQ(ev.name, "gap=delta_ss (out)");
    }
    if (run::kind_of(ev) == run::EventKind::measure_out) {
      ++measure;
      EXPECT_NE(ev.name.find("delta_ss"), std::string::npos) << ev.name;
      EXPECT_FALSE(coupling::is_solid_contact(ev.kind));
    }
    if (run::kind_of(ev) == run::EventKind::contact_in || run::kind_of(ev) == run::EventKind::contact_out) {
      EXPECT_TRUE(coupling::is_solid_contact(ev.kind));
    }
  }
  EXPECT_EQ(in, 1);
  EXPECT_EQ(out, 1);
  EXPECT_EQ(measure, 1);
  EXPECT_TRUE(coupling::is_solid_contact(run::tag(run::EventKind::touch)));
  EXPECT_FALSE(coupling::is_solid_contact(run::tag(run::EventKind::blend_edge)));
}

TEST(Coupling, TheStepRuleScalesAStartFromRestByTheSpeedItCanReach) {
  // free_fall_re100 without its flow.dt: U_ref is the terminal speed on the standard drag curve (0.3469 m/s, the
  // scene's comment), not 0 (which gave the viscous step and a Courant number near 2 at t = 0.21 s).
  Scene sc = load_scene(scene_path("coupled/free_fall_re100.toml"));
  sc.flow.dt = 0;
  const coupling::ReferenceSpeed u = coupling::reference_speed(sc);
  EXPECT_NEAR(u.u, 0.3469, 0.002);
  EXPECT_NE(u.source.find("terminal speed"), std::string::npos) << u.source;
  const coupling::FlowStep st = coupling::flow_step(sc, 0.01 / 24);
  EXPECT_EQ(st.limit, coupling::StepLimit::courant);
  EXPECT_NEAR(st.cfl, 0.5, 1e-12);  // Re 100 x 24 cells/D < 5600
  EXPECT_NEAR(st.dt, 0.5 * 0.01 / 24 / u.u, 1e-12);
  EXPECT_NE(st.rule.find("Re = 100"), std::string::npos) << st.rule;
  // Near a wall the fall bounds it: from rest 0.2 D above the plate, √(2 g' L) with g' = g (ρ_p − ρ_f)/(ρ_p + ρ_f/2).
  Scene w = sc;
  w.wall = WallSpec{};
  w.wall->position = 0.005 + 0.002;  // + is toward the target: gravity must point there
  w.gravity = 9.81;
  const double g_eff = 9.81 * 1000.0 / 2500.0;
  EXPECT_NEAR(coupling::reference_speed(w).u, std::sqrt(2 * g_eff * 0.002), 1e-9);
  // Away from the wall (buoyancy lifts it): the terminal speed again.
  w.gravity = -9.81;
  EXPECT_NEAR(coupling::reference_speed(w).u, u.u, 1e-9);
  // The file's flow.dt is kept.
  const coupling::FlowStep given = coupling::flow_step(load_scene(scene_path("coupled/free_fall_re100.toml")), 0.01 / 24);
  EXPECT_EQ(given.dt, 0.0005);
  EXPECT_EQ(given.limit, coupling::StepLimit::given);
}

TEST(Coupling, ALowReynoldsSphereRunsSaneAtTheDefaultStep) {
  // Glass, D = 3 mm, U = 0.05 m/s, mu = 1 Pa s (Re = 0.15), 12 cells/D, 1 D from a wall. The Courant step (cfl 0.5:
  // 2.5 ms) is 1.6 tau_p: the explicit fluid force overshoots and the run diverged. The default step is
  // flow.tau_p_fraction x tau_p; the sphere then slows without reversing (no oscillation) and never gains energy.
  const std::string text = std::string(R"(effects = ["drag", "lubrication", "added_mass", "history", "elastic", "flow"]
[fluid]
density = 1000.0
viscosity = 1.0
[[sphere]]
material = "glass"
diameter = 0.003
position = 0.0
velocity = 0.05
[wall]
material = "glass"
position = 0.0045
[flow]
cells_per_diameter = 12
levels = 3
fields = false
[solver]
t_end = 0.02
)");
  const Scene sc = parse_scene(text, "low_re.toml");
  const double tau_p = coupling::relaxation_time(sc, 0);
  const double rho_p = sc.spheres[0].density;
  EXPECT_NEAR(tau_p, (rho_p + 500.0) * 0.003 * 0.003 / 18.0, 1e-12);
  const coupling::FlowStep st = coupling::flow_step(sc, 0.003 / 12);
  EXPECT_EQ(st.limit, coupling::StepLimit::relaxation);
  EXPECT_NEAR(st.dt, sc.flow.tau_p_fraction * tau_p, 1e-15);
  const RunResult r = simulate(sc);
  EXPECT_LE(r.summary_json["flow"]["max_energy_ratio"].get<double>(), 1.0);
  const std::size_t iu = column(r, "u1");
  int reversals = 0;
  for (std::size_t k = 1; k < r.rows.size(); ++k)
    if (r.rows[k][0] > 3 * tau_p && r.rows[k][iu] * r.rows[k - 1][iu] < 0) ++reversals;
  EXPECT_EQ(reversals, 0);
  // At the Courant step alone (tau_p_fraction large) the run ends with exit 3 naming the flow coupling and flow.cfl.
  Scene courant = sc;
  courant.flow.tau_p_fraction = 1e6;
  const std::string mc = solver_error_of(courant);  // the run at 1.6 tau_p
  EXPECT_NE(mc.find("the flow coupling diverged"), std::string::npos) << mc;
  // A divergence while tau_p limits the step names tau_p, not the fluid's speed.
  Scene tau = sc;
  tau.flow.tau_p_fraction = 1.0;
  const std::string mt = solver_error_of(tau);  // the run at 1.0 tau_p
  EXPECT_NE(mt.find("flow.tau_p_fraction"), std::string::npos) << mt;
  EXPECT_EQ(mt.find("the fluid's speed"), std::string::npos) << mt;
}

TEST(Coupling, AHugeDevelopedTimeIsRefusedNotOverflowed) {
  // 1e29 s of start-up at a 1.8 ms flow step: 5.5e31 steps, which std::lround cannot hold (it used to run one step).
  try {
    simulate(load_scene(scene_path("coupled/gg3462.toml"), {{"flow.developed_time", "1e29"}, {"flow.fields", "false"}}));
    ADD_FAILURE() << "not refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "flow.developed_time") << e.what();
  }
}

TEST(Coupling, FlowFieldsAreComputedOnlyForASink) {
  // flow.fields (on by default) writes through simulate's file sink; a run without one (a sweep's point, a comparison)
  // computes no snapshots. The fields are read from the kernel, so the run itself is the same either way.
  const Scene sc = load_scene(scene_path("coupled/gg3462.toml"), {{"flow.cells_per_diameter", "8"}});
  std::vector<std::string> names;
  const RunResult written = simulate(sc, false, Recording::full, [&names](const std::string& name, const std::string&) { names.push_back(name); });
  const RunResult silent = simulate(sc);
  const auto& w = written.summary_json["flow"];
  const auto& s = silent.summary_json["flow"];
  EXPECT_GE(w["field_snapshots"].get<int>(), 2);  // at least the contact and the end
  EXPECT_NE(std::find(names.begin(), names.end(), "flow_end.csv"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "flow.pvd"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "flow.py"), names.end());  // the ParaView state beside it
  EXPECT_NE(std::find(names.begin(), names.end(), "vtk/flow_contact_kernel_spheres.vtp"), names.end());
  EXPECT_EQ(s["field_snapshots"].get<int>(), 0);
  EXPECT_EQ(s["fields_time_s"].get<double>(), 0.0);
  EXPECT_EQ(silent.summary_json["e"].get<double>(), written.summary_json["e"].get<double>());
  EXPECT_EQ(s["steps"].get<long>(), w["steps"].get<long>());
}
