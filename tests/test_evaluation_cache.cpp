// SPDX-License-Identifier: BSD-3-Clause
// The evaluation cache of `imcol calibrate --cache` (calibrate/evaluation_cache.hpp): what it writes reads back bit
// for bit; a header made for another calibration is refused naming what differs; a last line cut short by a kill
// is left out, a damaged one elsewhere is an error naming its line; the writer adds each evaluation once.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "calibrate/evaluation_cache.hpp"
#include "core/errors.hpp"
#include "tests/imcol_process.hpp"

namespace fs = std::filesystem;
using namespace imcol;
using namespace imcol::calib;
using imcol::test::slurp;

namespace {

CacheContext trajectory_context() {
  CacheContext c;
  c.imcol_version = "9.9.9";
  c.scene_text = "[fluid]\nviscosity = 1e-3\n";
  c.measurement_text = "t,z1\n0,0\n";
  c.overrides = {"solver.rtol=1e-8"};
  c.fit_keys = {"contact.delta_ss", "contact.e_dry"};
  c.window = {0.0125, -0.004, 0.008, 0.002};
  return c;
}

Evaluation evaluation(double objective, bool ok = true) {
  Evaluation e;
  e.ok = ok;
  e.objective = ok ? objective : INFINITY;
  e.rms = std::sqrt(e.objective);
  e.tau = 1.0 / 3.0 * 1e-3;
  e.residuals = 41;
  e.e_sim = {0.1 + 1e-17, NAN};
  e.message = ok ? "" : "CVODE: too much work, \"quoted\"\nnext line";
  e.wall_s = 0.0123;
  return e;
}

/// A cache file of this process's own, removed at the end of the test.
struct CacheFile {
  fs::path path = fs::temp_directory_path() / ("imcol_evaluation_cache_" + std::to_string(::getpid()) + ".cache");
  CacheFile() { fs::remove(path); }
  ~CacheFile() { fs::remove(path); }
  EvaluationCache read(const CacheContext& c = trajectory_context()) const { return {path.string(), slurp(path), c}; }
};

std::string refusal(const CacheFile& f, const CacheContext& c) {
  try {
    f.read(c);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(EvaluationCache, WhatItWritesReadsBackBitForBit) {
  CacheFile f;
  const std::vector<double> a{0.1, 0.95}, b{1.0 / 3.0 * 0.07, std::nextafter(0.9, 1.0)};
  {
    const EvaluationCache none = f.read();
    EXPECT_EQ(none.size(), 0u);
    CacheWriter w(f.path.string(), none, trajectory_context());
    w.add_item(evaluations_to_bytes({{a, evaluation(2.5e-11)}}));
    w.add_item(evaluations_to_bytes({{b, evaluation(0, false)}}));
    EXPECT_EQ(w.added(), 2u);
  }
  const EvaluationCache c = f.read();
  ASSERT_EQ(c.size(), 2u);
  const auto ea = c.find(a), eb = c.find(b);
  ASSERT_TRUE(ea && eb);
  const Evaluation want = evaluation(2.5e-11);
  EXPECT_TRUE(ea->ok);
  EXPECT_EQ(ea->objective, want.objective);
  EXPECT_EQ(ea->rms, want.rms);
  EXPECT_EQ(*ea->tau, *want.tau);
  EXPECT_EQ(ea->residuals, 41u);
  ASSERT_EQ(ea->e_sim.size(), 2u);
  EXPECT_EQ(ea->e_sim[0], want.e_sim[0]);
  EXPECT_TRUE(std::isnan(ea->e_sim[1]));
  EXPECT_FALSE(eb->ok);
  EXPECT_TRUE(std::isinf(eb->objective));
  EXPECT_EQ(eb->message, evaluation(0, false).message);
  EXPECT_FALSE(c.find({0.1, 0.9500000000000001}));  // the key is the exact values
}

TEST(EvaluationCache, TheWriterAddsEachEvaluationOnce) {
  CacheFile f;
  const std::vector<double> a{0.1, 0.9}, b{0.2, 0.9}, c{0.3, 0.9};
  {
    CacheWriter w(f.path.string(), f.read(), trajectory_context());
    w.add_item(evaluations_to_bytes({{a, evaluation(1)}, {b, evaluation(2)}, {a, evaluation(1)}}));
    EXPECT_EQ(w.added(), 2u);
  }
  const EvaluationCache held = f.read();
  CacheWriter w(f.path.string(), held, trajectory_context());
  w.add_item(evaluations_to_bytes({{b, evaluation(2)}, {c, evaluation(3)}}));  // b is in the file already
  w.add_item(evaluations_to_bytes({{a, evaluation(1)}}));                     // and a
  EXPECT_EQ(w.added(), 1u);
  EXPECT_EQ(f.read().size(), 3u);
  std::ifstream in(f.path);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) ++lines;
  EXPECT_EQ(lines, 3);  // the header once, and two items
}

TEST(EvaluationCache, AHeaderForAnotherCalibrationIsRefusedNamingWhatDiffers) {
  CacheFile f;
  CacheWriter(f.path.string(), f.read(), trajectory_context()).add_item(evaluations_to_bytes({{{0.1, 0.9}, evaluation(1)}}));
  EXPECT_EQ(f.read().size(), 1u);
  auto changed = [](auto&& change) {
    CacheContext c = trajectory_context();
    change(c);
    return c;
  };
  const std::pair<CacheContext, std::string> cases[] = {
      {changed([](CacheContext& c) { c.imcol_version = "9.9.10"; }), "not the same imcol's version: 9.9.9"},
      {changed([](CacheContext& c) { c.scene_text += "# a comment\n"; }), "not the same scene file's text"},
      {changed([](CacheContext& c) { c.overrides.push_back("contact.e_dry=0.9"); }), "not the same overrides"},
      {changed([](CacheContext& c) { std::swap(c.fit_keys[0], c.fit_keys[1]); }), "not the same fitted keys"},
      {changed([](CacheContext& c) { c.measurement_text += "0.1,0.001\n"; }), "not the same measurement file's text"},
      {changed([](CacheContext& c) { c.window[1] = -0.005; }), "not the same trajectory window"},
  };
  for (const auto& [context, what] : cases) {
    const std::string err = refusal(f, context);
    EXPECT_EQ(err.rfind(f.path.string() + ":1: key '--cache': made for another calibration (" + what, 0), 0u) << err;
  }
  std::ofstream(f.path) << "t,z1\n0,0\n";
  EXPECT_NE(refusal(f, trajectory_context()).find(":1: key '--cache': not an imcol calibrate cache"), std::string::npos);
}

TEST(EvaluationCache, ALastLineCutShortIsLeftOutAndADamagedOneIsAnError) {
  CacheFile f;
  {
    CacheWriter w(f.path.string(), f.read(), trajectory_context());
    for (int k = 0; k < 3; ++k) w.add_item(evaluations_to_bytes({{{0.1 * k, 0.9}, evaluation(k)}}));
  }
  const std::string whole = slurp(f.path);
  std::ofstream(f.path, std::ios::trunc) << whole.substr(0, whole.size() - 10);  // a kill inside the last item's write
  const EvaluationCache cut = f.read();
  EXPECT_EQ(cut.size(), 2u);
  EXPECT_TRUE(cut.cut_short());
  {
    CacheWriter w(f.path.string(), cut, trajectory_context());  // drops the cut line
    w.add_item(evaluations_to_bytes({{{0.2, 0.9}, evaluation(2)}}));
    EXPECT_EQ(w.added(), 1u);
  }
  EXPECT_EQ(slurp(f.path), whole);  // as if never killed
  EXPECT_EQ(f.read().size(), 3u);

  // A whole last line without its newline counts; the writer starts a line of its own after it.
  std::ofstream(f.path, std::ios::trunc) << whole.substr(0, whole.size() - 1);
  const EvaluationCache unended = f.read();
  EXPECT_EQ(unended.size(), 3u);
  EXPECT_FALSE(unended.cut_short());
  CacheWriter(f.path.string(), unended, trajectory_context()).add_item(evaluations_to_bytes({{{0.3, 0.9}, evaluation(3)}}));
  EXPECT_EQ(f.read().size(), 4u);

  // A line that does not read, not the last: damage.
  std::ofstream(f.path, std::ios::trunc) << whole.substr(0, whole.size() - 10) << "\n" << whole.substr(whole.find('\n') + 1);
  const std::string err = refusal(f, trajectory_context());
  EXPECT_NE(err.find(f.path.string() + ":4: key '--cache': not a line of evaluations"), std::string::npos) << err;
}

TEST(EvaluationCache, OneWriterAtATimeAndNotAfterTheFileChanged) {
  CacheFile f;
  const EvaluationCache none = f.read();
  auto writer_error = [&](const EvaluationCache& read) {
    try {
      CacheWriter w(f.path.string(), read, trajectory_context());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  {
    CacheWriter first(f.path.string(), none, trajectory_context());
    first.add_item(evaluations_to_bytes({{{0.1, 0.9}, evaluation(1)}}));
    const EvaluationCache now = f.read();
    EXPECT_NE(writer_error(now).find("key '--cache': '" + f.path.string() + "' is in use by another imcol calibrate"), std::string::npos);
  }
  const EvaluationCache read = f.read();
  CacheWriter(f.path.string(), read, trajectory_context()).add_item(evaluations_to_bytes({{{0.2, 0.9}, evaluation(2)}}));
  EXPECT_NE(writer_error(read).find("changed while it was read"), std::string::npos);  // `read` lacks the line just added
  EXPECT_EQ(writer_error(f.read()), "");
  EXPECT_EQ(f.read().size(), 2u);
}

TEST(EvaluationCache, ADamagedEvaluationIsRefusedNamingItsLineAndField) {
  // A line that reads as JSON but that no writer wrote: refused, not taken (an objective of "x", null or -5 would
  // otherwise be taken as a fit), nor skipped (values of another count than the fitted keys would never be found).
  CacheFile f;
  CacheWriter(f.path.string(), f.read(), trajectory_context()).add_item(evaluations_to_bytes({{{0.1, 0.9}, evaluation(1)}}));
  const std::string good = slurp(f.path);
  const std::string header = good.substr(0, good.find('\n') + 1), item = good.substr(header.size());  // each with its newline
  auto with = [&](const std::string& from, const std::string& to) {
    std::string line = item;
    const auto k = line.find(from);
    EXPECT_NE(k, std::string::npos) << from;
    return line.replace(k, from.size(), to);
  };
  const std::pair<std::string, std::string> cases[] = {
      {with("\"objective\":1.0", "\"objective\":\"x\""), "evaluation 1: 'objective' must be a finite number >= 0 in an evaluation that succeeded (got \"x\")"},
      {with("\"objective\":1.0", "\"objective\":null"), "evaluation 1: 'objective' must be a finite number >= 0 in an evaluation that succeeded (got null)"},
      {with("\"objective\":1.0", "\"objective\":-5"), "evaluation 1: 'objective' must be a finite number >= 0 in an evaluation that succeeded (got -5)"},
      {with("\"rms\":1.0", "\"rms\":-1.0"), "evaluation 1: 'rms' must be a finite number >= 0"},
      {with("\"ok\":true", "\"ok\":1"), "evaluation 1: 'ok' must be true or false (got 1)"},
      {with("\"values\":[0.1,0.9]", "\"values\":[0.1,null]"), "evaluation 1: 'values' must be a list of finite parameter values"},
      {with(",\"message\":\"\"", ""), "evaluation 1: 'message' must be given (got nothing)"},
      {"{}\n", "not a line of evaluations (not a list of evaluations)"},
      {with("\"values\":[0.1,0.9]", "\"values\":[0.1]"), "evaluation 1 has 1 parameter values for 2 fitted keys"},
      {with("\"values\":[0.1,0.9]", "\"values\":[0.1,0.9,0.5]"), "evaluation 1 has 3 parameter values for 2 fitted keys"},
  };
  for (const auto& [line, problem] : cases) {
    // The damaged line second of three, and as the last line without its newline: JSON, so not a write cut short.
    for (const std::string& text : {header + line + item, header + line.substr(0, line.size() - 1)}) {
      std::ofstream(f.path, std::ios::trunc) << text;
      const std::string err = refusal(f, trajectory_context());
      EXPECT_EQ(err.rfind(f.path.string() + ":2: key '--cache': ", 0), 0u) << err;
      EXPECT_NE(err.find(problem), std::string::npos) << "expected: " << problem << "\nin: " << err;
      EXPECT_NE(err.find("the file is damaged: remove it, or give another --cache"), std::string::npos) << err;
    }
  }
  // A failed evaluation has no objective: null, as written, and it stays failed.
  std::ofstream(f.path, std::ios::trunc) << header << with("\"ok\":true", "\"ok\":false");
  const auto failed = f.read().find({0.1, 0.9});
  ASSERT_TRUE(failed);
  EXPECT_FALSE(failed->ok);
  EXPECT_TRUE(std::isinf(failed->objective));
}

TEST(EvaluationCache, AWriterRefusesAFileThatIsNotRegular) {
  // /dev/null reads as an empty file; appending to it would lose every evaluation.
  const std::string err = [] {
    try {
      CacheWriter w("/dev/null", EvaluationCache(), trajectory_context());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_EQ(err, "/dev/null: key '--cache': is not a regular file (a cache is a text file)");
}
