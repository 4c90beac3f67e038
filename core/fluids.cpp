// SPDX-License-Identifier: BSD-3-Clause
#include "core/fluids.hpp"

#include <cmath>
#include <vector>

#include "core/errors.hpp"
#include "core/materials.hpp"

namespace imcol {

namespace fluid_correlations {

double water_density_kell(double t) {
  const double num = 999.83952 + t * (16.945176 + t * (-7.9870401e-3 + t * (-46.170461e-6 + t * (105.56302e-9 + t * -280.54253e-12))));
  return num / (1 + 16.879850e-3 * t);
}

double water_viscosity_iapws(double t_C, double density) {
  constexpr double kTc = 647.096, kRhoc = 322.0, kMuStar = 1e-6;  // K, kg/m^3, Pa s
  const double T = (t_C + 273.15) / kTc, rho = density / kRhoc;
  // mu_0: the dilute-gas term (Table 1 of the release).
  const double mu0 = 100 * std::sqrt(T) / (1.67752 + 2.20462 / T + 0.6366564 / (T * T) - 0.241605 / (T * T * T));
  // mu_1: H[i][j] multiplies (1/T - 1)^i (rho - 1)^j (Table 2).
  static constexpr double H[6][7] = {
      {5.20094e-1, 2.22531e-1, -2.81378e-1, 1.61913e-1, -3.25372e-2, 0, 0},
      {8.50895e-2, 9.99115e-1, -9.06851e-1, 2.57399e-1, 0, 0, 0},
      {-1.08374, 1.88797, -7.72479e-1, 0, 0, 0, 0},
      {-2.89555e-1, 1.26613, -4.89837e-1, 0, 6.98452e-2, 0, -4.35673e-3},
      {0, 0, -2.57040e-1, 0, 0, 8.72102e-3, 0},
      {0, 1.20573e-1, 0, 0, 0, 0, -5.93264e-4}};
  double sum = 0, ti = 1;
  for (int i = 0; i < 6; ++i, ti *= 1 / T - 1) {
    double inner = 0, rj = 1;
    for (int j = 0; j < 7; ++j, rj *= rho - 1) inner += H[i][j] * rj;
    sum += ti * inner;
  }
  return kMuStar * mu0 * std::exp(rho * sum);
}

double glycerol_water_viscosity_cheng(double w, double t) {
  const double mu_w = 1.790e-3 * std::exp((-1230 - t) * t / (36100 + 360 * t));  // Pa s
  const double mu_g = 12100e-3 * std::exp((-1233 + t) * t / (9900 + 70 * t));
  const double a = 0.705 - 0.0017 * t;
  const double b = (4.9 + 0.036 * t) * std::pow(a, 2.5);
  const double denom = a * w + b * (1 - w);
  const double alpha = 1 - w + (denom > 0 ? a * b * w * (1 - w) / denom : 0.0);
  return std::pow(mu_w, alpha) * std::pow(mu_g, 1 - alpha);
}

double glycerol_water_density_volk(double w, double t) {
  const double rho_g = 1273 - 0.612 * t;
  const double rho_w = 1000 * (1 - std::pow(std::abs(t - 3.98) / 615, 1.71));
  const double ideal = rho_g * rho_w / (w * rho_w + (1 - w) * rho_g);  // volumes add: 1/rho = w/rho_g + (1-w)/rho_w
  const double A = 1.78e-6 * t * t - 1.82e-4 * t + 1.41e-2;
  const double kappa = 1 + A * std::pow(std::sin(std::pow(w, 1.31) * M_PI), 0.81);
  return kappa * ideal;
}

}  // namespace fluid_correlations

namespace {

namespace fc = fluid_correlations;

struct Correlation {
  const char* id;
  const char* property;  // density | viscosity
  bool uses_w;
  double (*fn)(double w, double t);
};

const Correlation kCorrelations[] = {
    {"kell-1975", "density", false, [](double, double t) { return fc::water_density_kell(t); }},
    {"iapws-2008", "viscosity", false, [](double, double t) { return fc::water_viscosity_iapws(t, fc::water_density_kell(t)); }},
    {"volk-kahler-2018", "density", true, fc::glycerol_water_density_volk},
    {"cheng-2008", "viscosity", true, fc::glycerol_water_viscosity_cheng},
};

const Correlation* find_correlation(const std::string& id) {
  for (const auto& c : kCorrelations)
    if (id == c.id) return &c;
  return nullptr;
}

/// The first `n` comma-separated cells, then the rest of the line as one cell.
std::vector<std::string> cells(const std::string& line, std::size_t n) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while (out.size() < n) {
    const auto comma = line.find(',', at);
    if (comma == std::string::npos) break;
    out.push_back(line.substr(at, comma - at));
    at = comma + 1;
  }
  out.push_back(line.substr(at));
  return out;
}

}  // namespace

double FluidProperty::at(double w, double t_C) const {
  if (value) return *value;
  return find_correlation(correlation)->fn(w, t_C);
}

FluidTable FluidTable::load(const std::string& path) {
  FluidTable table;
  read_csv_rows(path, "fluid table", "fluid,property,value,correlation,t_min_C,t_max_C,w_min,w_max,source",
                [&](const std::string& where, const std::string& line) {
    const auto c = cells(line, 8);
    if (c.size() != 9) throw InputError(where, "", "expected 9 columns");
    FluidEntry& e = table.by_name_[c[0]];
    e.name = c[0];
    if (c[1] != "density" && c[1] != "viscosity") throw InputError(where, "property", "expected density or viscosity, got '" + c[1] + "'");
    FluidProperty& p = c[1] == "density" ? e.density : e.viscosity;
    if (!p.source.empty()) throw InputError(where, "property", "the " + c[1] + " of '" + c[0] + "' is given twice");
    p.value = csv_number(c[2], where, "value");
    p.correlation = c[3];
    p.source = c[8];
    if (p.source.empty()) throw InputError(where, "source", "missing");
    if (p.value.has_value() == !p.correlation.empty()) throw InputError(where, "value", "give either a value or a correlation");
    if (p.value && !(*p.value > 0)) throw InputError(where, "value", "must be > 0");
    if (!p.correlation.empty()) {
      const Correlation* k = find_correlation(p.correlation);
      if (!k) throw InputError(where, "correlation", "unknown correlation '" + p.correlation + "'");
      if (c[1] != k->property) throw InputError(where, "correlation", "'" + p.correlation + "' gives the " + k->property);
      const auto t_min = csv_number(c[4], where, "t_min_C"), t_max = csv_number(c[5], where, "t_max_C");
      if (!t_min || !t_max || !(*t_min < *t_max)) throw InputError(where, "t_min_C", "a correlation needs t_min_C < t_max_C");
      p.t_min = *t_min;
      p.t_max = *t_max;
      p.w_min = csv_number(c[6], where, "w_min");
      p.w_max = csv_number(c[7], where, "w_max");
      if (k->uses_w != (p.w_min && p.w_max)) throw InputError(where, "w_min", "'" + p.correlation + (k->uses_w ? "' needs" : "' takes no") + " w_min and w_max");
    }
  });
  for (const auto& [name, e] : table.by_name_)
    if (e.density.source.empty() || e.viscosity.source.empty())
      throw InputError(path, "", "fluid '" + name + "' needs both a density and a viscosity row");
  return table;
}

const FluidTable& FluidTable::builtin() {
  static const FluidTable t = load(data_dir() + "/fluids.csv");
  return t;
}

}  // namespace imcol
