// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Liquids by name: data/fluids.csv gives each property (density kg/m^3, viscosity Pa s) as a fixed value or as a
// correlation in the temperature t (°C) and, for glycerol-water, the glycerol mass fraction w (-). The correlations'
// formulas are here; their ranges and sources are the table's.
#include <optional>
#include <string>

#include "core/named_table.hpp"

namespace imcol {

namespace fluid_correlations {
/// Kell (1975), J. Chem. Eng. Data 20:97, eq. (16): air-free water at 1 atm, kg/m^3 (0-150 °C).
double water_density_kell(double t_C);
/// IAPWS R12-08 (2008), Huber et al. (2009): mu = mu* mu_0(T) mu_1(T, rho) with mu_2 = 1, Pa s (T in K inside).
double water_viscosity_iapws(double t_C, double density);
/// Cheng (2008), Ind. Eng. Chem. Res. 47:3285: mu = mu_w^alpha mu_g^(1 - alpha) with his fits of mu_w(t), mu_g(t), Pa s.
double glycerol_water_viscosity_cheng(double w, double t_C);
/// Volk & Kähler (2018), Exp. Fluids 59:75: kappa(w, T) times the ideal mixture of pure glycerol and water, kg/m^3.
double glycerol_water_density_volk(double w, double t_C);
}  // namespace fluid_correlations

/// One property of a named liquid: a fixed value, or a correlation valid over a temperature (and mass-fraction) range.
struct FluidProperty {
  std::optional<double> value;  // SI
  std::string correlation;      // kell-1975 | iapws-2008 | cheng-2008 | volk-kahler-2018
  double t_min = 0, t_max = 0;  // °C (a correlation)
  std::optional<double> w_min, w_max;  // glycerol mass fraction (a correlation in w)
  std::string source;
  bool uses_mass_fraction() const { return w_min.has_value(); }
  /// The value at glycerol mass fraction `w` and temperature `t_C` (the caller checks the ranges).
  double at(double w, double t_C) const;
};

struct FluidEntry {
  std::string name;
  FluidProperty density, viscosity;
  bool takes_temperature() const { return !density.value || !viscosity.value; }
  bool takes_mass_fraction() const { return density.uses_mass_fraction() || viscosity.uses_mass_fraction(); }
};

class FluidTable : public NamedTable<FluidEntry> {
 public:
  /// Reads a CSV with header fluid,property,value,correlation,t_min_C,t_max_C,w_min,w_max,source ('#' lines are
  /// comments). Throws InputError naming the file and line.
  static FluidTable load(const std::string& path);
  /// The table shipped in data/fluids.csv.
  static const FluidTable& builtin();
};

}  // namespace imcol
