// SPDX-License-Identifier: BSD-3-Clause
#include "flow/field_series.hpp"

#include <filesystem>

#include "core/data_dir.hpp"
#include "core/text_file.hpp"
#include "core/timing.hpp"
#include "flow/snapshot.hpp"

namespace imcol::flow {

void FieldSeries::take(const Solver& s, const SnapshotFrame& frame, const std::string& name, const std::string& label) {
  const auto t0 = WallClock::now();
  std::string moment = label;  // without the CSV comment's trailing comma
  if (!moment.empty() && moment.back() == ',') moment.pop_back();
  const bool same_step = s.steps() == last_vtk_step_ && !entries_.empty();
  if (vtk() && same_step) entries_.back().label += "; " + moment;  // the same fields: named in the series' comment
  const bool new_vtk = vtk() && !same_step;
  if (csv() || new_vtk) {  // the fields (and their pressure solve) only for a file that needs them
    const std::vector<LevelFields> levels = level_fields(s, frame);
    if (csv()) sink_(name + ".csv", snapshot_csv(s, levels, frame, label));
    if (new_vtk) {
      last_vtk_step_ = s.steps();
      for (const auto& f : snapshot_vtk(s, levels, frame, name, moment)) sink_("vtk/" + f.name, f.content);
      entries_.push_back({s.time() + frame.t_shift, "vtk/" + name + ".vtm", moment});
    }
  }
  seconds_ += seconds_since(t0);
}

void FieldSeries::finish() {
  const auto t0 = WallClock::now();
  if (vtk() && !entries_.empty()) {
    sink_("flow.pvd", vtk_series(entries_));
    const std::string state = data_dir() + "/paraview/flow.py";  // a ParaView state opening flow.pvd beside it
    if (std::filesystem::is_regular_file(state)) sink_("flow.py", read_text_file(state, "ParaView state", 1 << 20, "Python"));
  }
  seconds_ += seconds_since(t0);
}

}  // namespace imcol::flow
