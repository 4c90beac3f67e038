// SPDX-License-Identifier: BSD-3-Clause
#include "core/materials.hpp"

#include <sstream>
#include <vector>

#include "core/errors.hpp"

namespace imcol {

namespace {
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

/// A cell that must hold a number.
double number(const std::string& cell, const std::string& where, const std::string& col) {
  if (auto v = csv_number(cell, where, col)) return *v;
  throw InputError(where, col, "not a number: ''");
}
}  // namespace

MaterialTable MaterialTable::load(const std::string& path) {
  MaterialTable table;
  read_csv_rows(path, "material table", "material,", [&](const std::string& where, const std::string& line) {
    auto c = split(line);
    if (c.size() < 4) throw InputError(where, "", "expected at least 4 columns");
    Material m;
    m.name = c[0];
    m.density = number(c[1], where, "density_kg_m3");
    m.youngs_modulus = number(c[2], where, "youngs_modulus_Pa");
    m.poisson_ratio = number(c[3], where, "poisson_ratio");
    if (c.size() > 4) m.e_dry = csv_number(c[4], where, "e_dry");
    if (c.size() > 5) m.roughness = csv_number(c[5], where, "roughness_m");
    table.by_name_[m.name] = m;
  });
  return table;
}

const MaterialTable& MaterialTable::builtin() {
  static const MaterialTable t = load(data_dir() + "/materials.csv");
  return t;
}

}  // namespace imcol
