// SPDX-License-Identifier: BSD-3-Clause
#include "study/history_sweep.hpp"

#include <algorithm>

#include "run/simulate.hpp"
#include "study/history.hpp"
#include "study/run_all.hpp"
#include "study/point_json.hpp"

namespace imcol::study {

std::vector<HistorySeries> history_series(const std::vector<std::string>& kernels, const std::vector<std::string>& evaluators,
                                          const Scene& base) {
  std::vector<std::string> evals = evaluators;
  if (evals.empty()) evals = {to_string(base.history.evaluator)};
  std::vector<HistorySeries> s = {{"none", "-"}};
  for (const auto& k : kernels)
    for (const auto& e : evals)
      if (std::none_of(s.begin(), s.end(), [&](const HistorySeries& x) { return x.kernel == k && x.evaluator == e; })) s.push_back({k, e});
  return s;
}

std::size_t HistorySweepResult::failed() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) n += done[i] && !cells[i].ok() ? 1 : 0;
  return n;
}

namespace {

/// One cell's run; a failed run ends that cell only.
HistoryCell run_cell(const Scene& scene, HistoryCell c) {
  try {
    // e needs no force columns (as imcol sweep)
    c.summary = simulate(with_history_kernel(scene, c.series.kernel, c.series.evaluator), false, Recording::kinematics).summary;
    if (!c.summary.e) c.message = c.summary.e_missing.value_or("e is undefined");
  } catch (const std::exception& e) {
    c.status = "failed";
    c.message = e.what();
  }
  return c;
}

}  // namespace

HistorySweepResult history_sweep(const std::vector<Scene>& scenes, const std::string& vary, const std::vector<double>& values,
                                 const std::vector<HistorySeries>& series, const Executor& ex, const Hooks& hooks, const CellTaken& taken) {
  HistorySweepResult r;
  r.vary = vary;
  const char* column = sweep_column(vary);
  r.column = column ? column : "";
  r.values = values;
  r.series = series;
  for (std::size_t i = 0; i < values.size(); ++i)
    for (const auto& s : series) {
      HistoryCell c;
      c.point = static_cast<int>(i);
      c.value = values[i];
      c.series = s;
      r.cells.push_back(std::move(c));
    }
  r.done.assign(r.cells.size(), false);
  const bool all = run_all<HistoryCell>(
      ex, r.cells.size(), [&](std::size_t i) { return run_cell(scenes[static_cast<std::size_t>(r.cells[i].point)], r.cells[i]); },
      [&](std::size_t i, HistoryCell&& c) {
        r.cells[i] = std::move(c);
        r.done[i] = true;
        if (taken) taken(i, r.cells[i]);
        return true;
      },
      hooks);
  r.cancelled = !all && ex.deciding();
  return r;
}

namespace {

template <class Get>
void add_cell_numbers(Table& t, const std::string& name, const std::vector<HistoryCell>& cells, Get get) {
  auto& col = t.add(name);
  for (const auto& c : cells) col.numbers.push_back(c.ok() ? get(c).value_or(NAN) : NAN);
}

template <class Get>
void add_cell_words(Table& t, const std::string& name, const std::vector<HistoryCell>& cells, Get get) {
  auto& col = t.add(name, true);
  for (const auto& c : cells) col.text.push_back(get(c));
}

}  // namespace

Table history_sweep_table(const HistorySweepResult& r) {
  using V = std::optional<double>;
  using C = const HistoryCell&;
  const auto& cells = r.cells;
  Table t;
  t.rows = cells.size();
  auto& point = t.add("point");
  auto& value = t.add(r.column);
  for (const auto& c : cells) point.numbers.push_back(c.point), value.numbers.push_back(c.value);
  add_cell_words(t, "kernel", cells, [](C c) { return c.series.kernel; });
  add_cell_words(t, "evaluator", cells, [](C c) { return c.series.evaluator; });
  add_cell_words(t, "status", cells, [](C c) { return c.status; });
  add_cell_numbers(t, "St", cells, [](C c) { return c.summary.St; });
  add_cell_numbers(t, "e", cells, [](C c) { return c.summary.e; });
  add_cell_numbers(t, "St_initial", cells, [](C c) { return c.summary.St_initial; });
  add_cell_numbers(t, "Re", cells, [](C c) { return c.summary.Re; });
  add_cell_numbers(t, "impact_speed_m_s", cells, [](C c) { return c.summary.contact ? c.summary.contact->impact_speed_m_s : V(); });
  add_cell_words(t, "e_is", cells, [](C c) { return c.ok() ? std::string(to_string(c.summary.e_is)) : std::string(); });
  add_cell_numbers(t, "steps", cells, [](C c) { return V(static_cast<double>(c.summary.solver.stats.steps)); });
  add_cell_numbers(t, "wall_time_s", cells, [](C c) { return V(c.summary.wall_time_s); });
  add_cell_words(t, "message", cells, [](C c) { return c.message; });
  return t;
}

}  // namespace imcol::study
