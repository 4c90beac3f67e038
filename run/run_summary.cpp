// SPDX-License-Identifier: BSD-3-Clause
#include "run/run_summary.hpp"

namespace imcol {

const char* to_string(Configuration c) {
  switch (c) {
    case Configuration::free_sphere: return "free sphere";
    case Configuration::sphere_wall: return "sphere-wall";
    case Configuration::sphere_sphere: return "sphere-sphere";
  }
  return "";
}

std::optional<double> RunSummary::measure_e(EMeasure m) const {
  for (const auto& [k, v] : e_measures)
    if (k == m) return v;
  return std::nullopt;
}

std::optional<std::string> RunSummary::model_choice(const std::string& name) const {
  for (const auto& [k, v] : model)
    if (k == name) return v;
  return std::nullopt;
}

}  // namespace imcol
