// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One bounded local search on the unit cube: NLopt's LN_BOBYQA (Powell's quadratic models, derivative-free; NLopt
// 2.7 takes it in one dimension too).
#include <functional>
#include <vector>

namespace imcol::calib {

/// Minimises f over [0, 1]^d from u0 (d = u0.size() >= 1): at most `max_evals` calls of f, stopping when a step
/// changes every coordinate by less than `xtol`; `step` is the first step's size. f may return +inf (a failed
/// evaluation): the search then sees a value well above every finite one so far. Deterministic; never throws.
void local_search(const std::vector<double>& u0, int max_evals, double xtol, double step,
                  const std::function<double(const std::vector<double>&)>& f);

}  // namespace imcol::calib
