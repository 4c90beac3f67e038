// SPDX-License-Identifier: BSD-3-Clause
// Every documented scene key and every command-line option, given each of a set of bad values: the value is either
// legitimately allowed (listed below) or refused with an input error whose one-line message names the key or option.
// The scene keys come from the scene reference's template (docs/scene-reference.md) and the [flow] table of
// docs/coupling.md; the options from each subcommand's --help. A key or option added without a case here fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include <toml++/toml.h>

#include "core/errors.hpp"
#include "core/materials.hpp"
#include "core/scene.hpp"
#include "flow/flow_scene.hpp"
#include "tests/imcol_process.hpp"

namespace fs = std::filesystem;
using imcol::test::Outcome;
using imcol::test::slurp;
using namespace imcol;

namespace {

fs::path source_dir() { return fs::path(data_dir()).parent_path(); }

/// The template of docs/scene-reference.md ("## Every key"): a valid scene that sets every key.
std::string reference_template() {
  const std::string text = slurp(source_dir() / "docs/scene-reference.md");
  std::smatch m;
  const std::string rest = text.substr(text.find("## Every key"));
  EXPECT_TRUE(std::regex_search(rest, m, std::regex("```toml\\n([\\s\\S]*?)```")));
  return m[1].str();
}

/// Dotted keys of every value in a TOML table ([[sphere]] as sphere[0]); arrays of values are leaves.
void leaf_keys(const toml::table& t, const std::string& prefix, std::vector<std::string>& out) {
  for (auto&& [k, v] : t) {
    const std::string key = prefix + std::string(k.str());
    if (const auto* sub = v.as_table()) leaf_keys(*sub, key + ".", out);
    else if (const auto* arr = v.as_array(); arr && arr->is_array_of_tables()) leaf_keys(*arr->get(0)->as_table(), key + "[0].", out);
    else out.push_back(key);
  }
}

/// The [flow] table's keys: the backquoted names in the first column of docs/coupling.md's table.
std::vector<std::string> flow_keys() {
  const std::string text = slurp(source_dir() / "docs/coupling.md");
  const auto at = text.find("## The `[flow]` table");
  EXPECT_NE(at, std::string::npos);
  std::vector<std::string> keys;
  std::istringstream lines(text.substr(at));
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line) && line.rfind("## ", 0) != 0) {
    if (line.rfind("| `", 0) != 0) continue;
    const std::string first = line.substr(1, line.find('|', 1) - 1);
    static const std::regex name("`([a-z_]+)`");
    for (std::sregex_iterator it(first.begin(), first.end(), name), end; it != end; ++it)
      keys.push_back("flow." + (*it)[1].str());
  }
  return keys;
}

const std::vector<std::string> kBadValues = {"nan", "inf", "-inf", "0", "-1", "1e300", "\"some text\"", "{ x = 1 }"};

/// The values a key legitimately takes among kBadValues (everything else must be refused naming the key).
const std::map<std::string, std::set<std::string>> kAllowed = {
    {"name", {"\"some text\""}},
    {"description", {"\"some text\""}},
    {"gravity", {"0", "-1"}},
    {"sphere[0].position", {"0", "-1"}},    // the wall is moved to z = 1 m for these cases
    {"sphere[0].velocity", {"0", "-1"}},    // at rest, moving away
    {"sphere[0].poisson_ratio", {"0"}},
    {"sphere[0].e_dry", {"0"}},             // a perfectly plastic dry contact
    {"contact.e_dry", {"0"}},
    {"measure.stall_fraction", {"0"}},      // never judged stalled
    {"wall.position", {"0"}},
    {"history.modes", {"0"}},               // 0 = automatic
    {"history.min_lag", {"0"}},
    {"history.horizon", {"0"}},
    {"history.direct_step", {"0"}},
    {"solver.max_step", {"0"}},
    {"flow.energy_margin", {"0"}},          // no margin: any energy beyond the supply ends the run
    {"flow.fields_every", {"0"}},           // only the named moments
    {"flow.preconditioner_bins", {"0"}},    // 0 = chosen from the run's steps
    {"flow.block_probe_stride", {"0"}},     // 0 = every block column by column
};

/// The keys of the template, the inline material properties its comment lists and `h_c` (asymptotic only), and the
/// [flow] keys.
std::vector<std::string> scene_keys() {
  std::vector<std::string> keys;
  leaf_keys(toml::parse(reference_template()), "", keys);
  for (const char* k : {"sphere[0].density", "sphere[0].youngs_modulus", "sphere[0].poisson_ratio", "sphere[0].e_dry", "lubrication.h_c"})
    keys.push_back(k);
  for (const auto& k : flow_keys()) keys.push_back(k);
  return keys;
}

/// The template, made fit for `key`: a [flow] key gets the flow effect, h_c the asymptotic law, and the impact sphere's
/// position a wall far enough away that 0 and -1 are positions like any other.
std::string base_for(const std::string& key, std::vector<Override>& ov) {
  std::string text = reference_template();
  if (key.rfind("flow.", 0) == 0)
    text = std::regex_replace(text, std::regex("effects = \\[\"drag\", \"lubrication\", \"added_mass\", \"history\", \"elastic\"\\]"),
                              "effects = [\"drag\", \"lubrication\", \"added_mass\", \"history\", \"elastic\", \"flow\"]");
  if (key == "lubrication.h_c") ov.push_back({"lubrication.model", "\"asymptotic\""});
  if (key == "sphere[0].position") ov.push_back({"wall.position", "1.0"});
  return text;
}

}  // namespace

TEST(BadValues, TheSourcesListTheKeys) {
  const auto keys = scene_keys();
  // A sample of what the documents must yield (so that a broken extraction does not pass silently).
  for (const char* k : {"fluid.viscosity", "sphere[0].velocity", "solver.atol", "solver.krylov_tol", "measure.stall_fraction",
                        "flow.dt", "flow.krylov_restart", "flow.behind", "output.dt", "history.direct_step"})
    EXPECT_NE(std::find(keys.begin(), keys.end(), k), keys.end()) << k;
  EXPECT_GT(keys.size(), 80u);
  for (const auto& [key, values] : kAllowed) EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key;
}

TEST(BadValues, EverySceneKeyRefusesEachBadValueNamingTheKey) {
  int refused = 0, accepted = 0;
  for (const auto& key : scene_keys()) {
    std::vector<Override> base_ov;
    const std::string text = base_for(key, base_ov);
    ASSERT_NO_THROW(parse_scene(text, "ref.toml", base_ov)) << key;  // the base is valid
    for (const auto& value : kBadValues) {
      auto ov = base_ov;
      ov.push_back({key, value});
      const auto allowed = kAllowed.find(key);
      const bool may_accept = allowed != kAllowed.end() && allowed->second.count(value);
      try {
        parse_scene(text, "ref.toml", ov);
        EXPECT_TRUE(may_accept) << key << " = " << value << " was accepted";
        ++accepted;
      } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("'" + key + "'"), std::string::npos) << key << " = " << value << ": " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        EXPECT_FALSE(may_accept) << key << " = " << value << " is allowed but refused: " << msg;
        ++refused;
      } catch (const std::exception& e) {
        ADD_FAILURE() << key << " = " << value << ": not an InputError: " << e.what();
      }
    }
  }
  std::printf("%d refused, %d accepted\n", refused, accepted);
}

// ---- Flow scenes (imcol flow): the template of docs/flow-kernel.md ------------------------------------

namespace {

/// The flow-scene template's keys ([stream] and [wall] exclude each other there, so it is a list, not a scene).
std::vector<std::string> flow_scene_keys() {
  const std::string text = slurp(source_dir() / "docs/flow-kernel.md");
  std::smatch m;
  const std::string rest = text.substr(text.find("### Flow scenes"));
  EXPECT_TRUE(std::regex_search(rest, m, std::regex("```toml\\n([\\s\\S]*?)```")));
  std::vector<std::string> keys;
  leaf_keys(toml::parse(m[1].str()), "", keys);
  return keys;
}

/// `text` with `key` (dotted, sphere[0] for the first [[sphere]]) set to the TOML value `value`.
std::string with_value(const std::string& text, const std::string& key, const std::string& value) {
  toml::table root = toml::parse(text);
  toml::table* at = &root;
  std::string rest = key;
  for (auto dot = rest.find('.'); dot != std::string::npos; dot = rest.find('.')) {
    const std::string part = rest.substr(0, dot);
    rest = rest.substr(dot + 1);
    if (part == "sphere[0]") at = root["sphere"].as_array()->get(0)->as_table();
    else {
      if (!at->contains(part)) at->insert(part, toml::table{});
      at = (*at)[part].as_table();
    }
  }
  toml::table v = toml::parse("v = " + value);
  v["v"].node()->visit([&](auto&& node) { at->insert_or_assign(rest, node); });
  std::ostringstream os;
  os << root;
  return os.str();
}

/// The values a flow-scene key legitimately takes among kBadValues.
const std::map<std::string, std::set<std::string>> kFlowAllowed = {
    {"name", {"\"some text\""}},
    {"description", {"\"some text\""}},
    {"wall.position", {"0"}},                // the sphere starts at z = 4 D
    {"sphere[0].position", {"0", "-1"}},     // in a stream, inside the grid
    {"sphere[0].velocity", {"0"}},           // fixed in the stream
    {"sphere[0].amplitude", {"0"}},          // no oscillation
    {"sphere[0].frequency", {"0"}},
    {"stream.velocity", {"-1"}},             // the stream may run along -z
    {"grid.z_min", {"-1"}},                  // the sphere at z = 0 still 3 cells inside
    {"output.snapshots", {"0"}},             // none
    {"output.min_gap", {"0"}},               // never stop
};

/// Keys whose bad values may be refused as a relation with the sphere ("sphere outside the finest grid ..., grid z in
/// [z_min, z_max], r < r_max"): the message names the sphere's table and quotes the grid.
const std::set<std::string> kFlowGridKeys = {"grid.z_min", "grid.z_max", "grid.r_max"};

}  // namespace

TEST(BadValues, EveryFlowSceneKeyRefusesEachBadValueNamingTheKey) {
  const std::string stream = slurp(fs::path(data_dir()) / "scenes/flow/fixed_sphere_re20.toml");
  const std::string wall = slurp(fs::path(data_dir()) / "scenes/flow/sphere_wall_approach_re0.1.toml");
  const fs::path file = fs::temp_directory_path() / ("imcol_badvalues_flow_" + std::to_string(::getpid()) + ".toml");
  const auto keys = flow_scene_keys();
  EXPECT_GT(keys.size(), 25u);
  for (const auto& [key, values] : kFlowAllowed) EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key;
  int refused = 0;
  for (const auto& key : keys) {
    const std::string& base = key.rfind("wall.", 0) == 0 ? wall : stream;
    for (const auto& value : kBadValues) {
      std::ofstream(file) << with_value(base, key, value);
      const auto allowed = kFlowAllowed.find(key);
      const bool may_accept = allowed != kFlowAllowed.end() && allowed->second.count(value);
      try {
        flow::load_flow_scene(file.string());
        EXPECT_TRUE(may_accept) << key << " = " << value << " was accepted";
      } catch (const InputError& e) {
        const std::string msg = e.what();
        // A sphere's problem names its [[sphere]] table; every other the key.
        const std::string named = key.rfind("sphere[0].", 0) == 0 ? "sphere" : "'" + key + "'";
        const bool grid_relation = kFlowGridKeys.count(key) && msg.find("key 'sphere[0]': sphere outside the finest grid") != std::string::npos;
        EXPECT_TRUE(msg.find(named) != std::string::npos || grid_relation) << key << " = " << value << ": " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        EXPECT_FALSE(may_accept) << key << " = " << value << " is allowed but refused: " << msg;
        ++refused;
      } catch (const std::exception& e) {
        ADD_FAILURE() << key << " = " << value << ": not an InputError: " << e.what();
      }
    }
  }
  fs::remove(file);
  std::printf("%d refused\n", refused);
}

// ---- Options, through the binary -------------------------------------------------------------------

namespace {

Outcome run_binary(const std::vector<std::string>& args, int slot) {
  const fs::path errf = fs::temp_directory_path() / ("imcol_badopt_err_" + std::to_string(::getpid()) + "_" + std::to_string(slot));
  std::string cmd = "timeout 20 " + std::string(IMCOL_BINARY);
  for (const auto& a : args) {
    std::string q = "'";
    for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    cmd += " " + q + "'";
  }
  cmd += " >/dev/null 2>" + errf.string();
  const int raw = std::system(cmd.c_str());
  std::string err = slurp(errf);
  fs::remove(errf);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, "", err};
}

/// The options a subcommand's --help lists (positionals excluded).
std::vector<std::string> help_options(const std::string& sub) {
  const fs::path out = fs::temp_directory_path() / ("imcol_badopt_help_" + std::to_string(::getpid()));
  const std::string cmd = std::string(IMCOL_BINARY) + " " + sub + " --help >" + out.string() + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << sub;
  const std::string text = slurp(out);
  fs::remove(out);
  std::vector<std::string> opts;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::smatch m;
    if (std::regex_search(line, m, std::regex("^\\s+(?:-[a-zA-Z],)?(--[a-z][a-z-]*)")) && m[1] != "--help") opts.push_back(m[1]);
  }
  return opts;
}

// (inf takes nan's path. In list-valued options CLI11 drops empty items, so "1e-6," is 1e-6.)
const std::string kNumberBad[] = {"abc", "nan", "-1", "1e300", "1e-300", ""};

}  // namespace

TEST(BadValues, EveryOptionRefusesEachBadValueNamingIt) {
  const std::string scene = (fs::path(data_dir()) / "scenes/default.toml").string();
  const std::string flow_scene = (fs::path(data_dir()) / "scenes/flow/fixed_sphere_re20.toml").string();
  ASSERT_TRUE(fs::exists(flow_scene)) << flow_scene;
  // What each subcommand needs besides the option under test (never reached: the option is refused first).
  const std::map<std::string, std::vector<std::string>> base = {
      {"run", {scene}}, {"validate", {"seed"}}, {"bench", {scene}}, {"effects", {scene}}, {"history", {scene}}, {"laws", {scene}},
      {"flow", {flow_scene}}, {"work-precision", {scene}},
      {"sweep", {scene, "--vary", "velocity", "--from", "0.1", "--to", "0.2", "--points", "2"}}};
  // Bad values per option: numbers, choices, paths and scene overrides; a flag given a value.
  std::vector<std::string> numbers(std::begin(kNumberBad), std::end(kNumberBad));
  const std::vector<std::string> choices = {"abc", ""}, flag = {"=abc"};
  const std::map<std::string, std::vector<std::string>> bad = {
      {"--rtol", numbers}, {"--atol", numbers}, {"--tolerance", numbers}, {"--rtols", {"abc", "nan", "1e-6,abc", "1e-6,2", "1e-300", ""}}, {"--repeat", {"abc", "0", "-1", "1.5", "1e300", ""}},
      {"--cells", {"abc", "0", "3", "1.5", "99999999999999999999"}}, {"--levels", {"abc", "0", "17", "nan"}}, {"--dt", numbers},
      {"--t-end", numbers}, {"--direct-steps", {"abc", "nan", "1e-15", "1e-6", "1e-300", "1e300", "-1"}}, {"--direct-rtol", numbers},
      {"--ref-rtol", numbers}, {"--ref-history-tolerance", numbers}, {"--from", numbers}, {"--to", numbers},
      {"--points", {"abc", "0", "-1", "1.5", "1e300"}}, {"--jobs", {"abc", "-1", "1.5", "1e300"}},
      {"--integrator", choices}, {"--integrators", choices}, {"--evaluators", choices}, {"--kernels", choices}, {"--laws", choices},
      {"--models", choices}, {"--vary", choices}, {"--spacing", choices}, {"--export", choices},
      {"--set", {"novalue", "solver.rtol=1e-8\nsolver.bogus=1", "=1"}}, {"--out", {""}},
      {"--quiet", flag}, {"--no-plot", flag}, {"--flow", flag}, {"--allow-long", flag}, {"--add-history", flag}, {"--no-progress", flag}};
  struct Case {
    std::string label, option;
    std::vector<std::string> args;
  };
  std::vector<Case> cases;
  std::set<std::string> done;  // options tested with every bad value in one subcommand: in the others, the first and last
  for (const auto& [sub, args] : base) {
    const auto opts = help_options(sub);
    EXPECT_GT(opts.size(), 1u) << sub;
    for (const auto& opt : opts) {
      const auto it = bad.find(opt);
      if (it == bad.end()) {
        ADD_FAILURE() << "imcol " << sub << " " << opt << ": no bad values listed for this option";
        continue;
      }
      std::vector<std::string> values = it->second;
      if (!done.insert(opt).second && values.size() > 2) values = {values.front(), values.back()};
      for (const auto& value : values) {
        std::vector<std::string> a = {sub};
        // The option under test replaces a required option's value in the base arguments.
        for (std::size_t i = 0; i < args.size(); ++i) {
          if (args[i] == opt) {
            ++i;
            continue;
          }
          a.push_back(args[i]);
        }
        if (value.rfind("=", 0) == 0) a.push_back(opt + value);
        else a.insert(a.end(), {opt, value});
        cases.push_back({"imcol " + sub + " " + opt + " '" + value + "'", opt, a});
      }
    }
  }
  // The runs on a few threads (each is a process start and a refusal), the checks here.
  std::vector<Outcome> outcomes(cases.size());
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < 4; ++t)
    pool.emplace_back([&, t] {
      for (std::size_t i = next++; i < cases.size(); i = next++) outcomes[i] = run_binary(cases[i].args, t);
    });
  for (auto& t : pool) t.join();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& [label, opt, args] = cases[i];
    const Outcome& r = outcomes[i];
    EXPECT_EQ(r.status, 2) << label << ": " << r.err;
    EXPECT_EQ(r.err.rfind("imcol: error: ", 0), 0u) << label << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << label << ": " << r.err;
    EXPECT_NE(r.err.find(opt), std::string::npos) << label << ": " << r.err;
  }
  std::printf("%zu option cases\n", cases.size());
}

TEST(BadValues, EveryInputFileRefusesWhatIsNotARegularFileOfBoundedSize) {
  // A device, a FIFO (which would block a reader for ever), a directory and /proc text as the scene, the measurement,
  // the held-out measurement and the cache: exit 2 within the time limit, one line naming the path.
  const fs::path tmp = fs::temp_directory_path() / ("imcol_badfile_" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp / "a_directory");
  const std::string fifo = (tmp / "a_fifo").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string scene = (fs::path(data_dir()) / "scenes/gg3462.toml").string();
  const std::string data = (fs::path(data_dir()) / "measurements/gg3462_trajectory.csv").string();
  const std::vector<std::string> bad = {"/dev/zero", fifo, (tmp / "a_directory").string(), "/dev/null"};
  struct Case {
    std::string label, path;  // the case, the path its message must name
    std::vector<std::string> args;
  };
  std::vector<Case> cases;
  const std::vector<std::string> fit = {"--fit", "contact.delta_ss=0.005:0.05", "--out", (tmp / "out").string()};
  for (const auto& b : bad) {
    cases.push_back({"imcol run " + b, b, {"run", b, "--out", (tmp / "out").string()}});
    for (const std::string opt : {"--data", "--validate", "--cache"}) {
      std::vector<std::string> a = {"calibrate", scene, "--data", opt == "--data" ? b : data};
      a.insert(a.end(), fit.begin(), fit.end());
      if (opt != "--data") a.insert(a.end(), {opt, b});
      cases.push_back({"imcol calibrate " + opt + " " + b, b, a});
    }
  }
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& [label, path, args] = cases[i];
    const Outcome r = run_binary(args, static_cast<int>(i));
    EXPECT_EQ(r.status, 2) << label << ": " << r.err;
    EXPECT_EQ(r.err.rfind("imcol: error: ", 0), 0u) << label << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << label << ": " << r.err;
    EXPECT_NE(r.err.find(path), std::string::npos) << label << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(tmp / "out"));
  fs::remove_all(tmp);
}

TEST(BadValues, AnOutputFolderThatIsNotImcolsIsRefusedAndKeptAsItWas) {
  // A user's folder of CSV and JSON files, an imcol folder a user added a file to, a folder holding the scene, a name
  // of the staging form and a dangling symbolic link as --out: exit 2, one line naming --out, every file kept.
  const fs::path tmp = fs::temp_directory_path() / ("imcol_badout_" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  const std::string scene = (fs::path(data_dir()) / "scenes/default.toml").string();
  fs::create_directories(tmp / "userdir");
  std::ofstream(tmp / "userdir" / "experiment_2019.csv") << "t,z\n0,1\n";
  std::ofstream(tmp / "userdir" / "notes.json") << "{}\n";
  const std::string added = (tmp / "added").string();
  ASSERT_EQ(run_binary({"run", scene, "--quiet", "--no-plot", "--out", added}, 0).status, 0);
  std::ofstream(tmp / "added" / "experiment_2019.csv") << "mine\n";
  fs::create_directories(tmp / "holds_scene");
  fs::copy_file(scene, tmp / "holds_scene" / "scene.toml");
  fs::create_symlink(tmp / "nowhere", tmp / "dangling");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run", (tmp / "userdir").string()}, {"run", added}, {"sweep", (tmp / "added").string()},
      {"run", (tmp / ".x.part-1").string()}, {"run", (tmp / "dangling").string()}};
  int i = 0;
  for (const auto& [sub, out] : cases) {
    std::vector<std::string> a = {sub, scene, "--out", out};
    if (sub == "sweep") a.insert(a.end(), {"--vary", "velocity", "--from", "0.1", "--to", "0.2", "--points", "2"});
    const Outcome r = run_binary(a, ++i);
    EXPECT_EQ(r.status, 2) << sub << " --out " << out << ": " << r.err;
    EXPECT_EQ(r.err.rfind("imcol: error: command line: key '--out': ", 0), 0u) << out << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << out << ": " << r.err;
  }
  const Outcome in = run_binary({"run", (tmp / "holds_scene" / "scene.toml").string(), "--out", (tmp / "holds_scene").string()}, 9);
  EXPECT_EQ(in.status, 2) << in.err;
  EXPECT_NE(in.err.find("(the scene file), an input of this run"), std::string::npos) << in.err;
  // A calibration's cache inside its output folder would go with the folder's previous content.
  const Outcome cache = run_binary({"calibrate", (fs::path(data_dir()) / "scenes/gg3462.toml").string(), "--data",
                                    (fs::path(data_dir()) / "measurements/gg3462_trajectory.csv").string(), "--fit",
                                    "contact.delta_ss=0.005:0.05", "--cache", added + "/cache.csv", "--out", added}, 10);
  EXPECT_EQ(cache.status, 2) << cache.err;
  EXPECT_NE(cache.err.find("(--cache), an input of this run"), std::string::npos) << cache.err;
  EXPECT_FALSE(fs::exists(tmp / "added" / "cache.csv"));
  EXPECT_EQ(slurp(tmp / "userdir" / "experiment_2019.csv"), "t,z\n0,1\n");
  EXPECT_EQ(slurp(tmp / "added" / "experiment_2019.csv"), "mine\n");
  EXPECT_TRUE(fs::exists(tmp / "added" / "summary.json"));
  EXPECT_TRUE(fs::exists(tmp / "holds_scene" / "scene.toml"));
  EXPECT_FALSE(fs::exists(tmp / ".x.part-1"));
  EXPECT_FALSE(fs::exists(tmp / "nowhere"));
  fs::remove_all(tmp);
}
