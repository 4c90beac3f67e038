// SPDX-License-Identifier: BSD-3-Clause
// Randomized test of the scene reader: thousands of malformed scenes, made deterministically from
// valid ones (the shipped data/scenes/*.toml and builder scenes that use every table). Each must
// either parse to a validated Scene or throw InputError with a one-line message naming the file
// and a line or a key; mutations that are certainly invalid must be rejected at the mutated key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "core/errors.hpp"
#include "core/materials.hpp"
#include "core/scene.hpp"
#include "tests/scene_text.hpp"

using namespace imcol;

namespace {

const std::string kPath = "fuzz.toml";

// ---- Base scenes ----------------------------------------------------------------------------

/// A wall scene that sets every key of every table (valid).
std::string full_wall_scene() {
  return "name = \"full_wall\"\ndescription = \"every table\"\ngravity = -9.81\n"
         "effects = [\"drag\", \"lubrication\", \"added_mass\", \"elastic\", \"gravity\", \"history\"]\n" +
         test::fluid(0.02, 1200.0) +
         "[[sphere]]\ndensity = 7800.0\nyoungs_modulus = 2e11\npoisson_ratio = 0.3\ne_dry = 0.97\n"
         "diameter = 0.0127\nposition = -0.0127\nvelocity = 0.3\n" +
         test::wall("glass", 0.0) +
         "[contact]\ndelta_ss = 0.017\ndelta_sl = 0.1\ne_dry = 0.97\nbeta = 200.0\n"
         "[drag]\nlaw = \"schiller-naumann\"\n"
         "[lubrication]\nmodel = \"brenner\"\ncutoff = 1e-4\n"  // h_c: asymptotic only (the pair scene)
         "[added_mass]\nmodel = \"lagrangian\"\ndw_floor = 0.034\n"
         "[history]\nkernel = \"kim\"\nevaluator = \"soe\"\ntolerance = 1e-6\nmodes = 20\nmin_lag = 1e-6\n"
         "horizon = 1.0\nstart = \"impulsive\"\nreynolds = \"initial\"\nwall_correction = \"added-mass\"\n"
         "direct_step = 1e-5\n"
         "[solver]\nintegrator = \"cvode\"\nlinear_solver = \"gmres\"\nkrylov_tol = 0.05\nrtol = 1e-8\n"
         "atol = 1e-10\nt_end = 0.5\nmax_step = 1e-3\nmax_steps = 100000\n"
         "[measure]\nwindow = 0.01\ninstant_gap = 0.02\nstall_fraction = 0.01\n"
         "[output]\ndt = 1e-4\n";
}

/// A pair scene with the pair-only choices (valid).
std::string full_pair_scene() {
  return "effects = [\"drag\", \"lubrication\", \"added_mass\", \"elastic\"]\n" + test::fluid(0.004, 1112.0) +
         test::sphere("glass", 0.0127, 0.0, 0.11) + test::sphere("steel", 0.0127, 0.016, 0.0) +
         "[lubrication]\nmodel = \"asymptotic\"\ncutoff = 1e-4\nh_c = 0.5\n"
         "[added_mass]\nmodel = \"seed\"\n[contact]\ndelta_ss = 0.024\n"
         "[solver]\nintegrator = \"ida\"\nlinear_solver = \"dense\"\nt_end = 0.06\n";
}

std::vector<std::string> base_scenes() {
  std::vector<std::string> out = {full_wall_scene(), full_pair_scene(), test::basic_wall_scene()};
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(data_dir() + "/scenes"))
    if (e.path().extension() == ".toml") files.push_back(e.path());
  std::sort(files.begin(), files.end());  // a fixed order: the same cases on every run
  for (const auto& p : files) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    out.push_back(ss.str());
  }
  return out;
}

// ---- Line model: which table each `key = value` line belongs to ----------------------------

struct Line {
  std::string text;
  std::string table;  // "" (top), "fluid", "sphere[0]", ...
  std::string key;    // "" unless `key = value`
  std::string value;  // without a trailing comment
};

std::vector<Line> split(const std::string& text) {
  std::vector<Line> out;
  std::string table;
  int spheres = 0;
  std::istringstream in(text);
  for (std::string s; std::getline(in, s);) {
    Line l{s, table, "", ""};
    if (s.rfind("[[sphere]]", 0) == 0) {
      table = l.table = "sphere[" + std::to_string(spheres++) + "]";
    } else if (s.rfind("[", 0) == 0) {
      table = l.table = s.substr(1, s.find(']') - 1);
    } else if (auto eq = s.find(" = "); eq != std::string::npos && s[0] != '#') {
      l.key = s.substr(0, eq);
      l.value = s.substr(eq + 3);
      if (l.value[0] != '"' && l.value[0] != '[') l.value = l.value.substr(0, l.value.find(" #"));
    }
    out.push_back(l);
  }
  return out;
}

std::string join(const std::vector<Line>& lines) {
  std::string s;
  for (const auto& l : lines) s += l.text + "\n";
  return s;
}

void set_value(Line& l, const std::string& v) {
  l.value = v;
  l.text = l.key + " = " + v;
}

std::string full_key(const Line& l) { return l.table.empty() ? l.key : l.table + "." + l.key; }

bool is_number_line(const Line& l) {
  return !l.key.empty() && l.key != "effects" && !l.value.empty() && l.value[0] != '"';
}

// ---- Values -----------------------------------------------------------------------------------

/// TOML numbers at the edges: (text, what the reader must say if it rejects them at this key).
struct Extreme {
  const char* text;
  enum { finite_needed, too_large, plain } kind;
};
const Extreme kExtremes[] = {
    {"nan", Extreme::finite_needed},  {"+nan", Extreme::finite_needed}, {"-nan", Extreme::finite_needed},
    {"inf", Extreme::finite_needed},  {"-inf", Extreme::finite_needed}, {"1e308", Extreme::too_large},
    {"-1e308", Extreme::too_large},   {"1e31", Extreme::too_large},     {"1e30", Extreme::plain},
    {"-1e30", Extreme::plain},        {"1e-308", Extreme::plain},       {"5e-324", Extreme::plain},
    {"1e-31", Extreme::plain},        {"-0.0", Extreme::plain},         {"0.0", Extreme::plain},
    {"0", Extreme::plain},            {"-1", Extreme::plain},           {"-1.5e-3", Extreme::plain},
    {"1", Extreme::plain},            {"9007199254740993", Extreme::plain},
    {"9223372036854775807", Extreme::plain}, {"-9223372036854775808", Extreme::plain},
    {"0x7fffffff", Extreme::plain},   {"1_000", Extreme::plain},        {"0.1e-2", Extreme::plain},
};

const char* kWrongTypes[] = {"\"0.02\"", "\"\"", "[1.0, 2.0]", "[]", "{ a = 1 }", "{}", "true", "false",
                             "1979-05-27", "07:32:00", "1979-05-27T07:32:00Z", "[[1], [\"a\"]]", "'literal'",
                             "\"\"\"multi\nline\"\"\"", "\"steel\"", "\"ida\"", "[\"drag\"]"};

const char* kUnicode[] = {"é", "日本語", "🦀", "\u200b", "\u202e", "\xef\xbb\xbf", "\xff", "\xc3\x28",
                          "\xe2\x82", "\xf0\x9f\x98", "\xc0\xaf", "\xed\xa0\x80", "\\u00e9", "\\U0001F600",
                          "\\n", "\\r\\n", "\\t", "\\u0000", "\\u001b[31m", "\\\"", "\\x41", "\\uD800"};

const char* kEffects[] = {"drag", "lubrication", "added_mass", "elastic", "gravity", "history", "flow",
                          "Drag", "magic", "", " drag", "added-mass", "élastique"};

const char* kTables[] = {"fluid", "wall", "contact", "drag", "lubrication", "added_mass", "history",
                         "solver", "measure", "output", "sphere", "flow", "Fluid", "sphère"};

const char* kOverrideKeys[] = {"fluid.viscosity", "sphere[0].velocity", "sphere[1].position", "sphere.0.diameter",
                               "solver.rtol", "solver.integrator", "history.modes", "effects", "wall.position",
                               "bogus.key", "sphere[5].velocity", "fluid.viscosity.deeper", "name", "..", "[0]",
                               "wall", "sphere", "contact.e_dry", "effects[0]", "effects[0].x", "fluid.fluid",
                               "fluid.mass_fraction", "fluid.temperature"};

// ---- Random helpers (modulo arithmetic: the same cases with every standard library) ---------

struct Rng {
  std::mt19937_64 g{20261122};
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(g() % n); }
  bool chance(int percent) { return below(100) < static_cast<std::size_t>(percent); }
  template <class T, std::size_t N>
  const T& pick(const T (&a)[N]) { return a[below(N)]; }
  template <class T>
  const T& pick(const std::vector<T>& v) { return v[below(v.size())]; }
};

std::string random_value(Rng& r) {
  switch (r.below(5)) {
    case 0: return r.pick(kExtremes).text;
    case 1: return r.pick(kWrongTypes);
    case 2: return "\"" + std::string(r.pick(kUnicode)) + "\"";
    case 3: {
      const double mantissa = static_cast<double>(r.below(2000)) - 1000;
      return test::num(std::ldexp(mantissa, static_cast<int>(r.below(200)) - 100));
    }
    default: return "\"" + std::string(r.pick(kEffects)) + "\"";
  }
}

/// One random mutation of the whole text.
std::string mutate(std::string text, Rng& r) {
  std::vector<Line> lines = split(text);
  auto any_line = [&]() -> std::size_t { return r.below(lines.size()); };
  std::vector<std::size_t> kv;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (!lines[i].key.empty()) kv.push_back(i);
  switch (r.below(17)) {
    case 0:  // byte flips
      for (std::size_t k = 0, n = 1 + r.below(4); k < n && !text.empty(); ++k)
        text[r.below(text.size())] = static_cast<char>(r.below(256));
      return text;
    case 1: {  // byte insertion / deletion (one draw per statement: the same cases with every compiler)
      const bool insert = r.chance(50) || text.empty();
      const std::size_t at = r.below(text.size() + (insert ? 1 : 0));
      if (insert) return text.insert(at, 1, static_cast<char>(r.below(256)));
      return text.erase(at, 1 + r.below(3));
    }
    case 2:  // truncation
      return text.substr(0, r.below(text.size() + 1));
    case 3:  // delete a line
      if (!lines.empty()) lines.erase(lines.begin() + any_line());
      return join(lines);
    case 4:  // duplicate a line (duplicate keys, a third [[sphere]], ...)
      if (!lines.empty()) {
        auto i = any_line();
        lines.insert(lines.begin() + r.below(lines.size() + 1), lines[i]);
      }
      return join(lines);
    case 5:  // swap two lines (keys move to other tables)
      if (lines.size() > 1) {
        const std::size_t a = any_line(), b = any_line();
        std::swap(lines[a], lines[b]);
      }
      return join(lines);
    case 6:  // swap the values of two keys
      if (kv.size() > 1) {
        auto a = r.pick(kv), b = r.pick(kv);
        const std::string va = lines[a].value;
        set_value(lines[a], lines[b].value);
        set_value(lines[b], va);
      }
      return join(lines);
    case 7:  // a value of another type, an extreme number, unicode, an effect name
      if (!kv.empty()) {
        const std::size_t i = r.pick(kv);
        set_value(lines[i], random_value(r));
      }
      return join(lines);
    case 8: {  // unknown key somewhere
      const std::size_t at = r.below(lines.size() + 1);
      lines.insert(lines.begin() + at, Line{"zz_unknown_" + std::to_string(r.below(9)) + " = 1.0", "", "", ""});
      return join(lines);
    }
    case 9:  // a table: unknown, duplicated, or array-of-tables where a table is expected
      return r.chance(50) ? text + "[" + r.pick(kTables) + "]\nx = 1\n" : text + "[[" + r.pick(kTables) + "]]\n";
    case 10: {  // a random effects list
      std::string list = "effects = [";
      for (std::size_t k = 0, n = r.below(5); k < n; ++k) list += (k ? ", \"" : "\"") + std::string(r.pick(kEffects)) + "\"";
      return list + "]\n" + text;
    }
    case 11:  // unicode or escapes inside a string value or a key
      if (!kv.empty()) {
        Line& l = lines[r.pick(kv)];
        if (r.chance(50)) set_value(l, "\"x" + std::string(r.pick(kUnicode)) + "y\"");
        else l.text = "\"" + l.key + r.pick(kUnicode) + "\" = " + l.value;
      }
      return join(lines);
    case 12: {  // unicode bytes anywhere
      std::size_t p = r.below(text.size() + 1);
      return text.insert(p, r.pick(kUnicode));
    }
    case 13: {  // very long strings, keys and numbers
      const std::size_t n = 1000 + r.below(100000);
      switch (r.below(4)) {
        case 0: return "name = \"" + std::string(n, 'a') + "\"\n" + text;
        case 1: return "description = \"" + std::string(n, 'd') + "\"\n" + text;
        case 2: return std::string(n, 'k') + " = 1\n" + text;
        default:
          if (!kv.empty()) set_value(lines[r.pick(kv)], "1" + std::string(n % 5000, '0') + ".5");
          return join(lines);
      }
    }
    case 14: {  // deep nesting
      const std::size_t d = 1 + r.below(600);
      return "x = " + std::string(d, '[') + std::string(d, ']') + "\n" + text;
    }
    case 15:  // a table replaced by a value, or a value by a table
      if (!kv.empty()) {
        Line& l = lines[r.pick(kv)];
        l.text = "[" + (l.table.empty() ? "" : l.table + ".") + l.key + "]";
      }
      return join(lines);
    default:  // a line of random printable junk
      {
        std::string junk;
        for (std::size_t k = 0, n = 1 + r.below(30); k < n; ++k) junk += static_cast<char>(32 + r.below(95));
        lines.insert(lines.begin() + r.below(lines.size() + 1), Line{junk, "", "", ""});
        return join(lines);
      }
  }
}

// ---- Checks -----------------------------------------------------------------------------------

/// The message is `where[: key 'K']: problem`, one line, where = the file, or file:line with a line
/// of the text (the file alone only together with a key); with overrides also "--set" or the
/// command-line place.
void check_message(const InputError& e, const std::string& text, bool overrides, const std::string& context) {
  const std::string msg = e.what(), where = e.where(), key = e.key();
  ASSERT_EQ(msg.find_first_of("\n\r"), std::string::npos) << "not one line: " << msg << "\n" << context;
  const std::string head = where + (key.empty() ? "" : ": key '" + key + "'") + ": ";
  ASSERT_EQ(msg.rfind(head, 0), 0u) << "message does not start with its place: " << msg << "\n" << context;
  ASSERT_GT(msg.size(), head.size()) << "no problem stated: " << msg << "\n" << context;
  if (overrides && (where == "--set" || where.rfind("command line", 0) == 0)) {
    ASSERT_FALSE(key.empty()) << msg;
    return;
  }
  ASSERT_EQ(where.rfind(kPath, 0), 0u) << "does not name the file: " << msg << "\n" << context;
  if (where == kPath) {
    ASSERT_FALSE(key.empty()) << "names neither a line nor a key: " << msg << "\n" << context;
    return;
  }
  const std::string line = where.substr(kPath.size());
  ASSERT_TRUE(line.size() > 1 && line[0] == ':' && line.find_first_not_of("0123456789", 1) == std::string::npos)
      << "bad place '" << where << "': " << msg << "\n" << context;
  const long n = std::stol(line.substr(1));
  const long lines = 1 + static_cast<long>(std::count(text.begin(), text.end(), '\n'));
  ASSERT_TRUE(n >= 1 && n <= lines) << "line " << n << " not in the text (" << lines << " lines): " << msg << "\n" << context;
}

bool finite_positive(double v) { return std::isfinite(v) && v >= 1e-30 && v <= 1e30; }

/// What the reader promises about a scene it accepts.
void check_scene(const Scene& sc, const std::string& context) {
  ASSERT_TRUE(sc.spheres.size() == 1 || sc.spheres.size() == 2) << context;
  ASSERT_FALSE(sc.two_spheres() && sc.wall) << context;
  ASSERT_TRUE(!sc.name.empty() && sc.name.find_first_of("/\\") == std::string::npos) << context;
  for (const auto& s : sc.spheres) {
    ASSERT_TRUE(finite_positive(s.diameter) && finite_positive(s.density) && finite_positive(s.youngs_modulus)) << context;
    ASSERT_TRUE(s.poisson_ratio > -1 && s.poisson_ratio < 0.5) << context;
    ASSERT_TRUE(std::isfinite(s.position) && std::isfinite(s.velocity)) << context;
  }
  ASSERT_TRUE(!sc.fluid || (finite_positive(sc.fluid->density) && finite_positive(sc.fluid->viscosity))) << context;
  for (Effect e : {Effect::drag, Effect::lubrication, Effect::added_mass, Effect::history}) {
    ASSERT_TRUE(!sc.has(e) || sc.fluid) << context;
  }
  ASSERT_TRUE(!sc.has(Effect::flow) || sc.fluid) << context;
  ASSERT_TRUE(sc.flow.cells_per_diameter >= 4 && sc.flow.levels >= 1 && sc.flow.cfl >= 0 && sc.flow.cfl <= 1) << context;
  ASSERT_TRUE(sc.flow.dt >= 0 && std::isfinite(sc.flow.dt) && sc.flow.krylov_tol > 0) << context;
  ASSERT_TRUE(!sc.has_target() || sc.has(Effect::elastic)) << context;
  ASSERT_TRUE(sc.solver.rtol >= 1e-14 && sc.solver.rtol < 1) << context;
  ASSERT_TRUE(sc.solver.atol > 0 && sc.solver.atol < 1) << context;
  ASSERT_TRUE(finite_positive(sc.solver.t_end) && sc.solver.max_steps >= 1) << context;
  ASSERT_TRUE(sc.output.dt > 0 && sc.solver.t_end / sc.output.dt <= 1e7) << context;
  ASSERT_TRUE(sc.history.modes == 0 || (sc.history.modes >= 2 && sc.history.modes <= 400)) << context;
  ASSERT_TRUE(sc.contact.delta_ss > 0 && sc.contact.delta_ss < 1) << context;
  if (sc.two_spheres()) {
    ASSERT_GT(sc.spheres[1].position - sc.spheres[0].position, 0.5 * (sc.spheres[0].diameter + sc.spheres[1].diameter)) << context;
  }
  if (sc.wall) {
    ASSERT_GT(sc.wall->position - sc.spheres[0].position, 0.5 * sc.spheres[0].diameter) << context;
  }
}

struct FuzzOutcome {
  bool accepted = false;
  std::string key, problem;
};

/// Parses; fails the test on anything but a validated Scene or a well-formed InputError.
FuzzOutcome run_case(const std::string& text, const std::vector<std::string>& overrides, const std::string& what) {
  std::string context = "case: " + what + "\n--- text (lines cut at 100 bytes) ---\n";
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) context += l.substr(0, 100) + (l.size() > 100 ? "...\n" : "\n");
  FuzzOutcome o;
  try {
    std::vector<Override> ov;
    for (const auto& s : overrides) ov.push_back(parse_override(s));
    const Scene sc = parse_scene(text, kPath, ov);
    o.accepted = true;
    check_scene(sc, context);
  } catch (const InputError& e) {
    check_message(e, text, !overrides.empty(), context);
    o.key = e.key();
    const std::string msg = e.what();
    const std::string head = e.where() + (o.key.empty() ? "" : ": key '" + o.key + "'") + ": ";
    o.problem = msg.substr(std::min(head.size(), msg.size()));
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InputError: " << typeid(e).name() << ": " << e.what() << "\n" << context;
  } catch (...) {
    ADD_FAILURE() << "unknown exception type\n" << context;
  }
  return o;
}

struct Counts {
  long accepted = 0, rejected = 0;
  void add(const FuzzOutcome& o) { ++(o.accepted ? accepted : rejected); }
  long total() const { return accepted + rejected; }
};

void report(const char* name, const Counts& c) {
  std::cout << "[ fuzz     ] " << name << ": " << c.total() << " scenes, " << c.accepted << " accepted, " << c.rejected
            << " rejected\n";
  ::testing::Test::RecordProperty(std::string(name) + "_accepted", static_cast<int>(c.accepted));
  ::testing::Test::RecordProperty(std::string(name) + "_rejected", static_cast<int>(c.rejected));
}

}  // namespace

TEST(SceneFuzz, BaseScenesAreValid) {
  for (const auto& b : base_scenes()) EXPECT_NO_THROW(parse_scene(b, kPath)) << b;
}

// Random mutations, 1–3 stacked, some with random --set overrides.
TEST(SceneFuzz, RandomMutationsParseOrThrowInputError) {
  const auto bases = base_scenes();
  Rng r;
  Counts c;
  for (int i = 0; i < 3000; ++i) {
    std::string text = r.pick(bases);
    for (std::size_t k = 0, n = 1 + r.below(3); k < n; ++k) text = mutate(text, r);
    std::vector<std::string> ov;
    if (r.chance(15))
      for (std::size_t k = 0, n = 1 + r.below(2); k < n; ++k) {
        const std::string key = r.pick(kOverrideKeys);
        ov.push_back(key + "=" + random_value(r));
      }
    c.add(run_case(text, ov, "random #" + std::to_string(i)));
    if (HasFailure()) break;  // one clear report, not thousands
  }
  report("random", c);
  EXPECT_EQ(c.total(), 3000);
  EXPECT_GT(c.rejected, 1500);  // most mutations break a scene ...
  EXPECT_GT(c.accepted, 30);    // ... but not all: the reader is not rejecting everything
}

// Every numeric key of every base scene set to every edge value, alone.
TEST(SceneFuzz, ExtremeNumbersAreReadOrRejectedAtTheirKey) {
  Counts c;
  for (const auto& b : base_scenes()) {
    const auto lines = split(b);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (!is_number_line(lines[i])) continue;
      for (const Extreme& x : kExtremes) {
        auto mutated = lines;
        set_value(mutated[i], x.text);
        const std::string key = full_key(lines[i]);
        const FuzzOutcome o = run_case(join(mutated), {}, key + " = " + x.text);
        c.add(o);
        if (lines[i].key == "modes" || lines[i].key == "max_steps") {  // integers
          const bool integer = std::string(x.text).find_first_of(".eEna") == std::string::npos;
          if (!integer) {
            EXPECT_EQ(o.problem, "must be an integer") << key << " = " << x.text;
          }
        } else if (x.kind == Extreme::finite_needed || x.kind == Extreme::too_large) {
          EXPECT_FALSE(o.accepted) << key << " = " << x.text;
          EXPECT_EQ(o.key, key) << x.text;
          EXPECT_NE(o.problem.find(x.kind == Extreme::finite_needed ? "finite" : "magnitude at most 1e30"), std::string::npos)
              << key << " = " << x.text << ": " << o.problem;
        } else if (!o.accepted && o.key == key) {
          // A number within range, refused: the reason must not be that it is not a number.
          EXPECT_EQ(o.problem.find("must be a number"), std::string::npos) << key << " = " << x.text << ": " << o.problem;
        }
      }
    }
  }
  report("extreme", c);
  EXPECT_GT(c.total(), 1500);
}

// Mutations that are certainly invalid: each base, alone, must be rejected at the named key.
TEST(SceneFuzz, CertainlyInvalidScenesAreRejectedAtTheirKey) {
  struct Bad {
    const char* table;  // "" = top level
    const char* key;
    const char* value;
    const char* problem;
  };
  const Bad bad[] = {
      {"fluid", "viscosity", "-0.02", "> 0"},         {"fluid", "viscosity", "0.0", "> 0"},
      {"fluid", "viscosity", "nan", "finite"},         {"fluid", "density", "-1.0", "> 0"},
      {"fluid", "viscosity", "\"0.02\"", "must be a number"},
      {"fluid", "fluid", "\"honey\"", "unknown fluid"},     {"fluid", "fluid", "3", "must be a string"},
      {"fluid", "temperature", "\"warm\"", "must be a number"},
      {"sphere[0]", "diameter", "nan", "finite"},      {"sphere[0]", "diameter", "-0.0", "> 0"},
      {"sphere[0]", "diameter", "-0.0127", "> 0"},     {"sphere[0]", "diameter", "1e-31", "at least 1e-30"},
      {"sphere[0]", "diameter", "inf", "finite"},      {"sphere[0]", "velocity", "[0.3]", "must be a number"},
      {"sphere[0]", "material", "\"unobtainium\"", "unknown material"},
      {"sphere[0]", "material", "3", "must be a string"},
      {"solver", "rtol", "0.0", "must be in"},         {"solver", "rtol", "1e-15", "must be in"},
      {"solver", "atol", "-1e-10", "must be in"},      {"solver", "t_end", "-1.0", "> 0"},
      {"solver", "integrator", "\"rk4\"", "unknown choice"},
      {"solver", "max_steps", "1.5", "must be an integer"},
      {"measure", "window", "0", "> 0"},               {"contact", "delta_ss", "1.5", "must be in"},
      {"", "name", "\"a/b\"", "plain file name"},      {"", "name", "\"..\"", "plain file name"},
      {"", "gravity", "\"down\"", "must be a number"},
  };
  Counts c;
  for (const auto& b : base_scenes()) {
    const auto lines = split(b);
    auto has_table = [&](const std::string& t) {
      return std::any_of(lines.begin(), lines.end(), [&](const Line& l) { return l.table == t; });
    };
    auto expect_rejected = [&](const std::string& text, const std::string& key, const std::string& problem) {
      const FuzzOutcome o = run_case(text, {}, key + ": " + problem);
      c.add(o);
      EXPECT_FALSE(o.accepted) << key << " (" << problem << ")\n" << text;
      EXPECT_EQ(o.key, key) << o.problem << "\n" << text;
      EXPECT_NE(o.problem.find(problem), std::string::npos) << "expected '" << problem << "' in: " << o.problem;
    };
    for (const Bad& x : bad) {
      if (!has_table(x.table)) continue;
      auto mutated = lines;
      auto it = std::find_if(mutated.begin(), mutated.end(), [&](const Line& l) { return l.table == x.table && l.key == x.key; });
      const Line entry{std::string(x.key) + " = " + x.value, x.table, x.key, x.value};
      if (it != mutated.end()) set_value(*it, x.value);
      else if (std::string(x.table).empty()) mutated.insert(mutated.begin(), entry);
      else {  // after the table's header
        auto h = std::find_if(mutated.begin(), mutated.end(), [&](const Line& l) { return l.table == x.table; });
        mutated.insert(h + 1, entry);
      }
      expect_rejected(join(mutated), std::string(x.table).empty() ? x.key : std::string(x.table) + "." + x.key, x.problem);
    }
    // An unknown key in each table present, an unknown table, an unknown effect, a table given as an array.
    for (const std::string t : {"", "fluid", "sphere[0]", "sphere[1]", "wall", "contact", "history", "solver", "output"}) {
      if (!t.empty() && !has_table(t)) continue;
      auto mutated = lines;
      auto h = t.empty() ? mutated.begin() : std::find_if(mutated.begin(), mutated.end(), [&](const Line& l) { return l.table == t; }) + 1;
      mutated.insert(h, Line{"colour = \"red\"", t, "colour", "\"red\""});
      expect_rejected(join(mutated), t.empty() ? "colour" : t + ".colour", "unknown key");
    }
    expect_rejected(b + "[bogus_table]\nx = 1\n", "bogus_table", "unknown key");
    {
      auto mutated = lines;
      auto it = std::find_if(mutated.begin(), mutated.end(), [](const Line& l) { return l.table.empty() && l.key == "effects"; });
      const std::string list = "[\"drag\", \"warp_drive\"]";
      if (it != mutated.end()) set_value(*it, list);
      else mutated.insert(mutated.begin(), Line{"effects = " + list, "", "effects", list});
      expect_rejected(join(mutated), "effects", "unknown effect 'warp_drive'");
    }
    if (has_table("fluid")) {
      std::vector<Line> mutated;
      for (const auto& l : lines)
        if (l.table != "fluid") mutated.push_back(l);
      mutated.insert(mutated.begin(), Line{"fluid = [1.0, 2.0]", "", "fluid", "[1.0, 2.0]"});
      expect_rejected(join(mutated), "fluid", "must be a table");
    }
  }
  report("certain", c);
  EXPECT_GT(c.total(), 300);
}
