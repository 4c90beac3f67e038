// SPDX-License-Identifier: BSD-3-Clause
// An output folder is one unit: all of one run's files or none of them, one writer at a time
// (apps/output_unit.hpp). Unit tests of OutputUnit, then faults through the binary: kill -9 at random
// moments of a run and of a sweep, and concurrent writers into one folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/output_unit.hpp"
#include "core/errors.hpp"
#include "core/materials.hpp"
#include "tests/imcol_process.hpp"

namespace fs = std::filesystem;
using imcol::test::Outcome;
using imcol::test::slurp;
using imcol::OutputUnit;

namespace {

fs::path fresh(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("imcol_unit_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p;
}

Outcome run_shell(const std::string& cmd) {
  const fs::path errf = fs::temp_directory_path() / ("imcol_unit_err_" + std::to_string(::getpid()) + "_" +
                                                     std::to_string(std::hash<std::string>{}(cmd)));
  const int raw = std::system((cmd + " >/dev/null 2>" + errf.string()).c_str());
  Outcome o{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, "", slurp(errf)};
  fs::remove(errf);
  return o;
}

std::string imcol_cmd(const std::string& args) {
  return "cd '" + fs::path(imcol::data_dir()).parent_path().string() + "' && " + IMCOL_BINARY + " " + args;
}

/// Staging folders left beside `dir`.
std::vector<fs::path> staged_beside(const fs::path& dir) {
  std::vector<fs::path> v;
  std::string prefix = ".";  // appended: "." + a temporary string gives a false -Wrestrict in GCC 12 at -O3
  prefix += dir.filename().string();
  prefix += ".";
  for (const auto& f : fs::directory_iterator(dir.parent_path()))
    if (f.path().filename().string().rfind(prefix, 0) == 0) v.push_back(f.path());
  return v;
}

/// The folder is empty, or one run's whole unit: the marker lists exactly the files present, summary.json names
/// the same run, and the trajectory starts at the velocity the run was given. Returns the velocity (0 if empty).
double check_run_unit(const fs::path& dir) {
  if (!fs::exists(dir) || fs::is_empty(dir)) return 0;
  const auto marker = nlohmann::json::parse(slurp(dir / ".imcol-run.json"));
  std::set<std::string> listed, present;
  for (const auto& f : marker["files"]) listed.insert(f.get<std::string>());
  for (const auto& f : fs::directory_iterator(dir))
    if (f.path().filename() != ".imcol-run.json") present.insert(f.path().filename().string());
  EXPECT_EQ(listed, present) << dir;
  const auto summary = nlohmann::json::parse(slurp(dir / "summary.json"));
  EXPECT_EQ(summary["run"]["id"], marker["id"]);
  const std::string command = summary["run"]["command"].get<std::string>();
  const auto at = command.find("velocity=");
  EXPECT_NE(at, std::string::npos) << command;
  const double given = std::stod(command.substr(at + 9));
  std::istringstream csv(slurp(dir / "trajectory.csv"));
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  std::vector<std::string> cells;
  std::istringstream r(row);
  for (std::string c; std::getline(r, c, ',');) cells.push_back(c);
  EXPECT_GE(cells.size(), 3u);
  EXPECT_EQ(header.rfind("t,z1,u1,", 0), 0u) << header;
  EXPECT_DOUBLE_EQ(std::stod(cells.at(2)), given) << "trajectory and summary from different runs in " << dir;
  return given;
}

/// Writes `files` (name -> content) into `dir` as one committed unit.
void commit_files(const fs::path& dir, const std::vector<std::pair<std::string, std::string>>& files) {
  OutputUnit unit(dir.string(), "unused");
  for (const auto& [name, content] : files) {
    fs::create_directories((unit.dir() / name).parent_path());
    std::ofstream(unit.dir() / name) << content;
  }
  unit.commit();
}

std::set<std::string> names_in(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& f : fs::directory_iterator(dir)) names.insert(f.path().filename().string());
  return names;
}

/// The message of the InputError that constructing an OutputUnit throws ("" if it does not throw).
std::string refusal(const std::string& out, const std::string& scene_path = "", const std::vector<imcol::RunInput>& inputs = {}) {
  try {
    OutputUnit unit(out, "unused", scene_path, inputs);
  } catch (const imcol::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(OutputUnit, CommitReplacesTheWholeFolderAndNamesTheRun) {
  const fs::path dir = fresh("replace");
  // An earlier run's unit: a coupled run's field, a picture, its VTK folder.
  commit_files(dir, {{"flow_00.csv", "old\n"}, {"trajectory.png", "old"}, {"vtk/flow_00.vtm", "<VTKFile/>"}});
  EXPECT_EQ(names_in(dir), (std::set<std::string>{".imcol-run.json", "flow_00.csv", "trajectory.png", "vtk"}));
  {
    OutputUnit unit(dir.string(), "unused");
    EXPECT_NE(unit.dir(), dir);
    std::ofstream(unit.dir() / "summary.json") << "{}\n";
    EXPECT_TRUE(fs::exists(dir / "flow_00.csv"));  // nothing changes until the commit
    unit.commit();
  }
  EXPECT_EQ(names_in(dir), (std::set<std::string>{".imcol-run.json", "summary.json"}));
  const auto marker = nlohmann::json::parse(slurp(dir / ".imcol-run.json"));
  EXPECT_FALSE(marker["id"].get<std::string>().empty());
  EXPECT_EQ(marker["pid"].get<long>(), ::getpid());
  EXPECT_EQ(marker["files"], nlohmann::json::array({"summary.json"}));
  EXPECT_FALSE(marker.contains("complete"));
  EXPECT_TRUE(staged_beside(dir).empty());
  fs::remove_all(dir);
}

TEST(OutputUnit, AFolderIsReplacedOnlyWhenItsMarkerListsAllItHolds) {
  const fs::path dir = fresh("marker");
  // CSV and JSON files without a marker are a user's, however they are named.
  fs::create_directories(dir);
  std::ofstream(dir / "experiment_2019.csv") << "t,z\n";
  std::ofstream(dir / "notes.json") << "{}";
  std::string why = refusal(dir.string());
  EXPECT_NE(why.find("holds 'experiment_2019.csv', which imcol did not write (no .imcol-run.json"), std::string::npos) << why;
  EXPECT_EQ(slurp(dir / "experiment_2019.csv"), "t,z\n");
  // A marker that is not imcol's does not make the folder imcol's.
  std::ofstream(dir / ".imcol-run.json") << "{\"files\": [\"experiment_2019.csv\", \"notes.json\"]}";
  EXPECT_NE(refusal(dir.string()).find("which imcol did not write"), std::string::npos);
  fs::remove_all(dir);
  // An imcol folder that a user added a file to keeps it: the folder is refused, naming the file.
  commit_files(dir, {{"summary.json", "{}"}, {"vtk/flow_end.vtm", "<VTKFile/>"}});
  std::ofstream(dir / "experiment_2019.csv") << "mine";
  why = refusal(dir.string());
  EXPECT_NE(why.find("holds 'experiment_2019.csv', which imcol did not write (the run that wrote the folder lists its files"),
            std::string::npos) << why;
  EXPECT_EQ(slurp(dir / "experiment_2019.csv"), "mine");
  EXPECT_TRUE(staged_beside(dir).empty());
  // Without that file the folder is imcol's again, its vtk/ folder too.
  fs::remove(dir / "experiment_2019.csv");
  commit_files(dir, {{"summary.json", "{\"new\": 1}"}});
  EXPECT_EQ(names_in(dir), (std::set<std::string>{".imcol-run.json", "summary.json"}));
  fs::remove_all(dir);
}

TEST(OutputUnit, AFolderHoldingAnInputOfTheRunIsRefused) {
  const fs::path dir = fresh("inputs");
  commit_files(dir, {{"cache.csv", "# imcol evaluation cache\n"}, {"scene.toml", "name = 'x'\n"}});
  std::string why = refusal(dir.string(), "", {{"--data", "/nonexistent/m.csv"}, {"--cache", (dir / "cache.csv").string()}});
  EXPECT_NE(why.find("holds '" + (dir / "cache.csv").string() + "' (--cache), an input of this run"), std::string::npos) << why;
  // Also through a relative path and a path that names the folder another way.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir.parent_path());
  why = refusal(dir.filename().string() + "/", dir.filename().string() + "/./scene.toml");
  fs::current_path(cwd);
  EXPECT_NE(why.find("(the scene file), an input of this run"), std::string::npos) << why;
  EXPECT_TRUE(fs::exists(dir / "cache.csv"));
  // An input beside the folder is no reason to refuse it.
  EXPECT_EQ(refusal(dir.string(), "", {{"--cache", dir.string() + "-cache.csv"}}), "");
  fs::remove_all(dir);
}

TEST(OutputUnit, StagingNamesAreRefusedAndOnlyStagingFoldersAreRemoved) {
  const fs::path dir = fresh("staging");
  const fs::path parent = dir.parent_path();
  const std::string n = dir.filename().string();
  // A folder of the staging form cannot be an output folder: a later run into NAME would remove it.
  for (const std::string& name : {"." + n + ".part-1", "." + n + ".old-42"}) {
    const std::string why = refusal((parent / name).string());
    EXPECT_NE(why.find("has the form of the folders imcol stages a run in"), std::string::npos) << name << ": " << why;
    EXPECT_FALSE(fs::exists(parent / name));
  }
  // A run into NAME removes a killed run's staging folder, and nothing else that starts like one.
  fs::create_directories(parent / ("." + n + ".part-999999"));
  fs::create_directories(parent / ("." + n + ".part-mine"));
  std::ofstream(parent / ("." + n + ".old-7")) << "a file, not a staging folder";
  commit_files(dir, {{"summary.json", "{}"}});
  EXPECT_FALSE(fs::exists(parent / ("." + n + ".part-999999")));
  EXPECT_TRUE(fs::exists(parent / ("." + n + ".part-mine")));
  EXPECT_TRUE(fs::exists(parent / ("." + n + ".old-7")));
  fs::remove_all(parent / ("." + n + ".part-mine"));
  fs::remove(parent / ("." + n + ".old-7"));
  fs::remove_all(dir);
}

TEST(OutputUnit, ADanglingSymbolicLinkIsNamedAsSuch) {
  const fs::path link = fresh("dangling");
  fs::create_symlink(link.string() + "-nowhere", link);
  const std::string why = refusal(link.string());
  EXPECT_NE(why.find("is a symbolic link to '" + link.string() + "-nowhere', which does not exist"), std::string::npos) << why;
  fs::remove(link);
}

TEST(OutputUnit, KeptBesideLeavesThePreviousResultAsItWas) {
  const fs::path dir = fresh("beside");
  commit_files(dir, {{"sweep.csv", "complete\n"}, {"sweep.json", "{}"}});
  fs::path kept;
  {
    OutputUnit unit(dir.string(), "unused");
    std::ofstream(unit.dir() / "sweep.csv") << "partial\n";
    kept = unit.keep_beside();
  }
  EXPECT_EQ(slurp(dir / "sweep.csv"), "complete\n");
  EXPECT_TRUE(fs::exists(dir / "sweep.json"));
  EXPECT_EQ(kept.parent_path(), dir.parent_path());
  EXPECT_EQ(kept.filename().string().rfind(dir.filename().string() + ".partial-", 0), 0u) << kept;
  EXPECT_EQ(slurp(kept / "sweep.csv"), "partial\n");
  const auto marker = nlohmann::json::parse(slurp(kept / ".imcol-run.json"));
  EXPECT_EQ(marker["complete"], false);
  EXPECT_EQ(marker["files"], nlohmann::json::array({"sweep.csv"}));
  EXPECT_TRUE(staged_beside(dir).empty());
  // A new folder that only a kept-beside run used is removed again.
  const fs::path fresh_dir = fresh("beside_new");
  {
    OutputUnit unit(fresh_dir.string(), "unused");
    std::ofstream(unit.dir() / "sweep.csv") << "partial\n";
    const fs::path k = unit.keep_beside();
    fs::remove_all(k);
  }
  EXPECT_FALSE(fs::exists(fresh_dir));
  fs::remove_all(dir);
  fs::remove_all(kept);
}

TEST(OutputUnit, AClosedStandardOutputLosesNoResult) {
  // `imcol sweep … | true`: the reader is gone before the table is printed; the sweep still writes its folder whole.
  const fs::path dir = fresh("sigpipe");
  const fs::path status = dir.string() + ".status";
  const std::string cmd = "bash -c '" + imcol_cmd("sweep data/scenes/default.toml --vary velocity --from 0.1 --to 0.3 --points 40 "
                                                  "--no-plot --no-progress --out " + dir.string()) +
                          " | true; echo ${PIPESTATUS[0]} > " + status.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(slurp(status), "0\n");
  ASSERT_TRUE(fs::exists(dir / "sweep.json"));
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "sweep.json"))["complete"], true);
  EXPECT_FALSE(fs::exists(dir / "sweep.partial"));
  EXPECT_TRUE(staged_beside(dir).empty());
  fs::remove(status);
  fs::remove_all(dir);
}

TEST(OutputUnit, AnUncommittedUnitLeavesThePreviousResultAndNoTrace) {
  const fs::path dir = fresh("uncommitted");
  commit_files(dir, {{"summary.json", "previous\n"}});
  { OutputUnit unit(dir.string(), "unused"); std::ofstream(unit.dir() / "summary.json") << "new\n"; }
  EXPECT_EQ(slurp(dir / "summary.json"), "previous\n");
  EXPECT_TRUE(staged_beside(dir).empty());
  // A folder created for a run that never committed is removed again, with the parents it created.
  const fs::path nested = fresh("nested") / "a" / "b";
  { OutputUnit unit(nested.string(), "unused"); }
  EXPECT_FALSE(fs::exists(nested.parent_path().parent_path()));
  fs::remove_all(dir);
}

TEST(OutputUnit, ASecondWriterIsRefusedWhileTheFirstHoldsTheFolder) {
  const fs::path dir = fresh("second");
  OutputUnit first(dir.string(), "unused");
  try {
    OutputUnit second(dir.string(), "unused");
    FAIL() << "a second writer was let in";
  } catch (const imcol::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("being written by another imcol process (pid " + std::to_string(::getpid()) + ")"),
              std::string::npos) << e.what();
    EXPECT_EQ(e.key(), "--out");
  }
  // Another process too: exit 2 and one line, before anything runs.
  const Outcome o = run_shell(imcol_cmd("run data/scenes/default.toml --no-plot --quiet --out " + dir.string()));
  EXPECT_EQ(o.status, 2) << o.err;
  EXPECT_EQ(o.err.rfind("imcol: error: command line: key '--out': the output folder", 0), 0u) << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  first.commit();
  // Once committed, the folder is free again.
  OutputUnit third(dir.string(), "unused");
  third.commit();
  fs::remove_all(dir);
}

TEST(OutputUnit, FoldersThatAreNotImcolOutputsAreRefused) {
  const fs::path dir = fresh("foreign");
  fs::create_directories(dir / "notes");
  std::ofstream(dir / "thesis.tex") << "mine";
  try {
    OutputUnit unit(dir.string(), "unused");
    FAIL() << "a folder of other files was taken";
  } catch (const imcol::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("which imcol did not write"), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(dir / "thesis.tex"), "mine");
  EXPECT_TRUE(staged_beside(dir).empty());
  // The current folder (or one containing it) cannot be swapped out.
  const fs::path cwd = fs::current_path();
  fs::create_directories(dir / "inner");
  fs::current_path(dir / "inner");
  for (const std::string& out : std::vector<std::string>{".", "..", dir.string()}) {
    try {
      OutputUnit unit(out, "unused");
      ADD_FAILURE() << out << " was taken";
    } catch (const imcol::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("current folder"), std::string::npos) << e.what();
    }
  }
  fs::current_path(cwd);
  fs::remove_all(dir);
}

TEST(OutputUnit, AnImpossiblePlaceIsRefusedBeforeAnythingRuns) {
  // A folder under a regular file: exit 2 naming --out, before the sweep's 2000 points run (none is in the message).
  const fs::path file = fresh("file");
  std::ofstream(file) << "x";
  const Outcome o = run_shell(imcol_cmd("sweep data/scenes/gg3462.toml --vary velocity --from 0.1 --to 1 --points 2000 --no-plot --no-progress --out " +
                                        (file / "x").string()));
  EXPECT_EQ(o.status, 2) << o.err;
  EXPECT_EQ(o.err.rfind("imcol: error: command line: key '--out': cannot create the output folder", 0), 0u) << o.err;
  fs::remove(file);
}

TEST(OutputUnit, KilledRunsLeaveEitherTheOldResultOrTheNewOneWhole) {
  // kill -9 at random moments (seeded) of a run that replaces a run at another velocity, with and without plots.
  const fs::path dir = fresh("killed");
  ASSERT_EQ(run_shell(imcol_cmd("run data/scenes/default.toml --no-plot --quiet --set sphere[0].velocity=0.1 --out " + dir.string())).status, 0);
  ASSERT_DOUBLE_EQ(check_run_unit(dir), 0.1);
  std::mt19937 rng(20261126);
  int old_seen = 0, new_seen = 0;
  for (const bool plot : {false, true}) {
    // The time of a whole run, measured here, sets the range of the kill moments.
    const auto t0 = std::chrono::steady_clock::now();
    const std::string args = std::string("run data/scenes/default.toml --quiet ") + (plot ? "" : "--no-plot ") + "--out " + dir.string();
    ASSERT_EQ(run_shell(imcol_cmd(args + " --set sphere[0].velocity=0.2")).status, 0);
    const double whole = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (int k = 0; k < (plot ? 4 : 10); ++k) {
      const double prior = check_run_unit(dir);
      const double v = k % 2 ? 0.2 : 0.3;
      const double at = std::uniform_real_distribution<double>(0.005, 1.2 * whole)(rng);
      std::ostringstream cmd;
      cmd << "timeout -s KILL " << at << " " << IMCOL_BINARY << " " << args << " --set sphere[0].velocity=" << v;
      run_shell("cd '" + fs::path(imcol::data_dir()).parent_path().string() + "' && " + cmd.str());
      const double now = check_run_unit(dir);
      EXPECT_TRUE(now == prior || now == v) << "after a kill at " << at << " s: velocity " << now;
      (now == prior && prior != v ? old_seen : new_seen)++;
    }
  }
  // The next run cleans up whatever the killed ones left beside the folder.
  const Outcome last = run_shell(imcol_cmd("run data/scenes/default.toml --no-plot --quiet --set sphere[0].velocity=0.25 --out " + dir.string()));
  ASSERT_EQ(last.status, 0) << last.err;
  EXPECT_DOUBLE_EQ(check_run_unit(dir), 0.25);
  EXPECT_TRUE(staged_beside(dir).empty());
  std::cout << "kills that left the previous result: " << old_seen << ", the new one: " << new_seen << "\n";
  fs::remove_all(dir);
}

TEST(OutputUnit, ConcurrentWritersNeverMixAFolder) {
  // Four processes at four velocities into one folder, five rounds: each one either writes the whole folder or is
  // refused with one line (exit 2); the folder always holds one of the writers' whole results.
  const fs::path dir = fresh("concurrent");
  for (int round = 0; round < 5; ++round) {
    std::vector<std::thread> threads;
    std::vector<Outcome> outcomes(4);
    for (int w = 0; w < 4; ++w)
      threads.emplace_back([&, w] {
        outcomes[w] = run_shell(imcol_cmd("run data/scenes/default.toml --quiet --no-plot --out " + dir.string() +
                                          " --set sphere[0].velocity=0." + std::to_string(w + 1)));
      });
    for (auto& t : threads) t.join();
    std::set<double> written;
    for (int w = 0; w < 4; ++w) {
      if (outcomes[w].status == 0) {
        written.insert(0.1 * (w + 1));
        continue;
      }
      EXPECT_EQ(outcomes[w].status, 2) << outcomes[w].err;
      EXPECT_NE(outcomes[w].err.find("being written by another imcol process"), std::string::npos) << outcomes[w].err;
      EXPECT_EQ(std::count(outcomes[w].err.begin(), outcomes[w].err.end(), '\n'), 1) << outcomes[w].err;
    }
    ASSERT_FALSE(written.empty());
    const double v = check_run_unit(dir);
    bool from_a_writer = false;
    for (double x : written) from_a_writer = from_a_writer || std::abs(x - v) < 1e-12;
    EXPECT_TRUE(from_a_writer) << v;
  }
  EXPECT_TRUE(staged_beside(dir).empty());
  fs::remove_all(dir);
}

TEST(OutputUnit, TwoSweepsIntoOneFolderDoNotMix) {
  // A second sweep is refused while the first runs; the first then completes as one unit.
  const fs::path dir = fresh("sweeps");
  const std::string first = imcol_cmd("sweep data/scenes/gg3462.toml --vary velocity --from 0.1 --to 1 --points 400 --jobs 1 --no-plot "
                                      "--no-progress --out " + dir.string());
  std::thread t([&] { EXPECT_EQ(run_shell(first).status, 0); });
  // Wait until the first sweep holds the folder (its staging folder appears).
  for (int i = 0; i < 500 && (!fs::exists(dir.parent_path()) || staged_beside(dir).empty()); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const Outcome second = run_shell(imcol_cmd("sweep data/scenes/gg3462.toml --vary viscosity --from 0.01 --to 0.1 --points 5 --no-plot "
                                             "--no-progress --out " + dir.string()));
  t.join();
  EXPECT_EQ(second.status, 2) << second.err;
  EXPECT_NE(second.err.find("being written by another imcol process"), std::string::npos) << second.err;
  const auto j = nlohmann::json::parse(slurp(dir / "sweep.json"));
  EXPECT_EQ(j["vary"], "velocity");
  EXPECT_EQ(j["points"], 400);
  std::istringstream csv(slurp(dir / "sweep.csv"));
  int rows = -1;
  for (std::string line; std::getline(csv, line);) rows += !line.empty() && line[0] != '#';
  EXPECT_EQ(rows, 400);
  EXPECT_FALSE(fs::exists(dir / "sweep.partial"));
  fs::remove_all(dir);
}
