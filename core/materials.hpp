// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Material database: data/materials.csv (SI units: kg/m^3, Pa, -, -, m).
#include <optional>
#include <string>

#include "core/data_dir.hpp"
#include "core/named_table.hpp"

namespace imcol {

struct Material {
  std::string name;
  double density = 0;          // kg/m^3
  double youngs_modulus = 0;   // Pa
  double poisson_ratio = 0;    // -
  std::optional<double> e_dry; // dry restitution against a hard target
  std::optional<double> roughness;  // m
};

class MaterialTable : public NamedTable<Material> {
 public:
  /// Reads a CSV with header material,density_kg_m3,youngs_modulus_Pa,poisson_ratio,e_dry,roughness_m.
  /// Lines starting with '#' are comments. Throws InputError naming file and line.
  static MaterialTable load(const std::string& path);
  /// The table shipped in data/materials.csv.
  static const MaterialTable& builtin();
};

}  // namespace imcol
