// SPDX-License-Identifier: BSD-3-Clause
#include "study/sweep.hpp"

#include <algorithm>

#include "study/run_all.hpp"
#include "study/point_json.hpp"

namespace imcol::study {

std::size_t SweepResult::finished() const { return static_cast<std::size_t>(std::count(done.begin(), done.end(), true)); }

std::size_t SweepResult::failed() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < points.size(); ++i) n += done[i] && !points[i].ok ? 1 : 0;
  return n;
}

SweepResult run_sweep(const std::vector<Scene>& scenes, const std::string& vary, const std::vector<double>& values, const Executor& ex,
                      const Hooks& hooks, const PointTaken& taken) {
  SweepResult r;
  r.vary = vary;
  const char* column = sweep_column(vary);
  r.column = column ? column : "";
  r.values = values;
  r.points.resize(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) r.points[i].value = values[i];
  r.done.assign(values.size(), false);
  const bool all = run_all<SweepPoint>(
      ex, scenes.size(), [&](std::size_t i) { return run_sweep_point(scenes[i], values[i]); },
      [&](std::size_t i, SweepPoint&& p) {
        r.points[i] = std::move(p);
        r.done[i] = true;
        return taken ? taken(i, r) : true;
      },
      hooks);
  r.cancelled = !all && ex.deciding();
  return r;
}

}  // namespace imcol::study
