// SPDX-License-Identifier: BSD-3-Clause
// Layer 4: the shipped scenes against imcol's own stored results (data/reference/imcol_regression.csv).
// A failure means the model's output changed: if the change was deliberate, regenerate the file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "run/simulate.hpp"
#include "core/materials.hpp"

using namespace imcol;

namespace {
struct Row {
  std::string scene;
  std::optional<double> e, St, min_gap;
};

std::vector<Row> load() {
  std::ifstream in(data_dir() + "/reference/imcol_regression.csv");
  std::vector<Row> rows;
  std::string line;
  auto opt = [](const std::string& s) { return s.empty() ? std::nullopt : std::optional<double>(std::stod(s)); };
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("scene,", 0) == 0) continue;
    std::vector<std::string> c;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) c.push_back(x);
    c.resize(4);
    rows.push_back({c[0], opt(c[1]), opt(c[2]), opt(c[3])});
  }
  return rows;
}
}  // namespace

TEST(Regression, ShippedScenesReproduceStoredResults) {
  const auto rows = load();
  ASSERT_GE(rows.size(), 10u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.scene);
    const Scene sc = load_scene(data_dir() + "/scenes/" + row.scene + ".toml", {{"solver.rtol", "1e-10"}});
    const auto s = simulate(sc).summary_json;
    ASSERT_EQ(s["e"].is_null(), !row.e.has_value());
    if (row.e) {
      EXPECT_NEAR(s["e"].get<double>(), *row.e, 1e-6);
    }
    ASSERT_EQ(s["St"].is_null(), !row.St.has_value());
    if (row.St) {
      EXPECT_NEAR(s["St"].get<double>() / *row.St, 1.0, 1e-6);
    }
    if (row.min_gap) {
      EXPECT_NEAR(s["min_gap_m"].get<double>(), *row.min_gap, 1e-10 + 1e-3 * std::abs(*row.min_gap));
    }
  }
}
