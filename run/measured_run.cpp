// SPDX-License-Identifier: BSD-3-Clause
#include "run/measured_run.hpp"

#include <iomanip>
#include <sstream>

namespace imcol {

RunResult simulate_for_e(const Scene& scene) {
  Scene sc = scene;
  for (int attempt = 0;; ++attempt) {
    RunResult r = simulate(sc, false, Recording::kinematics);  // e needs no force columns
    if (attempt == 2 || !r.summary.t_end_too_short) return r;
    sc.solver.t_end *= 2;
  }
}

std::string e_missing_message(const RunSummary& s, double t_end_scene, double t_end_run) {
  std::string why = s.e_missing.value_or("e is undefined");
  const std::string hint = " (raise solver.t_end)";
  if (const auto k = why.find(hint); k != std::string::npos) why.erase(k, hint.size());
  std::ostringstream os;
  os << std::setprecision(4) << "e not measured: " << why;
  if (s.t_end_too_short && t_end_run != t_end_scene) os << "; still so with solver.t_end raised to " << t_end_run << " s";
  return os.str();
}

}  // namespace imcol
