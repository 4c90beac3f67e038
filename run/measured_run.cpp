// SPDX-License-Identifier: BSD-3-Clause
#include "run/measured_run.hpp"

namespace imcol {

RunResult simulate_for_e(const Scene& scene) {
  Scene sc = scene;
  for (int attempt = 0;; ++attempt) {
    RunResult r = simulate(sc, false, Recording::kinematics);  // e needs no force columns
    if (attempt == 2 || !r.summary.t_end_too_short) return r;
    sc.solver.t_end *= 2;
  }
}

}  // namespace imcol
