// SPDX-License-Identifier: BSD-3-Clause
// Bad input to the calibration engine: the measurement reader and --fit, one test each; every one an InputError
// naming the place (FILE:LINE, or the command line) and the key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "calibrate/fit_parameter.hpp"
#include "calibrate/measurement.hpp"
#include "calibrate/objective.hpp"
#include "core/materials.hpp"
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
