// SPDX-License-Identifier: BSD-3-Clause
// Bad input to the calibration engine: the measurement reader and --fit, one test each; every one an InputError
// naming the place (FILE:LINE, or the command line) and the key.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "calibrate/fit_parameter.hpp"
#include "calibrate/measurement.hpp"
#include "calibrate/objective.hpp"
#include "core/materials.hpp"
#include "core/toml_reader.hpp"
#include "tests/calibrate_runner.hpp"
#include "tests/input_error.hpp"

using namespace imcol;
using namespace imcol::calib;
using imcol::test::gg3462;
using imcol::test::input_error_of;
namespace fs = std::filesystem;

namespace {

/// A folder of this process's own, removed when the tests end.
struct ScratchDir {
  fs::path path = fs::temp_directory_path() / ("imcol_calibrate_inputs_" + std::to_string(::getpid()));
  ScratchDir() { fs::create_directories(path); }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

/// A measurement file with `text` in the scratch folder.
std::string file_with(const std::string& name, const std::string& text) {
  static const ScratchDir scratch;
  const fs::path& dir = scratch.path;
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

std::string read_error(const std::string& name, const std::string& text) {
  const std::string path = file_with(name, text);
  return input_error_of([&] { (void)read_measurement(path); });
}

const std::string kGood = "# t in s, z in m\nt,z1,z2\n0,0,0.016\n0.001,1e-4,0.016\n0.002,2e-4,0.016\n0.003,3e-4,0.016\n0.004,4e-4,0.016\n";

std::string fit_error(const std::string& text) {
  return input_error_of([&] { (void)parse_fit_parameter(text, gg3462()); });
}

}  // namespace

TEST(CalibrateInputs, AGoodTrajectoryAndTableAreRead) {
  const auto m = read_measurement(file_with("good.csv", kGood));
  const auto& tr = std::get<MeasuredTrajectory>(m);
  EXPECT_EQ(tr.t.size(), 5u);
  EXPECT_EQ(tr.columns, (std::vector<std::string>{"z1", "z2"}));
  EXPECT_EQ(tr.lines.front(), 3);
  EXPECT_EQ(tr.z[0][4], 4e-4);
  const auto tb = std::get<MeasuredTable>(read_measurement(file_with("table.csv", "sphere[0].velocity, e\n0.1, 0.8\n0.2,0.85\r\n")));
  EXPECT_EQ(tb.keys, std::vector<std::string>{"sphere[0].velocity"});
  EXPECT_EQ(tb.e, (std::vector<double>{0.8, 0.85}));
  EXPECT_EQ(tb.lines, (std::vector<int>{2, 3}));
}

TEST(CalibrateInputs, AMissingFile) {
  EXPECT_NE(input_error_of([] { (void)read_measurement("/nonexistent/measured.csv"); }).find("/nonexistent/measured.csv"), std::string::npos);
}

TEST(CalibrateInputs, UnsortedTimes) {
  const std::string e = read_error("unsorted.csv", "t,z1\n0,0\n0.002,1\n0.001,2\n0.003,3\n0.004,4\n");
  EXPECT_NE(e.find("unsorted.csv:4"), std::string::npos) << e;
  EXPECT_NE(e.find("key 't'"), std::string::npos) << e;
  EXPECT_NE(e.find("increase strictly"), std::string::npos) << e;
}

TEST(CalibrateInputs, RepeatedTimes) {
  const std::string e = read_error("repeated.csv", "t,z1\n0,0\n0.001,1\n0.001,2\n0.003,3\n0.004,4\n");
  EXPECT_NE(e.find("repeated.csv:4"), std::string::npos) << e;
  EXPECT_NE(e.find("increase strictly"), std::string::npos) << e;
}

TEST(CalibrateInputs, NaNCell) {
  const std::string e = read_error("nan.csv", "t,z1\n0,0\n0.001,nan\n0.002,2\n0.003,3\n0.004,4\n");
  EXPECT_NE(e.find("nan.csv:3"), std::string::npos) << e;
  EXPECT_NE(e.find("key 'z1'"), std::string::npos) << e;
  EXPECT_NE(e.find("not a finite number"), std::string::npos) << e;
}

TEST(CalibrateInputs, InfiniteCell) {
  const std::string e = read_error("inf.csv", "t,z1\n0,0\n0.001,1\ninf,2\n");
  EXPECT_NE(e.find("inf.csv:4"), std::string::npos) << e;
  EXPECT_NE(e.find("key 't'"), std::string::npos) << e;
}

TEST(CalibrateInputs, EmptyCell) {
  const std::string e = read_error("empty.csv", "t,z1,z2\n0,0,1\n0.001,,1\n");
  EXPECT_NE(e.find("empty.csv:3"), std::string::npos) << e;
  EXPECT_NE(e.find("key 'z1'"), std::string::npos) << e;
  EXPECT_NE(e.find("empty cell"), std::string::npos) << e;
}

TEST(CalibrateInputs, NotANumber) {
  const std::string e = read_error("word.csv", "t,z1\n0,0\n0.001,1mm\n");
  EXPECT_NE(e.find("word.csv:3"), std::string::npos) << e;
  EXPECT_NE(e.find("not a number: '1mm'"), std::string::npos) << e;
}

TEST(CalibrateInputs, MissingCells) {
  const std::string e = read_error("short_row.csv", "t,z1,z2\n0,0,1\n0.001,1\n");
  EXPECT_NE(e.find("short_row.csv:3"), std::string::npos) << e;
  EXPECT_NE(e.find("2 cells"), std::string::npos) << e;
}

TEST(CalibrateInputs, TooFewTrajectoryRows) {
  const std::string e = read_error("four.csv", "t,z1\n0,0\n0.001,1\n0.002,2\n0.003,3\n");
  EXPECT_NE(e.find("four.csv"), std::string::npos) << e;
  EXPECT_NE(e.find("4 rows"), std::string::npos) << e;
  EXPECT_NE(e.find("at least 5"), std::string::npos) << e;
}

TEST(CalibrateInputs, TooFewTableRows) {
  const std::string e = read_error("one_row.csv", "sphere[0].velocity,e\n0.1,0.8\n");
  EXPECT_NE(e.find("1 rows"), std::string::npos) << e;
  EXPECT_NE(e.find("at least 2"), std::string::npos) << e;
}

TEST(CalibrateInputs, NoHeader) {
  const std::string e = read_error("comments.csv", "# nothing\n\n");
  EXPECT_NE(e.find("comments.csv"), std::string::npos) << e;
  EXPECT_NE(e.find("no header"), std::string::npos) << e;
}

TEST(CalibrateInputs, UnknownTrajectoryColumn) {
  const std::string e = read_error("u1.csv", "t,z1,u1\n0,0,1\n");
  EXPECT_NE(e.find("u1.csv:1"), std::string::npos) << e;
  EXPECT_NE(e.find("key 'u1'"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown column"), std::string::npos) << e;
}

TEST(CalibrateInputs, UnknownKindOfMeasurement) {
  const std::string e = read_error("kind.csv", "time,z1\n0,0\n");
  EXPECT_NE(e.find("kind.csv:1"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown kind"), std::string::npos) << e;
}

TEST(CalibrateInputs, ColumnGivenTwice) {
  const std::string e = read_error("twice.csv", "t,z1,z1\n0,0,0\n");
  EXPECT_NE(e.find("key 'z1'"), std::string::npos) << e;
  EXPECT_NE(e.find("twice"), std::string::npos) << e;
}

TEST(CalibrateInputs, EAboveOne) {
  const std::string e = read_error("e_high.csv", "sphere[0].velocity,e\n0.1,0.8\n0.2,1.2\n");
  EXPECT_NE(e.find("e_high.csv:3"), std::string::npos) << e;
  EXPECT_NE(e.find("key 'e'"), std::string::npos) << e;
  EXPECT_NE(e.find("outside [0, 1]"), std::string::npos) << e;
}

TEST(CalibrateInputs, ENegative) {
  const std::string e = read_error("e_low.csv", "sphere[0].velocity,e\n0.1,-0.1\n0.2,0.8\n");
  EXPECT_NE(e.find("e_low.csv:2"), std::string::npos) << e;
  EXPECT_NE(e.find("outside [0, 1]"), std::string::npos) << e;
}

TEST(CalibrateInputs, ATableKeyThatIsNotASceneKey) {
  const std::string path = file_with("colour.csv", "sphere[0].colour,e\n1,0.8\n2,0.85\n");
  const auto tb = std::get<MeasuredTable>(read_measurement(path));
  const std::string e = input_error_of([&] { check_table_keys(tb, gg3462(), {}); });
  EXPECT_NE(e.find("colour.csv:2"), std::string::npos) << e;
  EXPECT_NE(e.find("sphere[0].colour"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
}

TEST(CalibrateInputs, ATableKeyThatIsNotNumeric) {
  const std::string path = file_with("law.csv", "contact.law,e\n1,0.8\n2,0.85\n");
  const auto tb = std::get<MeasuredTable>(read_measurement(path));
  const std::string e = input_error_of([&] { check_table_keys(tb, gg3462(), {}); });
  EXPECT_NE(e.find("law.csv:2"), std::string::npos) << e;
  EXPECT_NE(e.find("contact.law"), std::string::npos) << e;
}

TEST(CalibrateInputs, ATableValueTheSceneRefuses) {
  const std::string path = file_with("neg_d.csv", "sphere[0].diameter,e\n0.0127,0.8\n-0.01,0.85\n");
  const auto tb = std::get<MeasuredTable>(read_measurement(path));
  const std::string e = input_error_of([&] { check_table_keys(tb, gg3462(), {}); });
  EXPECT_NE(e.find("neg_d.csv:3"), std::string::npos) << e;
  EXPECT_NE(e.find("sphere[0].diameter"), std::string::npos) << e;
}

TEST(CalibrateInputs, FitParsesBoundsAndScale) {
  const FitParameter p = parse_fit_parameter("contact.delta_ss=0.005:0.05", gg3462());
  EXPECT_EQ(p.key, "contact.delta_ss");
  EXPECT_EQ(p.lo, 0.005);
  EXPECT_EQ(p.hi, 0.05);
  EXPECT_EQ(p.scale, Scale::linear);
  EXPECT_EQ(parse_fit_parameter("fluid.viscosity=1e-3:1e-2:log", gg3462()).scale, Scale::log);
}

TEST(CalibrateInputs, FitAStringKey) {
  const std::string e = fit_error("contact.law=0.1:0.2");
  EXPECT_NE(e.find("command line"), std::string::npos) << e;
  EXPECT_NE(e.find("key '--fit'"), std::string::npos) << e;
  EXPECT_NE(e.find("contact.law"), std::string::npos) << e;
  EXPECT_NE(e.find("the scene refuses contact.law = 0.1 (fit only numeric keys"), std::string::npos) << e;
  EXPECT_NE(e.find("must be a string"), std::string::npos) << e;
}

TEST(CalibrateInputs, FitAnUnknownKey) {
  const std::string e = fit_error("contact.delta_sss=0.005:0.05");
  EXPECT_NE(e.find("key '--fit'"), std::string::npos) << e;
  EXPECT_NE(e.find("contact.delta_sss"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
}

TEST(CalibrateInputs, FitABoundThatIsNotANumber) {
  const std::string e = fit_error("contact.delta_ss=small:0.05");
  EXPECT_NE(e.find("key '--fit'"), std::string::npos) << e;
  EXPECT_NE(e.find("contact.delta_ss"), std::string::npos) << e;
  EXPECT_NE(e.find("'small' is not a number"), std::string::npos) << e;
}

TEST(CalibrateInputs, FitAnInfiniteBound) {
  const std::string e = fit_error("contact.delta_ss=0.005:inf");
  EXPECT_NE(e.find("not finite"), std::string::npos) << e;
}

TEST(CalibrateInputs, FitBoundsReversed) {
  const std::string e = fit_error("contact.delta_ss=0.05:0.005");
  EXPECT_NE(e.find("key '--fit'"), std::string::npos) << e;
  EXPECT_NE(e.find("contact.delta_ss"), std::string::npos) << e;
  EXPECT_NE(e.find("reversed"), std::string::npos) << e;
}

TEST(CalibrateInputs, FitEqualBounds) {
  EXPECT_NE(fit_error("contact.delta_ss=0.02:0.02").find("reversed or empty"), std::string::npos);
}

TEST(CalibrateInputs, FitLogScaleFromZero) {
  const std::string e = fit_error("contact.delta_ss=0:0.05:log");
  EXPECT_NE(e.find("log scale needs LO > 0"), std::string::npos) << e;
}

TEST(CalibrateInputs, FitUnknownScale) {
  EXPECT_NE(fit_error("contact.delta_ss=0.005:0.05:lin").find("unknown scale 'lin'"), std::string::npos);
}

TEST(CalibrateInputs, FitWithoutBounds) {
  EXPECT_NE(fit_error("contact.delta_ss").find("expected KEY=LO:HI"), std::string::npos);
  EXPECT_NE(fit_error("contact.delta_ss=0.005").find("expected LO:HI"), std::string::npos);
}

TEST(CalibrateInputs, FitABoundTheSceneRefuses) {
  const std::string e = fit_error("sphere[0].diameter=-0.01:0.02");
  EXPECT_NE(e.find("key '--fit'"), std::string::npos) << e;
  EXPECT_NE(e.find("sphere[0].diameter"), std::string::npos) << e;
  EXPECT_NE(e.find("-0.01"), std::string::npos) << e;
}

TEST(CalibrateInputs, TrajectoryWindowWithTooFewSamples) {
  const auto tr = std::get<MeasuredTrajectory>(read_measurement(file_with("window.csv", kGood)));
  const Scene sc = load_scene(gg3462());
  const std::string e = input_error_of([&] { (void)trajectory_window(tr, sc, -0.0005, 0.0005, std::nullopt); });
  EXPECT_NE(e.find("key '--window'"), std::string::npos) << e;
  EXPECT_NE(e.find("at least 5"), std::string::npos) << e;
}

TEST(CalibrateInputs, TrajectoryZ2ForASceneWithOneSphere) {
  // A wall scene's run has no z2: the column is refused before anything runs, naming the header line.
  const auto tr = std::get<MeasuredTrajectory>(read_measurement(file_with("z2_wall.csv", kGood)));
  const Scene sc = load_scene(data_dir() + "/scenes/bouncing_steel.toml");
  ASSERT_FALSE(sc.two_spheres());
  const std::string e = input_error_of([&] { (void)trajectory_window(tr, sc, std::nullopt, std::nullopt, std::nullopt); });
  EXPECT_NE(e.find("z2_wall.csv:2: key 'z2'"), std::string::npos) << e;
  EXPECT_NE(e.find("one sphere"), std::string::npos) << e;
}

TEST(CalibrateInputs, WhatIsNotARegularFileIsRefusedBeforeItIsOpened) {
  // A directory, a device that never ends, a FIFO without a writer (opening it would wait for ever): each refused at
  // once, naming the file.
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path dir = fs::path(file_with("probe.csv", "")).parent_path();
  std::string e = input_error_of([&] { (void)read_measurement(dir.string()); });
  EXPECT_EQ(e, dir.string() + ": is a directory, not a measurement file") << e;
  e = input_error_of([] { (void)read_measurement("/dev/zero"); });
  EXPECT_EQ(e, "/dev/zero: is not a regular file (a measurement is a CSV text file)") << e;
  const fs::path fifo = dir / "fifo.csv";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  e = input_error_of([&] { (void)read_measurement(fifo.string()); });
  EXPECT_EQ(e, fifo.string() + ": is not a regular file (a measurement is a CSV text file)") << e;
  // The scene reader is the same reader, with its own words and bound.
  e = input_error_of([&] { (void)read_scene_file(fifo.string()); });
  EXPECT_EQ(e, fifo.string() + ": is not a regular file (a scene is a TOML text file)") << e;
  e = input_error_of([&] { (void)read_scene_file(dir.string()); });
  EXPECT_EQ(e, dir.string() + ": is a directory, not a scene file") << e;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
}

TEST(CalibrateInputs, AMeasurementLargerThanItsBoundIsRefusedUnread) {
  // A sparse file one byte over 64 MiB: refused by its size, before a byte of it is read.
  const std::string path = file_with("huge.csv", "t,z1\n");
  fs::resize_file(path, kMaxMeasurementBytes + 1);
  const std::string e = input_error_of([&] { (void)read_measurement(path); });
  EXPECT_EQ(e, path + ": the measurement file has 67108865 bytes, more than the 64 MiB a measurement may have") << e;
  fs::remove(path);
  const std::string scene = file_with("huge.toml", "");
  fs::resize_file(scene, kMaxSceneBytes + 1);
  EXPECT_EQ(input_error_of([&] { (void)read_scene_file(scene); }),
            scene + ": the scene file has 1048577 bytes, more than the 1 MiB a scene may have");
  fs::remove(scene);
  EXPECT_EQ(byte_count_text(std::uintmax_t{256} << 20), "256 MiB");
  EXPECT_EQ(byte_count_text(1000), "1000 bytes");
}

TEST(CalibrateInputs, ALeadingByteOrderMarkIsSkipped) {
  // Spreadsheets save CSV as UTF-8 with a byte order mark: it is not part of the first column's name.
  const auto tr = std::get<MeasuredTrajectory>(read_measurement(file_with("bom.csv", "\xEF\xBB\xBF" + kGood.substr(kGood.find('\n') + 1))));
  EXPECT_EQ(tr.t.size(), 5u);
  EXPECT_EQ(tr.columns, (std::vector<std::string>{"z1", "z2"}));
  const auto tb = std::get<MeasuredTable>(read_measurement(file_with("bom_table.csv", "\xEF\xBB\xBFsphere[0].velocity,e\n0.1,0.8\n0.2,0.85\n")));
  EXPECT_EQ(tb.keys, std::vector<std::string>{"sphere[0].velocity"});
}

TEST(CalibrateInputs, OutOfRangeCellsAreRefusedWithLineAndColumn) {
  // 1e308 squared overflows: every evaluation would fail. Refused as the scene reader refuses such a number.
  std::string e = read_error("huge_z.csv", "t,z1\n0,0\n0.001,1e308\n0.002,2e-4\n0.003,3e-4\n0.004,4e-4\n");
  EXPECT_NE(e.find("huge_z.csv:3: key 'z1': out of range: 1e308"), std::string::npos) << e;
  e = read_error("tiny_t.csv", "t,z1\n1e-40,0\n0.001,1e-4\n0.002,2e-4\n0.003,3e-4\n0.004,4e-4\n");
  EXPECT_NE(e.find("tiny_t.csv:2: key 't': out of range"), std::string::npos) << e;
  e = read_error("huge_key.csv", "sphere[0].velocity,e\n1e31,0.8\n0.2,0.85\n");
  EXPECT_NE(e.find("huge_key.csv:2: key 'sphere[0].velocity': out of range"), std::string::npos) << e;
}

TEST(CalibrateInputs, FitAnIntegerKey) {
  const std::string e = fit_error("solver.max_steps=1000:100000");
  EXPECT_NE(e.find("command line: key '--fit': parameter 'solver.max_steps': integer keys cannot be fitted"), std::string::npos) << e;
}

TEST(CalibrateInputs, ARowWithoutACollisionFailsTheEvaluation) {
  // 1 us (4 us with t_end doubled twice) is far too short for gg3462's sphere to reach its target: e is not measured,
  // and the evaluation fails with that reason instead of counting e = 0.
  const std::string path = file_with("short.csv", "sphere[0].velocity,e\n0.08,0.845\n0.11,0.872\n");
  const auto tb = std::get<MeasuredTable>(read_measurement(path));
  const Evaluation ev = evaluate_table(tb, gg3462(), {{"solver.t_end", "1e-6"}});
  EXPECT_FALSE(ev.ok);
  EXPECT_TRUE(std::isinf(ev.objective));
  EXPECT_TRUE(std::isnan(ev.e_sim[0])) << ev.e_sim[0];
  EXPECT_EQ(ev.message.rfind(path + ":2: e not measured: no collision by t_end", 0), 0u) << ev.message;
  EXPECT_NE(ev.message.find("still so with solver.t_end raised to 4e-06 s"), std::string::npos) << ev.message;
}
