// SPDX-License-Identifier: BSD-3-Clause
#include "study/validate_speed.hpp"

#include <cmath>
#include <string>

#include "core/number_text.hpp"

namespace imcol::study {

namespace validate_speed_impl {  // named: study/ is built in unity batches

/// A key's value: 12 significant digits.
std::string number_value(double v) {
  std::string s;
  append_number(s, v, 12);
  return s;
}

}  // namespace validate_speed_impl

std::vector<Override> speed_overrides(const Scene& sc, double scale) {
  std::vector<Override> ov;
  for (std::size_t i = 0; i < sc.spheres.size(); ++i)
    ov.push_back({"sphere[" + std::to_string(i) + "].velocity", validate_speed_impl::number_value(scale * sc.spheres[i].velocity)});
  if (sc.spheres.size() == 2) {
    const auto& a = sc.spheres[0];
    const auto& b = sc.spheres[1];
    const double touch = 0.5 * (a.diameter + b.diameter);
    ov.push_back({"sphere[1].position", validate_speed_impl::number_value(a.position + touch + scale * (b.position - a.position - touch))});
  }
  return ov;
}

double approach_speed(const Scene& sc) {
  return sc.spheres.size() == 2 ? sc.spheres[0].velocity - sc.spheres[1].velocity : sc.spheres.at(0).velocity;
}

double scale_to_St(double St_1, double St_target, const std::function<std::optional<double>(double)>& St_at, double tol) {
  const double s1 = St_target / St_1;
  const std::optional<double> St_s1 = St_at(s1);
  if (!St_s1 || std::abs(*St_s1 - St_target) <= tol * St_target || *St_s1 == St_1) return s1;
  const double s2 = s1 + (St_target - *St_s1) * (s1 - 1) / (*St_s1 - St_1);  // secant through (1, St_1), (s1, St(s1))
  if (!(std::isfinite(s2) && s2 > 0)) return s1;
  St_at(s2);
  return s2;
}

}  // namespace imcol::study
