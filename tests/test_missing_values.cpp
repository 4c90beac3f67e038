// SPDX-License-Identifier: BSD-3-Clause
// Values that are not there, said as such: bench's e of a free sphere ("-" and the reason), history.csv's cells
// (empty, never "nan"), the DEM export of a dry scene (its points have e, only St is undefined), and "1 job".
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "core/materials.hpp"
#include "tests/imcol_process.hpp"

namespace fs = std::filesystem;
using imcol::test::Outcome;
using imcol::test::run_imcol;

namespace {

fs::path scratch_of(const std::string& name) { return fs::temp_directory_path() / ("imcol_missing_" + name + "_" + std::to_string(::getpid())); }

std::string scene_file(const std::string& name) { return imcol::data_dir() + "/scenes/" + name + ".toml"; }

}  // namespace

TEST(MissingValues, BenchOfAFreeSphereSaysWhyThereIsNoE) {
  const Outcome r = run_imcol("bench " + scene_file("rising_sphere") + " --rtols 1e-5,1e-6 --repeat 1 --set solver.t_end=0.05",
                              scratch_of("bench"));
  EXPECT_EQ(r.status, 0) << r.err;  // as imcol run: a run without e is a result
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("e not measured: a free sphere"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("median of 1 run;"), std::string::npos) << r.out;
  // A table row: rtol, then "-" for e and for its error.
  std::istringstream rows(r.out);
  std::string line;
  int dashed = 0;
  while (std::getline(rows, line))
    if (line.rfind("  1.00e-05", 0) == 0) {
      std::istringstream cells(line);
      std::string rtol, e, err;
      cells >> rtol >> e >> err;
      EXPECT_EQ(e, "-") << line;
      EXPECT_EQ(err, "-") << line;
      ++dashed;
    }
  EXPECT_EQ(dashed, 1) << r.out;
}

TEST(MissingValues, HistoryCsvHasEmptyCellsNotNan) {
  const fs::path out = scratch_of("history");
  fs::remove_all(out);
  const Outcome r = run_imcol("history " + scene_file("rising_sphere") + " --out " + out.string() +
                                  " --kernels basset --evaluators soe --no-plot --set solver.t_end=0.01",
                              scratch_of("history_run"));
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(out / "history.csv");
  std::string header, line;
  std::getline(in, header);
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_EQ(line.find("nan"), std::string::npos) << line;
    // The kernel "none" has no reference: its diff_from_reference and force_diff_rel are empty cells.
    if (line.rfind("none,", 0) == 0) {
      EXPECT_NE(line.find(",,"), std::string::npos) << line;
    }
  }
  EXPECT_EQ(rows, 2);
  fs::remove_all(out);
}

TEST(MissingValues, DemExportOfADrySceneCountsNoPointWithoutE) {
  const fs::path out = scratch_of("dem");
  fs::remove_all(out);
  const Outcome r = run_imcol("sweep " + scene_file("dry_steel_steel") + " --vary velocity --from 0.05 --to 0.2 --points 3 --jobs 1"
                                  " --export dem --no-plot --no-progress --out " + out.string(),
                              scratch_of("dem_run"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("failed or without e"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("dem: no fit: the scene has no liquid"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("e = 0.9700 at 3 of 3 points"), std::string::npos) << r.out;
  // The closing line counts threads in the singular for one.
  EXPECT_NE(r.out.find(" on 1 job:"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("1 jobs"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(imcol::test::slurp(out / "dem.json"));
  EXPECT_EQ(j["points"]["total"], 3);
  EXPECT_EQ(j["points"]["without_e"], 0);
  EXPECT_EQ(j["points"]["without_St"], 3);
  EXPECT_EQ(j["points"]["used_in_fits"], 0);
  EXPECT_TRUE(j["fits"].empty());
  EXPECT_EQ(j["liggghts"]["fit_error"], "the scene has no liquid: the viscous rule has no St");
  fs::remove_all(out);
}
