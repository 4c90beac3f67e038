// SPDX-License-Identifier: BSD-3-Clause
#include "calibrate/local_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlopt.hpp>

namespace imcol::calib {

void local_search(const std::vector<double>& u0, int max_evals, double xtol, double step,
                  const std::function<double(const std::vector<double>&)>& f) {
  if (u0.empty() || max_evals <= 0) return;
  const std::size_t d = u0.size();
  struct State {
    const std::function<double(const std::vector<double>&)>* f;
    double worst = 0;  // the largest finite objective so far
    bool any = false;
  } state{&f};
  auto objective = [](const std::vector<double>& u, std::vector<double>&, void* data) -> double {
    auto& s = *static_cast<State*>(data);
    const double v = (*s.f)(u);
    if (std::isfinite(v)) {
      s.worst = s.any ? std::max(s.worst, v) : v;
      s.any = true;
      return v;
    }
    // A failed run: far above what the search has seen, finite so that the quadratic model stays defined.
    return s.any ? 10 * std::max(std::abs(s.worst), std::numeric_limits<double>::min()) : 1e30;
  };
  try {
    nlopt::opt o(nlopt::LN_BOBYQA, static_cast<unsigned>(d));
    o.set_lower_bounds(std::vector<double>(d, 0.0));
    o.set_upper_bounds(std::vector<double>(d, 1.0));
    o.set_min_objective(objective, &state);
    o.set_xtol_abs(xtol);
    o.set_maxeval(max_evals);
    o.set_initial_step(step);
    std::vector<double> u(u0);
    for (double& x : u) x = std::clamp(x, 0.0, 1.0);
    double fmin = 0;
    (void)o.optimize(u, fmin);
  } catch (const std::exception&) {
    // NLopt ends a search that cannot progress (round-off) with an exception: the evaluations made are kept.
  }
}

}  // namespace imcol::calib
