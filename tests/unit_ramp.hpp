// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// y' = 1 from y = 0, one component: the system the integrator driver's tests derive from (they add the roots, the stop
// time and the steps they test).
#include "core/system.hpp"

namespace imcol::test {

class UnitRamp : public DynamicalSystem {
 public:
  std::size_t size() const override { return 1; }
  std::vector<std::string> component_names() const override { return {"y"}; }
  std::vector<double> absolute_tolerances(double atol) const override { return {atol}; }
  void initial_state(std::span<double> y) const override { y[0] = 0; }
  void rhs(double, std::span<const double>, std::span<double> yd) override { yd[0] = 1; }
  void residual(double, std::span<const double>, std::span<const double> yp, std::span<double> r) override { r[0] = yp[0] - 1; }
};

}  // namespace imcol::test
