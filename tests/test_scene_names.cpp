// SPDX-License-Identifier: BSD-3-Clause
// Scenes by name (core/scene_files.hpp) and `imcol scenes`: from another working directory, by name, nested name,
// with ".toml"; a missing name names the places looked; every shipped scene listed with its description.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/errors.hpp"
#include "core/materials.hpp"
#include "core/scene.hpp"
#include "core/scene_files.hpp"
#include "tests/input_error.hpp"

namespace fs = std::filesystem;
using namespace imcol;

namespace {

struct Result {
  int status;
  std::string out, err;
};

/// Runs imcol with `args` in the folder `cwd`.
Result run_in(const fs::path& cwd, const std::string& args) {
  const fs::path base = fs::temp_directory_path() / ("imcol_names_" + std::to_string(::getpid()));
  const std::string cmd = "cd '" + cwd.string() + "' && " + std::string(IMCOL_BINARY) + " " + args + " >" + base.string() +
                          ".out 2>" + base.string() + ".err";
  const int raw = std::system(cmd.c_str());
  auto slurp = [](const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  Result r{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(base.string() + ".out"), slurp(base.string() + ".err")};
  fs::remove(base.string() + ".out");
  fs::remove(base.string() + ".err");
  return r;
}

/// An empty folder away from the source tree.
fs::path elsewhere() {
  const fs::path d = fs::temp_directory_path() / ("imcol_names_cwd_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

}  // namespace

TEST(SceneNames, FindSceneByName) {
  const fs::path dir = scenes_dir();
  EXPECT_EQ(fs::path(find_scene("default")), dir / "default.toml");
  EXPECT_EQ(fs::path(find_scene("default.toml")), dir / "default.toml");
  EXPECT_EQ(fs::path(find_scene("coupled/gg3462")), dir / "coupled/gg3462.toml");
  // The README's path: the file itself from the source tree, the shipped scene from anywhere else.
  EXPECT_TRUE(fs::equivalent(find_scene("data/scenes/gondret/st27.toml"), dir / "gondret/st27.toml"));
  // A path that exists wins over a name.
  const fs::path cwd = elsewhere();
  const fs::path own = cwd / "default";
  std::ofstream(own) << "x";
  EXPECT_EQ(find_scene(own.string()), own.string());
  fs::remove_all(cwd);
}

TEST(SceneNames, MissingSceneSaysWhereItLooked) {
  const std::string m = test::input_error_of([] { find_scene("defualt"); });
  ASSERT_FALSE(m.empty()) << "no error";
  EXPECT_NE(m.find("key 'scene'"), std::string::npos) << m;
  EXPECT_NE(m.find(fs::absolute("defualt").string()), std::string::npos) << m;
  EXPECT_NE(m.find(scenes_dir()), std::string::npos) << m;
  EXPECT_NE(m.find("close names: default"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST(SceneNames, CommandsTakeNamesFromAnotherFolder) {
  const fs::path cwd = elsewhere();
  const fs::path out = cwd / "out";
  Result r = run_in(cwd, "run default --quiet --no-plot --out " + (out / "a").string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "a" / "summary.json"));
  r = run_in(cwd, "run default.toml --quiet --no-plot --out " + (out / "b").string());
  EXPECT_EQ(r.status, 0) << r.err;
  r = run_in(cwd, "run gondret/st742 --quiet --no-plot --set solver.t_end=0.01 --out " + (out / "c").string());
  EXPECT_EQ(r.status, 0) << r.err;
  // The README's path works from any folder.
  r = run_in(cwd, "effects data/scenes/dry_steel_steel.toml");
  EXPECT_EQ(r.status, 0) << r.err;
  // A missing scene: exit 2, one line naming the places looked and the close names.
  r = run_in(cwd, "sweep gg346 --vary velocity --from 0.1 --to 0.2 --points 2");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find((cwd / "gg346").string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(scenes_dir()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("gg3462"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("coupled/gg3462"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  fs::remove_all(cwd);
}

TEST(SceneNames, ScenesListsEveryShippedScene) {
  const Result r = run_in(elsewhere(), "scenes");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto names = shipped_scene_names();
  ASSERT_GT(names.size(), 40u);
  std::istringstream lines(r.out);
  std::map<std::string, std::string> listed;  // name -> the rest of its line
  for (std::string l; std::getline(lines, l);) {
    std::istringstream ls(l);
    std::string first;
    ls >> first;
    std::string rest;
    std::getline(ls, rest);
    if (l.rfind("  ", 0) == 0) listed[first] = rest;
  }
  for (const auto& n : names) {
    ASSERT_TRUE(listed.count(n)) << n << " not listed:\n" << r.out;
    // Every shipped scene has a one-line description, and the list shows it.
    const std::string path = scenes_dir() + "/" + n + ".toml";
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto at = text.find("\ndescription = \"");
    ASSERT_NE(at, std::string::npos) << n << " has no description";
    const auto start = at + 16;
    const std::string description = text.substr(start, text.find('"', start) - start);
    EXPECT_FALSE(description.empty()) << n;
    EXPECT_NE(listed[n].find(description), std::string::npos) << n << ": " << listed[n];
    EXPECT_EQ(listed[n].find("unreadable"), std::string::npos) << n << ": " << listed[n];
  }
  EXPECT_NE(listed["default"].find("sphere-wall"), std::string::npos);
  EXPECT_NE(listed["gg3462"].find("sphere-sphere"), std::string::npos);
  EXPECT_NE(listed["coupled/gg3462"].find("sphere-sphere, coupled"), std::string::npos);
  EXPECT_NE(listed["flow/fixed_sphere_re20"].find("flow"), std::string::npos);
  // A pattern.
  const Result g = run_in(elsewhere(), "scenes gondret");
  EXPECT_EQ(g.status, 0);
  EXPECT_NE(g.out.find("gondret/st27"), std::string::npos);
  EXPECT_EQ(g.out.find("seed_run1"), std::string::npos);
  fs::remove_all(elsewhere());
}

TEST(SceneNames, AFolderNamedAsAShippedSceneIsTheShippedScene) {
  // An old output folder `default` (imcol run default --out default) in the working folder: `imcol run default` runs
  // the shipped scene, not "is a directory".
  const fs::path cwd = elsewhere();
  fs::create_directories(cwd / "default");
  fs::create_directories(cwd / "not_a_scene");
  const fs::path here = fs::current_path();
  fs::current_path(cwd);
  EXPECT_EQ(fs::path(find_scene("default")), fs::path(scenes_dir()) / "default.toml");
  EXPECT_EQ(find_scene("not_a_scene"), "not_a_scene");  // no such shipped scene: the folder, refused by the reader
  fs::current_path(here);
  const Result r = run_in(cwd, "run default --quiet --no-plot --out out_default");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(cwd / "out_default" / "summary.json"));
  const Result dir = run_in(cwd, "run not_a_scene --quiet --no-plot");
  EXPECT_EQ(dir.status, 2);
  EXPECT_NE(dir.err.find("is a directory"), std::string::npos) << dir.err;
  fs::remove_all(cwd);
}

TEST(SceneNames, AProcFileIsReadForWhatItHolds) {
  // /proc files report size 0: their text is read all the same, so the error is about that text (not TOML),
  // not a missing [[sphere]].
  const Result r = run_in(elsewhere(), "run /proc/self/status --quiet --no-plot");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err.find("key 'sphere': missing"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/proc/self/status"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("TOML"), std::string::npos) << r.err;
}

TEST(SceneNames, ASceneOfTheOtherKindNamesItsCommand) {
  const Result run = run_in(elsewhere(), "run flow/fixed_sphere_re20 --quiet --no-plot");
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("this is a flow scene"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("imcol flow"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("missing"), std::string::npos) << run.err;
  const Result sweep = run_in(elsewhere(), "sweep flow/fixed_sphere_re20 --vary velocity --from 0.1 --to 1 --points 2 --no-plot");
  EXPECT_EQ(sweep.status, 2);
  EXPECT_NE(sweep.err.find("this is a flow scene"), std::string::npos) << sweep.err;
  const Result flow = run_in(elsewhere(), "flow default --no-plot");
  EXPECT_EQ(flow.status, 2);
  EXPECT_NE(flow.err.find("this is a collision scene"), std::string::npos) << flow.err;
  EXPECT_NE(flow.err.find("imcol run"), std::string::npos) << flow.err;
  EXPECT_EQ(flow.err.find("missing"), std::string::npos) << flow.err;
  // Every shipped scene is read by its own command's reader without this message.
  for (const auto& name : shipped_scene_names()) {
    if (name.starts_with("flow/")) continue;
    EXPECT_NO_THROW(load_scene(find_scene(name))) << name;
  }
}
