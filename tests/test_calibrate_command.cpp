// SPDX-License-Identifier: BSD-3-Clause
// `imcol calibrate` through the program: each bad input exits 2 with one line naming its place (FILE:LINE of the
// measurement, or the option), before anything runs; a run writes its four files and calibration.json's best is
// the best row of calibration.csv; the plot script draws calibration.png.
#include <gtest/gtest.h>

#include <unistd.h>

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/materials.hpp"
#include "tests/imcol_process.hpp"

namespace fs = std::filesystem;

namespace {

using imcol::test::slurp;
using Result = imcol::test::Outcome;

fs::path scratch(std::string name) {
  std::replace(name.begin(), name.end(), ' ', '_');
  return fs::temp_directory_path() / ("imcol_calcmd_" + std::to_string(::getpid()) + "_" + name);
}

Result run_imcol(const std::string& args) { return imcol::test::run_imcol(args, scratch("run")); }

/// imcol ARGS killed after 60 s (exit status 137): a command that waits for ever fails the test instead of hanging it.
Result run_bounded(const std::string& args) {
  const fs::path o = scratch("bounded.stdout"), e = scratch("bounded.stderr");
  const int raw = std::system(("timeout -s KILL 60 " + std::string(IMCOL_BINARY) + " " + args + " >" + o.string() + " 2>" + e.string()).c_str());
  Result r{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(o), slurp(e)};
  fs::remove(o);
  fs::remove(e);
  return r;
}

std::string measurement(const std::string& name) { return imcol::data_dir() + "/measurements/" + name; }

/// A measurement file in the scratch folder, removed when the test ends.
struct DataFile {
  fs::path path;
  DataFile(const std::string& name, const std::string& text) : path(scratch(name)) { std::ofstream(path) << text; }
  ~DataFile() { fs::remove(path); }
  DataFile(const DataFile&) = delete;
  DataFile& operator=(const DataFile&) = delete;
  std::string string() const { return path.string(); }
};

const std::string kFit = " --fit contact.delta_ss=0.005:0.05";

/// imcol calibrate gg3462 with `args`; expects exit 2 and one line naming `place` (and `more`, if given).
void expect_refused(const std::string& what, const std::string& args, const std::string& place, const std::string& more = "") {
  const fs::path out = scratch("out_" + what);
  const Result r = run_imcol("calibrate gg3462 --no-plot --no-progress --out " + out.string() + " " + args);
  EXPECT_EQ(r.status, 2) << what << ": " << r.err;
  EXPECT_NE(r.err.find(place), std::string::npos) << what << ": expected '" << place << "' in: " << r.err;
  if (!more.empty()) {
    EXPECT_NE(r.err.find(more), std::string::npos) << what << ": expected '" << more << "' in: " << r.err;
  }
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << ": " << r.err;
  EXPECT_TRUE(r.out.empty()) << what << ": nothing runs before the inputs are checked: " << r.out;
  EXPECT_FALSE(fs::exists(out)) << what << ": no output folder";
}

std::vector<std::map<std::string, std::string>> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> head;
  for (std::stringstream h(line); std::getline(h, line, ',');) head.push_back(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::map<std::string, std::string> row;
    std::stringstream c(line);
    for (const auto& name : head) {
      std::string cell;
      std::getline(c, cell, ',');
      row[name] = cell;
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST(CalibrateCommand, BadMeasurementsNameTheirFileAndLine) {
  // Times not increasing: line 4 (after the header and two rows) goes back.
  const DataFile unsorted("unsorted.csv", "t,z1,z2\n0.000,0,0.016\n0.001,0.0001,0.016\n0.0005,0.0002,0.016\n0.002,0.0003,0.016\n"
                                                   "0.003,0.0004,0.016\n0.004,0.0005,0.016\n");
  expect_refused("unsorted", "--data " + unsorted.string() + kFit, unsorted.string() + ":4");
  const DataFile nan("nan.csv", "t,z1,z2\n0.000,0,0.016\n0.001,nan,0.016\n0.002,0.0002,0.016\n0.003,0.0003,0.016\n0.004,0.0004,0.016\n");
  expect_refused("nan", "--data " + nan.string() + kFit, nan.string() + ":3");
  const DataFile few("few.csv", "t,z1,z2\n0.000,0,0.016\n0.001,0.0001,0.016\n");
  expect_refused("too few rows", "--data " + few.string() + kFit, few.string());
  const auto missing = scratch("no_such_file.csv");
  expect_refused("missing file", "--data " + missing.string() + kFit, missing.string());
}

TEST(CalibrateCommand, BadParametersNameTheOption) {
  const std::string data = " --data " + measurement("gg3462_trajectory.csv");
  expect_refused("not numeric", data + " --fit contact.law=0:1", "command line: key '--fit'", "contact.law");
  expect_refused("reversed bounds", data + " --fit contact.delta_ss=0.05:0.005", "command line: key '--fit'", "contact.delta_ss");
  expect_refused("unknown key", data + " --fit contact.delta_sss=0.005:0.05", "command line: key '--fit'", "contact.delta_sss");
  expect_refused("not a number", data + " --fit contact.delta_ss=a:0.05", "command line: key '--fit'");
  expect_refused("log of zero", data + " --fit contact.delta_ss=0:0.05:log", "command line: key '--fit'");
  expect_refused("given twice", data + kFit + kFit, "command line: key '--fit'", "twice");
  expect_refused("no --fit", data, "--fit");
}

TEST(CalibrateCommand, BadOptionsNameTheOption) {
  const std::string data = " --data " + measurement("gg3462_trajectory.csv") + kFit;
  // 0.2 ms around the contact holds no sample 0.5 ms apart.
  expect_refused("window too short", data + " --window -0.0001:0.0001", "command line: key '--window'");
  expect_refused("window reversed", data + " --window 0.01:-0.01", "command line: key '--window'");
  expect_refused("window not numbers", data + " --window a:b", "command line: key '--window'");
  expect_refused("offset negative", data + " --offset-max -1", "command line: key '--offset-max'");
  expect_refused("factor below 1", data + " --factor 0.5", "command line: key '--factor'");
  expect_refused("factor and confidence", data + " --factor 1.01 --confidence 0.9", "command line: key '--confidence'", "--factor");
  expect_refused("confidence 0", data + " --confidence 0", "command line: key '--confidence'");
  expect_refused("confidence 1", data + " --confidence 1", "command line: key '--confidence'");
  expect_refused("confidence above 1", data + " --confidence 95", "command line: key '--confidence'");
  expect_refused("refine negative", data + " --refine -1", "command line: key '--refine'");
  expect_refused("refine-to 0", data + " --refine-to 0", "command line: key '--refine-to'");
  expect_refused("refine-to 1", data + " --refine-to 1", "command line: key '--refine-to'");
  expect_refused("one profile point", data + " --profile-points 1", "command line: key '--profile-points'");
  const DataFile table("table.csv", "sphere[0].velocity,e\n0.1,0.5\n0.2,0.6\n0.3,0.7\n");
  expect_refused("validation of the other kind", data + " --validate " + table.string(), "command line: key '--validate'", table.string());
  expect_refused("window on a table", " --data " + table.string() + kFit + " --window -0.01:0.01", "command line: key '--window'");
  const DataFile bad_key("badkey.csv", "sphere[0].speed,e\n0.1,0.5\n0.2,0.6\n");
  expect_refused("table key unknown", " --data " + bad_key.string() + kFit, bad_key.string() + ":2", "sphere[0].speed");
  expect_refused("fitted key is a column", " --data " + table.string() + " --fit 'sphere[0].velocity=0.05:0.5'", "command line: key '--fit'");
  // Two rows for two parameters: no residual left to estimate the noise of the default (confidence) interval.
  const DataFile two_rows("two_rows.csv", "sphere[0].velocity,e\n0.1,0.5\n0.2,0.6\n");
  expect_refused("too few residuals", " --data " + two_rows.string() + kFit + " --fit contact.e_dry=0.8:1", two_rows.string(), "2 residuals");
  // A trajectory: 5 samples of one column for 4 parameters and the time offset.
  const DataFile five("five.csv", "t,z1\n0,0\n0.001,1e-4\n0.002,2e-4\n0.003,3e-4\n0.004,4e-4\n");
  // --cache: its folder missing, a folder, a file that is not a cache (left as it was).
  expect_refused("cache folder missing", data + " --cache /nonexistent_imcol_folder/x.cache", "command line: key '--cache'", "does not exist");
  expect_refused("cache a folder", data + " --cache " + fs::temp_directory_path().string(),
                 fs::temp_directory_path().string() + ": key '--cache': is a directory, not a cache file");
  expect_refused("cache not a cache", data + " --cache " + table.string(), table.string() + ":1: key '--cache'", "not an imcol calibrate cache");
  EXPECT_EQ(slurp(table.path), "sphere[0].velocity,e\n0.1,0.5\n0.2,0.6\n0.3,0.7\n");
  expect_refused("too few residuals trajectory", " --data " + five.string() + kFit + " --fit contact.e_dry=0.8:1 --fit fluid.viscosity=1e-3:1e-2"
                 " --fit fluid.density=900:1100 --window -0.01:0.01", five.string(), "5 residuals");
}

TEST(CalibrateCommand, FilesThatAreNotRegularAreRefusedAtOnce) {
  // /dev/zero never ends (read whole, it took 45 s and 16.8 GB before "no header line"); a FIFO without a writer
  // blocks its reader for ever; /dev/null reads as an empty cache. Each is refused before it is opened: with
  // `timeout` around the command, a reader that waits is killed (exit status 137) instead of hanging the test.
  const fs::path fifo = scratch("fifo");
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string fit = " --data " + measurement("gg3462_trajectory.csv") + kFit;
  const std::pair<std::string, std::string> cases[] = {
      {" --data /dev/zero" + kFit, "/dev/zero: is not a regular file (a measurement is a CSV text file)"},
      {" --data " + fifo.string() + kFit, fifo.string() + ": is not a regular file (a measurement is a CSV text file)"},
      {" --data " + fs::temp_directory_path().string() + kFit, fs::temp_directory_path().string() + ": is a directory, not a measurement file"},
      {fit + " --validate /dev/zero", "/dev/zero: is not a regular file (a measurement is a CSV text file)"},
      {fit + " --cache /dev/null", "/dev/null: key '--cache': is not a regular file (a cache is a text file)"},
      {fit + " --cache " + fifo.string(), fifo.string() + ": key '--cache': is not a regular file"},
  };
  for (const auto& [args, message] : cases) {
    const fs::path out = scratch("out_not_regular");
    const auto t0 = std::chrono::steady_clock::now();
    const Result r = run_bounded("calibrate gg3462 --no-plot --no-progress --out " + out.string() + args);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("imcol: error: " + message, 0), 0u) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_LT(seconds, 20.0) << args;  // the start-up and the scene's checks: well under a second unloaded
    EXPECT_FALSE(fs::exists(out));
  }
  fs::remove(fifo);
}

TEST(CalibrateCommand, MisleadingInputsAreNamedPlainly) {
  const std::string data = " --data " + measurement("gg3462_trajectory.csv");
  expect_refused("integer key", data + " --fit solver.max_steps=1000:100000", "command line: key '--fit'",
                 "parameter 'solver.max_steps': integer keys cannot be fitted");
  const DataFile huge("huge_z.csv", "t,z1\n0,0\n0.001,1e308\n0.002,2e-4\n0.003,3e-4\n0.004,4e-4\n");
  expect_refused("z out of range", " --data " + huge.string() + kFit, huge.string() + ":3: key 'z1'", "out of range");
}

// Runs that never reach their target have no e: every evaluation fails with sweep's reason (never e = 0), the command
// exits 3, and calibration.json's best has no objective.
TEST(CalibrateCommand, RunsWithoutACollisionFailTheirEvaluations) {
  const fs::path out = scratch("out_no_collision");
  fs::remove_all(out);
  const DataFile table("e_short.csv", "sphere[0].velocity,e\n0.08,0.8450\n0.11,0.8723\n0.16,0.8964\n");
  const Result r = run_imcol("calibrate gg3462 --data " + table.string() + " --fit solver.t_end=1e-6:1e-5 --scan 2 --starts 1"
                             " --max-evals 3 --profile-points 0 --no-plot --no-progress --jobs 2 --out " + out.string());
  EXPECT_EQ(r.status, 3) << r.err << r.out;
  EXPECT_NE(r.err.find("no evaluation succeeded"), std::string::npos) << r.err;
  const auto rows = read_csv(out / "calibration.csv");
  ASSERT_FALSE(rows.empty());
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "failed");
    EXPECT_TRUE(row.at("objective").empty());
    EXPECT_EQ(row.at("message").rfind(table.string() + ":2: e not measured: no collision by t_end", 0), 0u) << row.at("message");
  }
  const auto j = nlohmann::json::parse(slurp(out / "calibration.json"));
  EXPECT_FALSE(j["best"]["ok"].get<bool>());
  EXPECT_TRUE(j["best"]["objective"].is_null()) << j["best"];
  EXPECT_TRUE(j["best"]["rms"].is_null()) << j["best"];
  EXPECT_EQ(j["evaluations"]["failed"], j["evaluations"]["count"]);
  const auto best = read_csv(out / "best.csv");
  ASSERT_EQ(best.size(), 3u);
  EXPECT_TRUE(best[0].at("e_sim").empty());
  fs::remove_all(out);
}

TEST(CalibrateCommand, WritesItsFilesAndTheBestIsTheBestRow) {
  const fs::path out = scratch("out_ok");
  fs::remove_all(out);
  const Result r = run_imcol("calibrate gg3462 --data " + measurement("gg3462_trajectory.csv") + kFit +
                             " --set contact.delta_ss=0.006 --scan 6 --starts 1 --max-evals 12 --profile-points 5 --jobs 2 --no-progress"
                             " --validate " + measurement("gg3462_trajectory_repeat.csv") + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  for (const char* f : {"calibration.json", "calibration.csv", "measured.csv", "best.csv", "calibration.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_TRUE(r.err.empty()) << r.err;  // the plot script ran without a warning
  EXPECT_EQ(slurp(out / "measured.csv"), slurp(measurement("gg3462_trajectory.csv")));
  const auto j = nlohmann::json::parse(slurp(out / "calibration.json"));
  const auto rows = read_csv(out / "calibration.csv");
  ASSERT_EQ(rows.size(), j["evaluations"]["count"].get<std::size_t>());
  // The best row: the smallest objective among those that ran.
  const auto* best = &rows.front();
  for (const auto& row : rows)
    if (row.at("status") == "ok" && (best->at("status") != "ok" || std::stod(row.at("objective")) < std::stod(best->at("objective")))) best = &row;
  const double v = j["best"]["values"]["contact.delta_ss"].get<double>();
  EXPECT_EQ(std::stod(best->at("contact.delta_ss")), v);  // 17 digits: the same double
  EXPECT_NEAR(std::stod(best->at("objective")), j["best"]["objective"].get<double>(), 1e-11 * j["best"]["objective"].get<double>());
  // Started at 0.006, the fit finds the value the measurement was made with (0.024, noise 2 um): within 0.004, about
  // a third of this recording's 95 % interval (0.0154 to 0.0284, docs/calibration.md).
  EXPECT_NEAR(v, 0.024, 0.004);
  // The interval's rule: 95 % confidence, n the window's samples x 2 columns, p = delta_ss and the time offset.
  const auto& rule = j["profiles"][0]["factor_rule"];
  EXPECT_EQ(rule["kind"], "confidence");
  EXPECT_EQ(rule["confidence"].get<double>(), 0.95);
  EXPECT_NEAR(rule["q"].get<double>(), 3.841459, 1e-6);
  EXPECT_EQ(rule["n"].get<std::size_t>(), 2 * j["measurement"]["window"]["samples"].get<std::size_t>());
  EXPECT_EQ(rule["p"].get<int>(), 2);
  EXPECT_NEAR(j["profiles"][0]["factor"].get<double>(), 1 + 3.841459 / (rule["n"].get<double>() - 2), 1e-9);
  EXPECT_GT(j["evaluations"]["by_stage"].value("edge", 0), 0);
  EXPECT_EQ(j["parameters"][0]["start"].get<double>(), 0.006);
  EXPECT_EQ(j["measurement"]["kind"], "trajectory");
  EXPECT_EQ(j["profiles"].size(), 1u);
  EXPECT_TRUE(j["validation"]["ok"].get<bool>());
  EXPECT_TRUE(j["validation"]["tau_refitted"].get<bool>());
  // best.csv: the fitted run on the measurement's clock.
  const auto fitted = read_csv(out / "best.csv");
  ASSERT_GT(fitted.size(), 10u);
  EXPECT_NEAR(std::stod(fitted.front().at("t")), j["best"]["tau_s"].get<double>(), 1e-9);
  EXPECT_NE(r.out.find("contact.delta_ss = "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("validation on"), std::string::npos) << r.out;
  fs::remove_all(out);
}

TEST(CalibrateCommand, FitsAnETableAndValidatesItRowByRow) {
  const fs::path out = scratch("out_table");
  fs::remove_all(out);
  // e of gg3462 (delta_ss = 0.024) at five speeds, by imcol run gg3462 --set sphere[0].velocity=V (4 digits; yang_hunt_2006).
  const DataFile fit("e_fit.csv", "# gg3462, delta_ss = 0.024\nsphere[0].velocity,e\n0.08,0.8096\n0.11,0.8336\n0.16,0.8540\n");
  const DataFile held("e_held.csv", "sphere[0].velocity,e\n0.095,0.8234\n0.135,0.8456\n");
  const Result r = run_imcol("calibrate gg3462 --data " + fit.string() + kFit + " --scan 4 --starts 1 --max-evals 10 --profile-points 0"
                             " --no-progress --jobs 2 --validate " + held.string() + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  EXPECT_TRUE(fs::exists(out / "calibration.png"));  // the plot of a table without profiles
  EXPECT_TRUE(r.err.empty()) << r.err;
  const auto j = nlohmann::json::parse(slurp(out / "calibration.json"));
  EXPECT_EQ(j["measurement"]["kind"], "table");
  ASSERT_EQ(j["validation"]["by_row"].size(), 2u);
  EXPECT_EQ(j["validation"]["by_row"][0]["e_meas"].get<double>(), 0.8234);
  // Fitted on three speeds, the held-out two agree within 0.005 (4-digit data, delta_ss found to a few per cent).
  for (const auto& row : j["validation"]["by_row"]) EXPECT_NEAR(row["e_sim"].get<double>(), row["e_meas"].get<double>(), 0.005) << row;
  EXPECT_TRUE(j["validation"]["by_row"][0]["e_sim"].is_number());
  const auto best = read_csv(out / "best.csv");
  ASSERT_EQ(best.size(), 3u);
  EXPECT_EQ(best[1].at("e_meas"), "0.8336");
  EXPECT_FALSE(best[1].at("e_sim").empty());
  fs::remove_all(out);
}

// --cache: a second run takes every evaluation from the file and writes the same calibration.csv; a run killed
// part-way (its file cut inside a line) is resumed, running only what the file lost; another scene setting is refused.
TEST(CalibrateCommand, ACacheReplaysTheSearchAndResumesAKilledOne) {
  const fs::path cache = scratch("evaluations.cache");
  fs::remove(cache);
  const std::string args = "calibrate gg3462 --data " + measurement("gg3462_trajectory.csv") + kFit +
                           " --scan 4 --starts 1 --max-evals 10 --profile-points 5 --refine 3 --jobs 2 --no-plot --no-progress"
                           " --cache " + cache.string() + " --out ";
  auto calibrate_into = [&](const std::string& name, const std::string& more = "") {
    const fs::path out = scratch(name);
    fs::remove_all(out);
    const Result r = run_imcol(args + out.string() + more);
    EXPECT_EQ(r.status, 0) << name << ": " << r.err << r.out;
    auto j = nlohmann::json::parse(slurp(out / "calibration.json"));
    auto rows = read_csv(out / "calibration.csv");
    for (auto& row : rows) row.erase("wall_ms");
    fs::remove_all(out);
    return std::make_pair(j, rows);
  };
  const auto [first, first_rows] = calibrate_into("cache_first");
  const std::size_t count = first["evaluations"]["count"].get<std::size_t>();
  EXPECT_EQ(first["cache"]["held"], 0);
  EXPECT_EQ(first["cache"]["reused"], 0);
  const std::size_t added = first["cache"]["added"].get<std::size_t>();
  EXPECT_GT(added, count / 2);
  EXPECT_LE(added, count);  // a point the search meets twice is run twice, and written once

  const auto [again, again_rows] = calibrate_into("cache_again");
  EXPECT_EQ(again["cache"]["held"].get<std::size_t>(), added);
  EXPECT_EQ(again["cache"]["reused"].get<std::size_t>(), count);
  EXPECT_EQ(again["cache"]["added"], 0);
  EXPECT_EQ(again_rows, first_rows);
  EXPECT_EQ(again["best"], first["best"]);

  // A kill: the header, the first half of the items, and half of the next item's line.
  std::vector<std::string> lines;
  {
    std::istringstream in(slurp(cache));
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  ASSERT_GE(lines.size(), 4u);
  const std::size_t kept = lines.size() / 2;
  {
    std::ofstream out(cache, std::ios::trunc);
    for (std::size_t k = 0; k < kept; ++k) out << lines[k] << '\n';
    out << lines[kept].substr(0, lines[kept].size() / 2);
  }
  const auto [resumed, resumed_rows] = calibrate_into("cache_resumed");
  const std::size_t held = resumed["cache"]["held"].get<std::size_t>();
  EXPECT_LT(held, added);
  EXPECT_GT(resumed["cache"]["reused"].get<std::size_t>(), 0u);
  EXPECT_EQ(resumed["cache"]["added"].get<std::size_t>(), added - held);
  EXPECT_EQ(resumed_rows, first_rows);
  EXPECT_EQ(resumed["best"], first["best"]);
  EXPECT_EQ(calibrate_into("cache_whole_again").first["cache"]["reused"].get<std::size_t>(), count);

  const std::string before = slurp(cache);
  const fs::path out = scratch("cache_refused");
  const Result r = run_imcol(args + out.string() + " --set contact.e_dry=0.9");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err, "imcol: error: " + cache.string() +
                       ":1: key '--cache': made for another calibration (not the same overrides (--set and the tolerance options)): "
                       "remove the file, or give another --cache\n");
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(slurp(cache), before);
  fs::remove(cache);
}
