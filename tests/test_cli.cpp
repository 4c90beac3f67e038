// SPDX-License-Identifier: BSD-3-Clause
// The command line: exit status 2 and a one-line message naming key and file for bad input;
// complete outputs for good input.
#include <gtest/gtest.h>

#include <algorithm>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>

#include "core/materials.hpp"
#include "tests/imcol_process.hpp"
#include "tests/scene_text.hpp"

namespace fs = std::filesystem;

namespace {
struct Result {
  int status;
  std::string err;
};

/// Runs imcol with `args`; `shell_prefix` runs first in the same shell (e.g. a ulimit).
Result run_imcol(const std::string& args, const std::string& shell_prefix = "") {
  const fs::path errf = fs::temp_directory_path() / ("imcol_cli_err_" + std::to_string(::getpid()));
  const std::string cmd = shell_prefix + std::string(IMCOL_BINARY) + " " + args + " >/dev/null 2>" + errf.string();
  const int raw = std::system(cmd.c_str());
  std::ifstream in(errf);
  std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  fs::remove(errf);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, err};
}

fs::path write_scene(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("imcol_cli_" + name + ".toml");
  std::ofstream(p) << text;
  return p;
}

const std::string kScene = imcol::test::basic_wall_scene();

/// `imcol sweep` of the gg3462 scene with `args` into `out`, emptied first.
Result sweep_gg3462(const fs::path& out, const std::string& args) {
  fs::remove_all(out);
  return run_imcol("sweep " + imcol::data_dir() + "/scenes/gg3462.toml " + args + " --out " + out.string());
}

void expect_input_error(const std::string& name, const std::string& text, const std::string& key, const std::string& extra = "") {
  const fs::path p = write_scene(name, text);
  const Result r = run_imcol("run " + p.string() + " --out " + (fs::temp_directory_path() / "imcol_cli_out").string() + " " + extra);
  EXPECT_EQ(r.status, 2) << name << ": " << r.err;
  EXPECT_NE(r.err.find(key), std::string::npos) << name << ": " << r.err;
  if (extra.empty()) {
    EXPECT_NE(r.err.find(p.string()), std::string::npos) << name << ": " << r.err;
  }
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << name << ": " << r.err;
}

}  // namespace

TEST(Cli, BadInputGivesExitStatusTwoAndNamesTheKey) {
  expect_input_error("missing", imcol::test::edit(kScene, "viscosity = 0.01\n", ""), "fluid.viscosity");
  expect_input_error("unknown", imcol::test::edit(kScene, "viscosity = 0.01", "viscosity = 0.01\nsurface_tension = 0.07"), "fluid.surface_tension");
  expect_input_error("negvisc", imcol::test::edit(kScene, "viscosity = 0.01", "viscosity = -0.01"), "fluid.viscosity");
  expect_input_error("negdens", imcol::test::edit(kScene, "density = 1000.0", "density = -1000.0"), "fluid.density");
  expect_input_error("overlap", imcol::test::edit(kScene, "position = -0.02", "position = -0.005"), "wall.position");
  expect_input_error("material", imcol::test::edit(kScene, "\"steel\"", "\"kryptonite\""), "sphere[0].material");
  expect_input_error("rtol", kScene + "[solver]\nrtol = 0\n", "solver.rtol");
  expect_input_error("rtolcli", kScene, "key '--rtol'", "--rtol -1e-8");
  const Result r = run_imcol("run /nonexistent/scene.toml");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("/nonexistent/scene.toml"), std::string::npos);
  expect_input_error("noelastic", "effects = [\"drag\"]\n" + kScene, "effects");
  expect_input_error("tiny", imcol::test::edit(kScene, "diameter = 0.0127", "diameter = 1e-200"), "sphere[0].diameter");
  expect_input_error("huge", imcol::test::edit(kScene, "velocity = 0.2", "velocity = 1e300"), "sphere[0].velocity");
  expect_input_error("samples", kScene + "[output]\ndt = 1e-12\n", "output.dt");
  expect_input_error("path", "name = \"../escaped\"\n" + kScene, "name");
  EXPECT_EQ(run_imcol("run").status, 2);
  EXPECT_EQ(run_imcol("frobnicate").status, 2);
}

TEST(Cli, RunWritesCompleteOutputs) {
  const fs::path p = write_scene("good", kScene);
  const fs::path out = fs::temp_directory_path() / "imcol_cli_good_out";
  fs::remove_all(out);
  const Result r = run_imcol("run " + p.string() + " --out " + out.string() + " --rtol 1e-9 --set sphere[0].velocity=0.25");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream js(out / "summary.json");
  const auto s = nlohmann::json::parse(js);
  for (const char* k : {"e", "e_instant", "St", "Re", "min_gap_m", "max_contact_force_N", "group_velocity_m_s", "effects",
                        "model", "solver", "wall_time_s"})
    EXPECT_TRUE(s.contains(k)) << k;
  EXPECT_DOUBLE_EQ(s["solver"]["rtol"].get<double>(), 1e-9);
  for (const char* k : {"integrator", "steps", "rhs_evals", "root_events", "error_test_fails"}) EXPECT_TRUE(s["solver"].contains(k)) << k;
  std::ifstream csv(out / "trajectory.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("t,z1,u1,gap", 0), 0u) << header;
  // run draws its own picture (--no-plot skips it), and leaves no temporary files behind.
  EXPECT_TRUE(fs::exists(out / "trajectory.png"));
  for (const auto& f : fs::directory_iterator(out)) EXPECT_EQ(f.path().string().find(".tmp"), std::string::npos);
  // Velocity override took effect: the first row's u1.
  std::string row;
  std::getline(csv, row);
  EXPECT_NE(row.find(",0.25,"), std::string::npos) << row;
}

TEST(Cli, SolverFailureIsReportedWithItsCause) {
  const fs::path p = write_scene("fail", kScene);
  const Result r = run_imcol("run " + p.string() + " --out " + (fs::temp_directory_path() / "imcol_cli_fail").string() +
                         " --set solver.max_steps=3 --set 'effects=[\"drag\",\"lubrication\",\"added_mass\",\"elastic\"]'");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("CV_TOO_MUCH_WORK"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("gap="), std::string::npos) << r.err;  // names the state components
  EXPECT_NE(r.err.find("t = "), std::string::npos) << r.err;
}

TEST(Cli, ContactZoneTooThinForTheImpactIsAnInputError) {
  // A soft sphere at high speed: the Hertz indentation exceeds delta_ss*D.
  const fs::path p = write_scene("soft", imcol::test::edit(imcol::test::edit(kScene, "material = \"steel\"", "density = 1000.0\nyoungs_modulus = 1e5\npoisson_ratio = 0.45\ne_dry = 0.5"), "velocity = 0.2", "velocity = 5.0"));
  const Result r = run_imcol("run " + p.string() + " --out " + (fs::temp_directory_path() / "imcol_cli_soft").string() +
                         " --set contact.delta_ss=0.001");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("contact.delta_ss"), std::string::npos) << r.err;
}

TEST(Cli, HistoryComparesKernelsAndWritesTableAndPlotData) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_history";
  fs::remove_all(out);
  const std::string scene = imcol::data_dir() + "/scenes/rising_sphere.toml";
  const Result r = run_imcol("history " + scene + " --out " + out.string() +
                             " --kernels basset,kim --evaluators soe --no-plot --set solver.t_end=0.01");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(out / "history.csv");
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("kernel,evaluator,u_end_m_s,", 0), 0u) << header;
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 3);  // none, basset soe, kim soe
  EXPECT_TRUE(fs::exists(out / "history_forces.csv"));
  // `effects` on a scene with a [history] table drops the effect without tripping over the table.
  EXPECT_EQ(run_imcol("effects " + scene + " --set solver.t_end=0.01").status, 0);
  const Result bad = run_imcol("history " + scene + " --kernels oseen --out " + out.string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("oseen"), std::string::npos) << bad.err;
}

namespace {
/// Rows of a CSV file as column name → cell (lines starting with '#' before the header are comments).
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> cols;
  std::vector<std::map<std::string, std::string>> rows;
  auto split = [](const std::string& line) {
    std::vector<std::string> v;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) v.push_back(x);
    if (!line.empty() && line.back() == ',') v.emplace_back();
    return v;
  };
  std::string line;
  while (std::getline(in, line) && line.rfind('#', 0) == 0) {
  }
  cols = split(line);
  while (std::getline(in, line)) {
    const auto cells = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cols.size() && i < cells.size(); ++i) row[cols[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}
}  // namespace

TEST(Cli, WorkPrecisionErrorsFallAsTheToleranceTightens) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_wp";
  fs::remove_all(out);
  const Result r = run_imcol("work-precision " + imcol::data_dir() + "/scenes/default.toml --out " + out.string() +
                             " --rtols 1e-4,1e-6,1e-8 --integrators cvode-dense,ida --repeat 1 --ref-rtol 1e-11 --no-plot --set 'effects=[\"drag\",\"lubrication\",\"added_mass\",\"elastic\"]'");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = read_csv(out / "work_precision.csv");
  ASSERT_EQ(rows.size(), 6u);
  for (std::size_t k = 0; k < rows.size(); k += 3) {
    for (std::size_t i = k; i < k + 3; ++i) EXPECT_EQ(rows[i].at("status"), "ok") << rows[i].at("message");
    const double loose = std::stod(rows[k].at("err_e")), tight = std::stod(rows[k + 2].at("err_e"));
    EXPECT_LT(tight, loose / 10) << rows[k].at("integrator");  // two decades of rtol buy at least one of error
    EXPECT_LT(tight, 1e-5);
    EXPECT_LT(std::stod(rows[k + 2].at("err_trajectory")), std::stod(rows[k].at("err_trajectory")));
  }
  std::ifstream js(out / "work_precision.json");
  const auto j = nlohmann::json::parse(js);
  EXPECT_EQ(j["reference"]["rtol"].get<double>(), 1e-11);
  EXPECT_TRUE(j["cheapest"].contains("1e-03"));
  EXPECT_FALSE(j["cheapest"]["1e-03"].is_null());
  // gmres without history cannot run: skipped with its reason, not an error.
  const Result g = run_imcol("work-precision " + imcol::data_dir() + "/scenes/default.toml --out " + out.string() +
                             " --rtols 1e-6 --integrators cvode-gmres,cvode-dense --repeat 1 --ref-rtol 1e-10 --no-plot --set 'effects=[\"drag\",\"lubrication\",\"added_mass\",\"elastic\"]'");
  EXPECT_EQ(g.status, 0) << g.err;
  EXPECT_EQ(read_csv(out / "work_precision.csv").size(), 1u);
  const Result bad = run_imcol("work-precision " + imcol::data_dir() + "/scenes/default.toml --integrators lsoda --out " + out.string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("lsoda"), std::string::npos) << bad.err;
}

TEST(Cli, SweepWritesStAndEAndKeepsFinishedPointsWhenOneFails) {
  const std::string scene = imcol::data_dir() + "/scenes/gg3462.toml";
  const fs::path out = fs::temp_directory_path() / "imcol_cli_sweep";
  const Result r = sweep_gg3462(out, "--vary velocity --from 0.05 --to 0.4 --points 4 --jobs 2 --no-plot");
  ASSERT_EQ(r.status, 0) << r.err;
  auto rows = read_csv(out / "sweep.csv");
  ASSERT_EQ(rows.size(), 4u);
  double last_st = 0, last_e = -1;
  for (const auto& row : rows) {
    ASSERT_EQ(row.at("status"), "ok") << row.at("message");
    const double st = std::stod(row.at("St")), e = std::stod(row.at("e"));
    EXPECT_GT(st, last_st);  // faster impact, larger St
    EXPECT_GT(e, last_e);    // and a more elastic rebound
    EXPECT_LE(e, 0.97);
    last_st = st, last_e = e;
  }
  // The very viscous point needs < 50 steps between samples, the least viscous > 80: with 70 allowed, one fails.
  const Result f = sweep_gg3462(out, "--vary viscosity --from 0.001 --to 0.1 --points 2 --no-plot --set solver.max_steps=70 "
                                     "--set 'effects=[\"drag\",\"lubrication\",\"added_mass\",\"elastic\"]'");
  EXPECT_EQ(f.status, 3) << f.err;
  // Said on stderr too (stdout may be a file): one line with the count and where the reasons are.
  EXPECT_EQ(f.err.rfind("imcol: error: 1 of 2 sweep points failed", 0), 0u) << f.err;
  EXPECT_NE(f.err.find("sweep.json"), std::string::npos) << f.err;
  EXPECT_EQ(std::count(f.err.begin(), f.err.end(), '\n'), 1) << f.err;
  rows = read_csv(out / "sweep.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("status"), "failed");
  EXPECT_NE(rows[0].at("message").find("CV_TOO_MUCH_WORK"), std::string::npos) << rows[0].at("message");
  EXPECT_EQ(rows[1].at("status"), "ok");
  EXPECT_FALSE(rows[1].at("e").empty());
  std::ifstream js(out / "sweep.json");
  const auto j = nlohmann::json::parse(js);
  ASSERT_EQ(j["failures"].size(), 1u);
  EXPECT_EQ(j["failures"][0]["point"].get<int>(), 0);
  // Bad input stops the sweep before anything runs.
  const Result bad = run_imcol("sweep " + scene + " --vary viscosity --from -1 --to 0.1 --points 3 --out " + out.string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("--from"), std::string::npos) << bad.err;
  const Result neg = run_imcol("sweep " + scene + " --vary velocity --from 0.1 --to 0.2 --points 2 --set fluid.viscosity=-1 --out " + out.string());
  EXPECT_EQ(neg.status, 2) << neg.err;
  EXPECT_NE(neg.err.find("fluid.viscosity"), std::string::npos) << neg.err;
}

TEST(Cli, SweepThatCannotWriteItsTableKeepsThePreviousResultAndPutsItsPointsBeside) {
  // A complete sweep, then one under a file-size limit of 1 KiB: sweep.csv outgrows it after a few points and the
  // write fails in a worker thread. The complete sweep stays; the points finished go to a folder beside it.
  const fs::path out = fs::temp_directory_path() / "imcol_cli_sweep_unwritable";
  const std::string sweep = "sweep " + imcol::data_dir() + "/scenes/default.toml --vary velocity --from 0.1 --to 0.3 --jobs 2 --no-plot --no-progress ";
  auto partials = [&] {
    std::vector<fs::path> v;
    for (const auto& f : fs::directory_iterator(out.parent_path()))
      if (f.path().filename().string().rfind(out.filename().string() + ".partial-", 0) == 0) v.push_back(f.path());
    return v;
  };
  for (const auto& p : partials()) fs::remove_all(p);
  fs::remove_all(out);
  ASSERT_EQ(run_imcol(sweep + "--points 3 --out " + out.string()).status, 0);
  const std::string complete = imcol::test::slurp(out / "sweep.csv");
  const Result r = run_imcol(sweep + "--points 200 --out " + out.string(), "ulimit -f 2; ");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err.rfind("imcol: error: sweep stopped after ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("writing sweep.csv failed (") , std::string::npos) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(out.string() + " is as it was"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(imcol::test::slurp(out / "sweep.csv"), complete);
  EXPECT_TRUE(fs::exists(out / "sweep.json"));
  EXPECT_FALSE(fs::exists(out / "sweep.partial"));
  const auto kept = partials();
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_NE(r.err.find(kept[0].string()), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(kept[0] / "sweep.partial"));
  EXPECT_TRUE(fs::exists(kept[0] / "sweep.csv"));
  EXPECT_FALSE(fs::exists(kept[0] / "sweep.json"));
  for (const auto& f : fs::directory_iterator(kept[0])) EXPECT_EQ(f.path().string().find(".tmp."), std::string::npos) << f.path();
  for (const auto& f : fs::directory_iterator(out.parent_path()))
    EXPECT_NE(f.path().filename().string().rfind("." + out.filename().string() + ".", 0), 0u) << f.path();
  fs::remove_all(kept[0]);
  fs::remove_all(out);
}

TEST(Cli, BadBouncesValueNamesFileLineAndKey) {
  const std::string text = kScene + "[measure]\nbounces = \"every\"\n";
  const fs::path p = write_scene("bounces", text);
  const Result r = run_imcol("run " + p.string() + " --out " + (fs::temp_directory_path() / "imcol_cli_out").string());
  EXPECT_EQ(r.status, 2) << r.err;
  const int line = static_cast<int>(std::count(text.begin(), text.end(), '\n'));  // the last line holds the key
  EXPECT_NE(r.err.find(p.string() + ":" + std::to_string(line)), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("measure.bounces"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("first | all"), std::string::npos) << r.err;
}

TEST(Cli, ValidateSeedRunsBothGapLawsWithBothStokesNumbers) {
  // Reduced-order Table 6.1 (12 runs of a few ms): the seed's gap law and the asymptotic one, both St_B conventions.
  const fs::path out = fs::temp_directory_path() / "imcol_cli_validate";
  fs::remove_all(out);
  const Result r = run_imcol("validate seed --no-plot --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = read_csv(out / "validate_seed.csv");
  ASSERT_EQ(rows.size(), 24u);  // each run and model at V_Io and at the printed St_B
  std::map<std::string, std::map<std::string, double>> e;  // model -> run -> e at V_Io
  for (const auto& row : rows) {
    if (row.at("speed_set") != "V_Io") continue;
    const double e_seed = std::stod(row.at("e_seed")), v = std::stod(row.at("e"));
    EXPECT_EQ(row.at("lubrication_model"), row.at("model"));
    EXPECT_NEAR(std::stod(row.at("e_minus_e_seed")), v - e_seed, 1e-9);
    EXPECT_NEAR(std::stod(row.at("St_B_eq_6_2")) / std::stod(row.at("St_B_table_6_1")), 2.0, 1e-9);
    EXPECT_EQ(row.at("St_B"), row.at("St_B_table_6_1"));
    e[row.at("model")][row.at("run")] = v;
  }
  ASSERT_EQ(e["seed"].size(), 6u);
  ASSERT_EQ(e["asymptotic"].size(), 6u);
  // Twice the gap resistance dissipates more: the seed's law never gives the larger e (equal radii in every run).
  for (const auto& [run, v] : e["seed"]) EXPECT_LE(v, e["asymptotic"][run] + 1e-9) << "run " << run;
  EXPECT_LT(e["seed"]["4"], e["asymptotic"]["4"] - 0.1);
  const Result bad = run_imcol("validate seed --no-plot --models seed,wall --out " + out.string());
  EXPECT_EQ(bad.status, 2) << bad.err;
  EXPECT_NE(bad.err.find("--models"), std::string::npos) << bad.err;
}

TEST(Cli, ValidateSeedRunsEachRunAtVIoAndAtThePrintedStB) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_validate_speed";
  fs::remove_all(out);
  const imcol::test::Outcome r = imcol::test::run_imcol("validate seed --no-plot --out " + out.string(), out.string() + "_output");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("At V_Io"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("At St_B"), std::string::npos) << r.out;
  std::map<std::string, double> V_Io;  // run -> the printed approach speed, m/s
  for (const auto& t : read_csv(fs::path(imcol::data_dir()) / "reference" / "li_2010_table_6_1.csv"))
    V_Io[t.at("run")] = std::stod(t.at("V_Io_cm_s")) / 100;
  std::map<std::string, std::map<std::string, int>> sets;  // run,model -> speed_set -> rows
  for (const auto& row : read_csv(out / "validate_seed.csv")) {
    const std::string& set = row.at("speed_set");
    ++sets[row.at("run") + "," + row.at("model")][set];
    const double St = std::stod(row.at("St_B_table_6_1")), printed = std::stod(row.at("St_B_seed")), V = std::stod(row.at("V_m_s"));
    if (set == "St_B") {
      EXPECT_LT(std::abs(St - printed) / printed, 0.02) << "run " << row.at("run") << ", " << row.at("model");
      continue;
    }
    ASSERT_EQ(set, "V_Io");
    // The V_Io rows are the shipped scenes as they stand: the same numbers as `imcol run` gives.
    EXPECT_NEAR(V, V_Io.at(row.at("run")), 1e-12);
    const fs::path one = out.string() + "_run";
    const std::string scene = imcol::data_dir() + "/scenes/seed_run" + row.at("run") + ".toml";
    ASSERT_EQ(run_imcol("run " + scene + " --quiet --no-plot --set 'lubrication.model=\"" + row.at("lubrication_model") + "\"' --out " +
                        one.string()).status, 0);
    std::ifstream js(one / "summary.json");
    const auto s = nlohmann::json::parse(js);
    EXPECT_NEAR(std::stod(row.at("e")), s["e"].get<double>(), 1e-9) << "run " << row.at("run");
    EXPECT_NEAR(St, s["St_B_table_6_1"].get<double>(), 1e-9 * St) << "run " << row.at("run");
    fs::remove_all(one);
  }
  ASSERT_EQ(sets.size(), 12u);
  for (const auto& [key, n] : sets) EXPECT_EQ(n, (std::map<std::string, int>{{"St_B", 1}, {"V_Io", 1}})) << key;
  fs::remove_all(out);
}

TEST(Cli, ValidateRejectsBadInput) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_validate_bad";
  fs::remove_all(out);
  auto expect_exit2 = [&](const Result& r, std::initializer_list<const char*> fragments) {
    EXPECT_EQ(r.status, 2) << r.err;
    for (const char* f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << "'" << f << "' missing in: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  };
  const std::string base = "validate seed --no-plot --out " + out.string() + " ";
  expect_exit2(run_imcol(base + "--tolerance -0.1"), {"--tolerance", "(0, 1]"});
  expect_exit2(run_imcol(base + "--tolerance 0"), {"--tolerance"});
  EXPECT_EQ(run_imcol(base + "--tolerance abc").status, 2);
  // The gap law is what the models differ in: --set cannot override it, --models chooses.
  expect_exit2(run_imcol(base + "--set 'lubrication.model=\"asymptotic\"'"), {"lubrication.model", "--models"});
  EXPECT_FALSE(fs::exists(out));  // nothing ran, nothing was created

  // A malformed reference table (IMCOL_DATA_DIR makes it user input) names the file, the line and the column.
  const fs::path data = fs::temp_directory_path() / "imcol_cli_validate_data";
  fs::remove_all(data);
  fs::create_directories(data / "reference");
  fs::copy_file(fs::path(imcol::data_dir()) / "materials.csv", data / "materials.csv");
  const fs::path table = data / "reference" / "li_2010_table_6_1.csv";
  auto with_table = [&](const std::string& rows) {
    std::ofstream(table) << "# a comment\nrun,mu_cP,rho_l_g_cm3,rho_p_star_g_cm3,V_Io_cm_s,Re_Io,St_B,e,pair\n"
                            "1,4.1,1.11,7.78,8.4,264,197,0.87,steel-steel\n" << rows;
    const std::string cmd = "IMCOL_DATA_DIR='" + data.string() + "' " + IMCOL_BINARY + " " + base + " >/dev/null 2>" + (data / "err").string();
    const int raw = std::system(cmd.c_str());
    std::ifstream in(data / "err");
    return Result{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>())};
  };
  expect_exit2(with_table("2,4.1,1.11,3.83,9.6,294,104,0.7x5,steel-glass\n"), {(table.string() + ":4").c_str(), "key 'e'", "0.7x5"});
  expect_exit2(with_table("2,4.1,1.11,3.83,9.6,294,,0.75,steel-glass\n"), {(table.string() + ":4").c_str(), "key 'St_B'"});
  expect_exit2(with_table("2,4.1,1.11,3.83,9.6,294,104,0.75\n"), {(table.string() + ":4").c_str(), "9 columns"});
  expect_exit2(with_table("x,4.1,1.11,3.83,9.6,294,104,0.75,steel-glass\n"), {(table.string() + ":4").c_str(), "key 'run'"});
  expect_exit2(with_table("2,4.1,1.11,3.83,9.6,294,104,1.75,steel-glass\n"), {(table.string() + ":4").c_str(), "key 'e'"});
  fs::remove_all(data);
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, ValidatePlotsBothLayoutsAndLeavesNoStalePicture) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_validate_plot";
  fs::remove_all(out);
  // An earlier validation with its picture; then --no-plot: the old picture goes, the CSV is new.
  ASSERT_EQ(run_imcol("validate seed --models seed --out " + out.string()).status, 0);
  ASSERT_TRUE(fs::exists(out / "validate_seed.png"));
  ASSERT_EQ(run_imcol("validate seed --no-plot --models seed --out " + out.string()).status, 0);
  EXPECT_FALSE(fs::exists(out / "validate_seed.png"));
  // With the plot (reduced-order layout, both models): a real PNG.
  const Result r = run_imcol("validate seed --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  ASSERT_TRUE(fs::exists(out / "validate_seed.png"));
  EXPECT_GT(fs::file_size(out / "validate_seed.png"), 10000u);
  // The --flow layout (its extra columns; the coupled runs are too slow for a test): the reduced-order rows with the
  // coupled columns filled from them, drawn by the script as the command would.
  std::ifstream in(out / "validate_seed.csv");
  std::string header, line, csv;
  std::getline(in, header);
  csv = header + ",e_reduced_order,e_reduced_order_minus_e_seed,St_B_table_6_1_reduced_order,St_B_eq_6_2_reduced_order,"
                 "wall_time_reduced_order_s,flow_steps,flow_ms_per_step,cells_per_diameter,flow_dt_s\n";
  const auto rows = read_csv(out / "validate_seed.csv");
  ASSERT_EQ(rows.size(), 24u);
  for (std::size_t i = 0; std::getline(in, line); ++i) {
    const auto& row = rows.at(i);
    csv += line + "," + row.at("e") + "," + row.at("e_minus_e_seed") + "," + row.at("St_B_table_6_1") + "," + row.at("St_B_eq_6_2") +
           "," + row.at("wall_time_s") + ",10,1.0,16,0.001\n";
  }
  const fs::path flow = fs::temp_directory_path() / "imcol_cli_validate_plot_flow";
  fs::remove_all(flow);
  fs::create_directories(flow);
  std::ofstream(flow / "validate_seed.csv") << csv;
  const std::string script = (fs::path(imcol::data_dir()).parent_path() / "scripts" / "plot_validate_seed.py").string();
  const int raw = std::system(("/usr/bin/python3 '" + script + "' '" + flow.string() + "' >/dev/null 2>&1").c_str());
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0);
  EXPECT_TRUE(fs::exists(flow / "validate_seed.png"));
  fs::remove_all(out);
  fs::remove_all(flow);
}

namespace {
/// Exit status 2 and one line `imcol: error: ...` holding every fragment.
void expect_refused(const Result& r, const std::string& label, std::initializer_list<std::string> fragments) {
  EXPECT_EQ(r.status, 2) << label << ": " << r.err;
  EXPECT_EQ(r.err.rfind("imcol: error: ", 0), 0u) << label << ": " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << label << ": " << r.err;
  for (const auto& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << label << ": '" << f << "' missing in: " << r.err;
}
}  // namespace

TEST(Cli, SweepExportDemWritesATableAndFitsConsistentWithSweepCsv) {
  const std::string scene = imcol::data_dir() + "/scenes/gg3462.toml";
  const fs::path out = fs::temp_directory_path() / "imcol_cli_sweep_dem";
  const Result r = sweep_gg3462(out, "--vary velocity --from 0.005 --to 1 --points 8 --jobs 2 --no-plot --export dem");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto sweep = read_csv(out / "sweep.csv");
  const auto dem = read_csv(out / "dem.csv");
  ASSERT_EQ(sweep.size(), 8u);
  ASSERT_EQ(dem.size(), 8u);
  std::ifstream head(out / "dem.csv");
  std::string first, second, third;
  std::getline(head, first), std::getline(head, second), std::getline(head, third);
  EXPECT_EQ(first.rfind("# imcol sweep --export dem", 0), 0u) << first;
  EXPECT_NE(second.find("scene: gg3462"), std::string::npos) << second;
  EXPECT_NE(third.find("fluid: density 1112 kg/m3, viscosity 0.004 Pa s"), std::string::npos) << third;
  // A pair: St is the summary's (Table 6.1), St_B_eq_6_2 twice it, the DEM convention; impact speed proportional to St.
  std::size_t with_e = 0, no_rebound = 0;
  double St_lo = INFINITY, St_hi = 0, St_per_U = 0;
  std::vector<std::pair<double, double>> used;  // (St eq. 6.2, e) of the points with e > 0
  for (std::size_t i = 0; i < dem.size(); ++i) {
    const auto &s = sweep[i], &d = dem[i];
    EXPECT_EQ(d.at("point"), s.at("point"));
    EXPECT_EQ(d.at("velocity_m_s"), s.at("velocity_m_s"));
    EXPECT_EQ(d.at("St"), s.at("St"));
    EXPECT_EQ(d.at("St_B_eq_6_2"), s.at("St_B_eq_6_2"));
    EXPECT_EQ(d.at("e"), s.at("e"));
    EXPECT_EQ(d.at("status"), s.at("status"));
    EXPECT_EQ(d.at("e_status"), s.at("e_status"));
    ASSERT_EQ(d.at("status"), "ok");
    const double St = std::stod(d.at("St_B_eq_6_2")), e = std::stod(d.at("e")), U = std::stod(d.at("impact_speed_m_s"));
    EXPECT_NEAR(St, 2 * std::stod(d.at("St")), 1e-9 * St);
    if (St_per_U == 0) St_per_U = St / U;
    EXPECT_NEAR(St / U, St_per_U, 1e-9 * St_per_U);
    EXPECT_NEAR(std::stod(d.at("e_over_e_dry")), e / 0.97, 1e-9);
    EXPECT_EQ(d.at("used_in_fit"), e > 0 ? "1" : "0");
    ++with_e;
    if (e == 0) {
      ++no_rebound;
      continue;
    }
    used.emplace_back(St, e);
    St_lo = std::min(St_lo, St), St_hi = std::max(St_hi, St);
  }
  ASSERT_GE(used.size(), 3u);
  ASSERT_GE(no_rebound, 1u);  // 5 mm/s: no rebound
  // The lookup table: every point with e, by St (eq. 6.2).
  const auto table = read_csv(out / "dem_table.csv");
  ASSERT_EQ(table.size(), with_e);
  for (std::size_t k = 1; k < table.size(); ++k) EXPECT_LT(std::stod(table[k - 1].at("St")), std::stod(table[k].at("St")));
  std::ifstream js(out / "dem.json");
  const auto j = nlohmann::json::parse(js);
  EXPECT_EQ(j["table"], "dem.csv");
  EXPECT_EQ(j["St_column"], "St_B_eq_6_2");
  EXPECT_EQ(j["points"]["used_in_fits"].get<std::size_t>(), used.size());
  EXPECT_EQ(j["points"]["no_rebound"].get<std::size_t>(), no_rebound);
  ASSERT_EQ(j["fits"].size(), 4u);  // exp and linear, e_dry fixed and fitted
  ASSERT_FALSE(j["best"].is_null());
  for (const auto& f : j["fits"]) {
    EXPECT_NEAR(f["valid_St"][0].get<double>(), St_lo, 1e-10 * St_lo);  // the CSV has 12 digits
    EXPECT_NEAR(f["valid_St"][1].get<double>(), St_hi, 1e-10 * St_hi);
    // The residual it reports is that of its curve against the table's e.
    const bool expo = f["form"] == "exp";
    const double St_c = f["St_c"], e_dry = f["e_dry"];
    double ss = 0, mx = 0;
    for (const auto& [St, e] : used) {
      const double m = e_dry * (expo ? std::exp(-St_c / St) : std::max(0.0, 1 - St_c / St));
      ss += (m - e) * (m - e), mx = std::max(mx, std::abs(m - e));
    }
    EXPECT_NEAR(f["rms_residual"].get<double>(), std::sqrt(ss / used.size()), 1e-6) << f["form"];
    EXPECT_NEAR(f["max_residual"].get<double>(), mx, 1e-6) << f["form"];
    if (f["e_dry_is"] != "fitted") {
      EXPECT_EQ(e_dry, 0.97);
    }
  }
  // LIGGGHTS's viscous rule fitted through the replay: its parameters, its residual against the same points, the
  // materials and step it used.
  const auto& lg = j["liggghts"];
  ASSERT_TRUE(lg.is_object());
  EXPECT_TRUE(lg["fit_error"].is_null()) << lg["fit_error"];
  for (const char* key : {"CriticalStokes", "MaximumRestitution", "FluidViscosity", "rms_residual", "max_residual", "max_residual_at_St",
                          "within_tolerance", "beyond_tolerance", "valid_St", "MaximumRestitution_fixed", "exp_formula_replayed", "points",
                          "contact", "stiffness", "table_replay"})
    EXPECT_TRUE(lg.contains(key)) << key;
  EXPECT_EQ(lg["FluidViscosity"].get<double>(), 0.004);
  EXPECT_GT(lg["MaximumRestitution"].get<double>(), 0);
  EXPECT_LE(lg["MaximumRestitution"].get<double>(), 1);
  EXPECT_EQ(lg["MaximumRestitution_fixed"]["MaximumRestitution"].get<double>(), 0.97);
  EXPECT_EQ(lg["within_tolerance"].get<bool>(), lg["max_residual"].get<double>() <= 0.03);
  double rss = 0, rmax = 0;
  std::size_t n_used = 0;
  for (const auto& p : lg["points"]) {
    if (!p["used_in_fit"].get<bool>()) continue;
    const double r = p["e_replay"].get<double>() - p["e"].get<double>();
    rss += r * r, rmax = std::max(rmax, std::abs(r)), ++n_used;
  }
  EXPECT_EQ(n_used, used.size());
  EXPECT_NEAR(lg["rms_residual"].get<double>(), std::sqrt(rss / n_used), 1e-12);
  EXPECT_NEAR(lg["max_residual"].get<double>(), rmax, 1e-12);
  EXPECT_GT(lg["contact"]["k_n_N_per_m"].get<double>(), 0);
  EXPECT_EQ(lg["contact"]["steps_per_contact"].get<int>(), 1000);
  EXPECT_EQ(lg["contact"]["youngsModulus_Pa"].size(), 2u);
  EXPECT_LT(lg["table_replay"]["max_difference_in_e"].get<double>(), 2e-3);
  for (const auto& k : lg["stiffness"]) {
    if (k["step"] == "the same steps per contact") {
      EXPECT_LT(k["max_change_in_e"].get<double>(), 1e-9) << k;
    }
  }

  // Failed points stay in the table with their status and no e; two points with e fit only with e_dry fixed.
  const Result f = sweep_gg3462(out, "--vary viscosity --from 0.01 --to 0.05 --points 4 --export dem --set solver.max_steps=70 "
                                     "--set 'effects=[\"drag\",\"lubrication\",\"added_mass\",\"elastic\"]'");
  EXPECT_EQ(f.status, 3) << f.err;
  // The plot draws the failed points (marked gaps) and the fits without failing.
  EXPECT_TRUE(fs::exists(out / "sweep.png"));
  EXPECT_EQ(f.err.find("plot"), std::string::npos) << f.err;
  const auto rows = read_csv(out / "dem.csv");
  ASSERT_EQ(rows.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(rows[i].at("status"), i < 2 ? "failed" : "ok");  // the two least viscous need more than 70 steps
    EXPECT_EQ(rows[i].at("e").empty(), i < 2);
    EXPECT_EQ(rows[i].at("used_in_fit"), i < 2 ? "0" : "1");
  }
  std::ifstream js2(out / "dem.json");
  const auto j2 = nlohmann::json::parse(js2);
  EXPECT_EQ(j2["points"]["without_e"].get<int>(), 2);
  ASSERT_EQ(j2["fits"].size(), 2u);
  for (const auto& fit : j2["fits"]) EXPECT_EQ(fit["e_dry_is"], "fixed to the scene's");
  EXPECT_NE(j2["fit_error"].get<std::string>().find("at least 3 points with e > 0"), std::string::npos) << j2["fit_error"];
  EXPECT_NE(j2["liggghts"]["fit_error"].get<std::string>().find("at least 3 points with e > 0"), std::string::npos) << j2["liggghts"];

  // --export takes dem only; a fit needs 3 points.
  const Result bad = run_imcol("sweep " + scene + " --vary velocity --from 0.05 --to 0.4 --points 4 --export vtk --out " + out.string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("--export"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("expected dem"), std::string::npos) << bad.err;
  const Result two = run_imcol("sweep " + scene + " --vary velocity --from 0.05 --to 0.4 --points 2 --export dem --out " + out.string());
  EXPECT_EQ(two.status, 2);
  EXPECT_NE(two.err.find("--points 3"), std::string::npos) << two.err;
}

TEST(Cli, NumericOptionsAreCheckedBeforeAnythingRuns) {
  const std::string scene = imcol::data_dir() + "/scenes/default.toml";
  const std::string out = " --out " + (fs::temp_directory_path() / "imcol_cli_opts").string();
  for (const char* v : {"abc", "nan", "-1", "2", "1e300"}) {
    expect_refused(run_imcol("bench " + scene + " --rtols " + v), std::string("--rtols ") + v, {"--rtols"});
    expect_refused(run_imcol("run " + scene + " --rtol " + v + out), std::string("--rtol ") + v, {"command line: key '--rtol'"});
  }
  // bench varies rtol itself: --rtol would be ignored, so it is refused even when valid.
  expect_refused(run_imcol("bench " + scene + " --rtol 1e-6"), "bench --rtol", {"--rtol", "--rtols"});
  expect_refused(run_imcol("run " + scene + " --atol 1e-300" + out), "--atol 1e-300", {"--atol", "1e-30"});
  expect_refused(run_imcol("sweep " + scene + " --vary velocity --from 0.1 --to 0.2 --points 2.5" + out), "--points 2.5", {"--points"});
  expect_refused(run_imcol("bench " + scene + " --repeat 1e3"), "--repeat 1e3", {"--repeat"});
  // The direct evaluator's step multiples: [0.1, 100] (a finer step costs quadratically more; 1e-15 missed grid points).
  for (const char* v : {"1e-15", "1e-6", "1e-300", "0.05", "1000"})
    expect_refused(run_imcol("work-precision " + scene + " --direct-steps 1," + std::string(v) + out), std::string("--direct-steps ") + v,
                   {"--direct-steps", "[0.1, 100]"});
}

TEST(Cli, ParseErrorsAreOneLineWithThePrefix) {
  const std::string scene = imcol::data_dir() + "/scenes/default.toml";
  expect_refused(run_imcol("run " + scene + " --frobnicate"), "unknown option", {"--frobnicate", "--help"});
  expect_refused(run_imcol("sweep " + scene + " --from 1"), "missing option", {"--vary"});
  expect_refused(run_imcol("run"), "missing scene", {"scene"});
  const Result help = run_imcol("run --help");
  EXPECT_EQ(help.status, 0) << help.err;
  EXPECT_EQ(run_imcol("--help").status, 0);
}

TEST(Cli, BadScenesAreNamedByTheKeyAtFault) {
  const std::string scene = imcol::data_dir() + "/scenes/default.toml";
  const std::string out = " --quiet --no-plot --out " + (fs::temp_directory_path() / "imcol_cli_keys").string();
  // A tiny nonzero speed (its square underflows in the Hertz contact time): the velocity, not the history, is named.
  expect_refused(run_imcol("run " + scene + " --set 'sphere[0].velocity=1e-300'" + out), "velocity 1e-300",
                 {"sphere[0].velocity", "1e-30"});
  // Tolerances below 1e-30 (the NaN weights they would give) and a stall fraction of that size.
  expect_refused(run_imcol("run " + scene + " --set solver.atol=1e-300" + out), "atol", {"solver.atol"});
  expect_refused(run_imcol("run " + scene + " --set solver.krylov_tol=1e-31" + out), "krylov_tol", {"solver.krylov_tol"});
  expect_refused(run_imcol("run " + scene + " --set measure.stall_fraction=1e-40" + out), "stall_fraction", {"measure.stall_fraction"});
  // A viscosity no liquid has, refused when the scene is read (it used to fail at t = 0 with exit status 3).
  expect_refused(run_imcol("run " + scene + " --set fluid.viscosity=1e29" + out), "viscosity", {"fluid.viscosity", "1e+12"});
  // A flow step longer than the run (it used to overflow the grid's cell count: "nr must be even").
  const std::string coupled = imcol::data_dir() + "/scenes/coupled/group_b.toml";
  expect_refused(run_imcol("run " + coupled + " --set flow.dt=1e29" + out), "flow.dt", {"flow.dt", "solver.t_end"});
  // With a long run such a step is allowed, and the start-up's travel (689 m in one step) is refused before the grid's
  // cell count is converted to an int.
  const Result far = run_imcol("run " + coupled + " --set flow.dt=1e4 --set solver.t_end=1e4 --set output.dt=1 --set measure.max_samples=1e9" + out);
  expect_refused(far, "far start-up", {"key 'flow.dt'", "689 m"});
  EXPECT_EQ(far.err.find("nr must be even"), std::string::npos) << far.err;
  // A flow scene's grid of more than 1e6 cells along an axis (it used to overflow to a grid that "missed" the sphere).
  std::ifstream fin(imcol::data_dir() + "/scenes/flow/fixed_sphere_re20.toml");
  std::string flow_text((std::istreambuf_iterator<char>(fin)), std::istreambuf_iterator<char>());
  const auto at = flow_text.find("\nr_max = ");
  ASSERT_NE(at, std::string::npos);
  flow_text.replace(at, flow_text.find('\n', at + 1) - at, "\nr_max = 1e10");
  const fs::path big = write_scene("flow_big_grid", flow_text);
  expect_refused(run_imcol("flow " + big.string() + " --no-plot --out " + (fs::temp_directory_path() / "imcol_cli_flow_big").string()), "flow r_max", {"grid.r_max", "1e6"});
  // One --set sets one key: a line break would smuggle in more.
  expect_refused(run_imcol("run " + scene + " --set \"$(printf 'solver.rtol=1e-8\\nsolver.bogus=1')\"" + out), "newline", {"--set", "line break"});
}

TEST(Cli, AFileSizeLimitIsAnIoErrorNotASignal) {
  const fs::path dir = fs::temp_directory_path() / ("imcol_cli_fsize_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const fs::path errf = dir.string() + ".err";
  const std::string cmd = "bash -c 'ulimit -f 1; exec " + std::string(IMCOL_BINARY) + " run " + imcol::data_dir() +
                          "/scenes/default.toml --quiet --no-plot --out " + dir.string() + "' >/dev/null 2>" + errf.string();
  const int raw = std::system(cmd.c_str());
  std::ifstream in(errf);
  const std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  fs::remove(errf);
  fs::remove_all(dir);
  ASSERT_TRUE(WIFEXITED(raw)) << "ended by a signal: " << err;
  EXPECT_EQ(WEXITSTATUS(raw), 1) << err;
  EXPECT_EQ(err.rfind("imcol: error: ", 0), 0u) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

namespace {
/// laws.json of a finished `imcol laws` run.
nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}
}  // namespace

TEST(Cli, LawsRunsEveryShippedLawAndWritesOneRowEach) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_laws";
  fs::remove_all(out);
  const std::string scene = imcol::data_dir() + "/scenes/default.toml";
  const Result r = run_imcol("laws " + scene + " --out " + out.string() + " --rtol 1e-6 --no-plot");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = read_csv(out / "laws.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("law"), "ramp");
  EXPECT_EQ(rows[1].at("law"), "hertz");
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "ran") << row.at("law") << ": " << row.at("message");
    const double e = std::stod(row.at("e"));
    EXPECT_TRUE(std::isfinite(e) && e > 0 && e < 1) << row.at("law") << ": " << e;
    EXPECT_GT(std::stod(row.at("contact_time_s")), 0) << row.at("law");
    EXPECT_GT(std::stod(row.at("max_contact_force_N")), 0) << row.at("law");
    EXPECT_GT(std::stod(row.at("max_overlap_m")), 0) << row.at("law");
    EXPECT_FALSE(row.at("law_W_o_N").empty()) << row.at("law");  // both laws report the Hertz peak force at impact
  }
  EXPECT_FALSE(rows[1].at("law_alpha").empty());  // hertz's own numbers
  EXPECT_TRUE(rows[0].at("law_alpha").empty());
  EXPECT_NEAR(std::stod(rows[1].at("e_minus_e_ramp")), std::stod(rows[1].at("e")) - std::stod(rows[0].at("e")), 1e-9);
  const auto j = read_json(out / "laws.json");
  ASSERT_EQ(j["laws"].size(), 2u);
  for (const auto& row : j["laws"]) {
    EXPECT_TRUE(row["e"].is_number()) << row.dump();
    EXPECT_TRUE(row["e_measures"].contains("contact_ends")) << row.dump();
    EXPECT_EQ(row["model"]["contact.law"], row["law"]) << row.dump();
  }
  EXPECT_TRUE(j["run"].contains("id")) << j.dump();
  EXPECT_TRUE(fs::exists(out / "laws_traces.csv"));
  EXPECT_FALSE(fs::exists(out / "laws.png"));  // --no-plot
  // --laws chooses (and a law named twice runs once).
  const Result one = run_imcol("laws " + scene + " --out " + out.string() + " --rtol 1e-6 --no-plot --laws hertz,hertz");
  ASSERT_EQ(one.status, 0) << one.err;
  const auto hertz_only = read_csv(out / "laws.csv");
  ASSERT_EQ(hertz_only.size(), 1u);
  EXPECT_EQ(hertz_only[0].at("law"), "hertz");
  EXPECT_TRUE(hertz_only[0].at("e_minus_e_ramp").empty());  // no ramp row to compare with
}

TEST(Cli, LawsGiveEDryOnADryCollision) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_laws_dry";
  fs::remove_all(out);
  const Result r = run_imcol("laws " + imcol::data_dir() + "/scenes/dry_steel_steel.toml --rtol 1e-8 --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "laws.png"));  // U_rel and the gap near contact, per law
  const auto j = read_json(out / "laws.json");
  ASSERT_EQ(j["laws"].size(), 2u);
  const double e_dry = j["e_dry"].get<double>();
  EXPECT_DOUBLE_EQ(e_dry, 0.97);
  // Both laws are built to return e_dry without a fluid (measured: within 7e-7 at rtol 1e-8).
  for (const auto& row : j["laws"]) EXPECT_NEAR(row["e"].get<double>(), e_dry, 1e-5) << row["law"];
}

TEST(Cli, LawsGiveARefusedLawItsReasonAndStillRunTheOthers) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_laws_refused";
  fs::remove_all(out);
  const std::string scene = imcol::data_dir() + "/scenes/dry_steel_steel.toml";
  // Tsuji's damping reaches e_dry down to about 3e-3: hertz refuses e_dry = 1e-3, the ramp runs.
  const Result r = run_imcol("laws " + scene + " --set contact.e_dry=0.001 --rtol 1e-6 --no-plot --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = read_csv(out / "laws.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("status"), "ran");
  EXPECT_EQ(rows[1].at("status"), "refused");
  EXPECT_NE(rows[1].at("message").find("contact.e_dry"), std::string::npos) << rows[1].at("message");
  EXPECT_TRUE(rows[1].at("e").empty());
  const auto j = read_json(out / "laws.json");
  EXPECT_EQ(j["laws"][1]["status"], "refused");
  EXPECT_NE(j["laws"][1]["message"].get<std::string>().find("contact.e_dry"), std::string::npos);
  // The ramp refuses a start inside its zone that it cannot store (a fast approach 2 um from contact); hertz runs.
  const Result inside = run_imcol("laws " + imcol::data_dir() + "/scenes/hard/start_inside_contact_zone.toml --no-plot --out " +
                                  out.string() + " --set sphere[0].position=-0.006352 --set sphere[0].velocity=1.0");
  ASSERT_EQ(inside.status, 0) << inside.err;
  const auto rows2 = read_csv(out / "laws.csv");
  ASSERT_EQ(rows2.size(), 2u);
  EXPECT_EQ(rows2[0].at("status"), "refused");
  EXPECT_NE(rows2[0].at("message").find("sphere[0].position"), std::string::npos) << rows2[0].at("message");
  EXPECT_EQ(rows2[1].at("status"), "ran") << rows2[1].at("message");
  // No law runs: exit 2, one line with the reason.
  expect_refused(run_imcol("laws " + scene + " --laws hertz --set contact.e_dry=0.001 --no-plot --out " + out.string()), "every law refused",
                 {"contact.e_dry", "hertz", "no contact law ran"});
}

TEST(Cli, LawsAcrossASweepGiveARowPerPointAndLaw) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_laws_sweep";
  fs::remove_all(out);
  const Result r = run_imcol("laws " + imcol::data_dir() + "/scenes/gg3462.toml --vary velocity --from 0.05 --to 0.5 --points 2 --rtol 1e-6 --out " +
                             out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = read_csv(out / "laws.csv");
  ASSERT_EQ(rows.size(), 4u);
  const std::vector<std::pair<std::string, std::string>> expected = {{"0", "ramp"}, {"0", "hertz"}, {"1", "ramp"}, {"1", "hertz"}};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].at("point"), expected[i].first);
    EXPECT_EQ(rows[i].at("law"), expected[i].second);
    EXPECT_EQ(rows[i].at("status"), "ran") << rows[i].at("message");
    EXPECT_TRUE(std::isfinite(std::stod(rows[i].at("e"))));
  }
  EXPECT_DOUBLE_EQ(std::stod(rows[0].at("velocity_m_s")), 0.05);
  EXPECT_DOUBLE_EQ(std::stod(rows[3].at("velocity_m_s")), 0.5);
  // The same St for both laws at a point (the approach is the same until the gap reaches delta_SS), a larger St at the faster one.
  EXPECT_EQ(rows[0].at("St"), rows[1].at("St"));
  EXPECT_GT(std::stod(rows[2].at("St")), std::stod(rows[0].at("St")));
  const auto j = read_json(out / "laws.json");
  EXPECT_EQ(j["vary"], "velocity");
  EXPECT_EQ(j["laws"].size(), 4u);
  EXPECT_TRUE(fs::exists(out / "laws.png"));
}

TEST(Cli, LawsRefuseBadOptionsWithOneLine) {
  const std::string scene = imcol::data_dir() + "/scenes/default.toml";
  const std::string out = " --out " + (fs::temp_directory_path() / "imcol_cli_laws_bad").string();
  expect_refused(run_imcol("laws " + scene + " --laws ramp,spring" + out), "--laws spring", {"--laws", "spring", "hertz"});
  expect_refused(run_imcol("laws " + scene + " --rtol 2" + out), "--rtol 2", {"--rtol"});
  expect_refused(run_imcol("laws " + scene + " --set contact.bogus=1" + out), "--set bogus", {"contact.bogus"});
  expect_refused(run_imcol("laws" + out), "no scene", {"scene"});
  // A sweep needs its range, and a range needs --vary.
  expect_refused(run_imcol("laws " + scene + " --from 0.1" + out), "--from alone", {"--from", "--vary"});
  expect_refused(run_imcol("laws " + scene + " --vary velocity --from 0.1 --to 0.2" + out), "--vary without --points", {"--vary", "--points"});
  expect_refused(run_imcol("laws " + scene + " --vary velocity --from 0.1 --to 0.1 --points 3" + out), "empty range", {"--to", "--from"});
  // A free sphere has no contact to compare.
  expect_refused(run_imcol("laws " + imcol::data_dir() + "/scenes/rising_sphere.toml" + out), "free sphere", {"no contact law"});
}

TEST(Cli, HistoryTablePeakIsThePlottedPeakAndResolvesTheContact) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_history_peak", fine = fs::temp_directory_path() / "imcol_cli_history_fine";
  const std::string scene = imcol::data_dir() + "/scenes/default.toml";
  ASSERT_EQ(run_imcol("history " + scene + " --kernels basset --evaluators soe-step --no-plot --out " + out.string()).status, 0);
  // The reference: the run's own rows every microsecond (a hundredth of output.dt).
  ASSERT_EQ(run_imcol("run " + scene + " --no-plot --quiet --set output.dt=1e-6 --out " + fine.string()).status, 0);
  double fine_peak = 0;
  for (const auto& row : read_csv(fine / "trajectory.csv")) fine_peak = std::max(fine_peak, std::abs(std::stod(row.at("f_hist1"))));
  double plotted = 0;
  for (const auto& row : read_csv(out / "history_forces.csv"))
    if (row.at("kernel") == "basset") plotted = std::max(plotted, std::abs(std::stod(row.at("f_hist1"))));
  double table = NAN;
  for (const auto& row : read_csv(out / "history.csv"))
    if (row.at("kernel") == "basset") table = std::stod(row.at("peak_history_force_N"));
  EXPECT_NEAR(table, plotted, 1e-9 * plotted);  // the same samples
  EXPECT_NEAR(plotted, fine_peak, 0.01 * fine_peak) << "the samples near contact miss the peak";
}

TEST(Cli, HistorySweepGivesEPerKernelAsSeparateRunsDo) {
  const fs::path out = fs::temp_directory_path() / "imcol_cli_history_sweep";
  const fs::path one = fs::temp_directory_path() / "imcol_cli_history_sweep_one";
  fs::remove_all(out);
  const std::string scene = imcol::data_dir() + "/scenes/default.toml";
  // From the scene's own speed upwards, so that the points keep its t_end (as a separate run does).
  const Result r = run_imcol("history " + scene + " --vary velocity --from 0.3 --to 0.6 --points 3 --kernels basset,kim --jobs 2 --out " +
                             out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* f : {"history_sweep.csv", "history_sweep.json", "history_sweep.png"}) EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto rows = read_csv(out / "history_sweep.csv");
  ASSERT_EQ(rows.size(), 9u);  // 3 points × (none, basset, kim)
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "ok") << row.at("message");
    EXPECT_GT(std::stod(row.at("St")), 0);
    if (row.at("kernel") == "none") continue;
    EXPECT_EQ(row.at("evaluator"), "soe-step");  // the scene's evaluator
    const Result single = run_imcol("run " + scene + " --no-plot --quiet --out " + one.string() + " --set sphere[0].velocity=" +
                                    row.at("velocity_m_s") + " --set 'history.kernel=\"" + row.at("kernel") + "\"'");
    ASSERT_EQ(single.status, 0) << single.err;
    const double e = read_json(one / "summary.json")["e"].get<double>();
    EXPECT_NEAR(std::stod(row.at("e")), e, 5e-7) << row.at("kernel") << " at " << row.at("velocity_m_s");  // the printed digits
  }
  // A kernel changes e: the three series differ at every point.
  EXPECT_NE(rows[0].at("e"), rows[1].at("e"));
  EXPECT_NE(rows[1].at("e"), rows[2].at("e"));
  const auto j = read_json(out / "history_sweep.json");
  EXPECT_EQ(j["vary"], "velocity");
  EXPECT_EQ(j["series"].size(), 3u);
  EXPECT_EQ(j["failures"].size(), 0u);
}

TEST(Cli, HistorySweepRefusesBadOptionsWithOneLine) {
  const std::string scene = imcol::data_dir() + "/scenes/default.toml";
  const std::string out = " --out " + (fs::temp_directory_path() / "imcol_cli_history_bad").string();
  expect_refused(run_imcol("history " + scene + " --from 0.1" + out), "--from alone", {"--from", "--vary"});
  expect_refused(run_imcol("history " + scene + " --jobs 2" + out), "--jobs alone", {"--jobs", "--vary"});
  expect_refused(run_imcol("history " + scene + " --vary velocity --from 0.1 --to 0.2" + out), "--vary without --points", {"--vary", "--points"});
  expect_refused(run_imcol("history " + scene + " --vary speed --from 0.1 --to 0.2 --points 2" + out), "--vary speed", {"--vary", "speed"});
  expect_refused(run_imcol("history " + scene + " --vary velocity --from 0.1 --to 0.1 --points 3" + out), "empty range", {"--to", "--from"});
  expect_refused(run_imcol("history " + scene + " --vary velocity --from 0.1 --to 0.2 --points 2 --kernels oseen" + out), "--kernels oseen",
                 {"--kernels", "oseen"});
  expect_refused(run_imcol("history " + imcol::data_dir() + "/scenes/rising_sphere.toml --vary velocity --from 0.1 --to 0.2 --points 2" + out),
                 "free sphere", {"no collision"});
}
