// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A run's flow-field snapshots as files: each snapshot as NAME.csv (flow/snapshot.hpp) and/or vtk/NAME.vtm with its
// levels and bodies (flow/vtk.hpp), and at the end flow.pvd, the time series of the .vtm files, with flow.py beside it
// (data/paraview/flow.py: a ParaView state that opens it). The files go to a
// sink as they are made (a run with many snapshots holds none of them), names relative to the output folder.
#include <functional>
#include <string>
#include <vector>

#include "core/choices.hpp"
#include "flow/fields.hpp"
#include "flow/solver.hpp"
#include "flow/vtk.hpp"

namespace imcol::flow {

/// Receives a file: its name relative to the output folder, and its content.
using FileSink = std::function<void(const std::string& name, const std::string& content)>;

class FieldSeries {
 public:
  FieldSeries(FieldsFormat format, FileSink sink) : format_(format), sink_(std::move(sink)) {}
  /// One snapshot of the solver's present fields seen from `frame`. The VTK files are written once per kernel step:
  /// a second snapshot at the same step writes its CSV only (the time series would repeat a time).
  void take(const Solver& s, const SnapshotFrame& frame, const std::string& name, const std::string& label);
  /// Writes flow.pvd and flow.py (with VTK output and at least one snapshot). Call once, after the last snapshot.
  void finish();
  bool csv() const { return format_ != FieldsFormat::vtk; }
  bool vtk() const { return format_ != FieldsFormat::csv; }
  /// Wall time spent computing and formatting the snapshots' files, s (the sink's writing included).
  double seconds() const { return seconds_; }

 private:
  FieldsFormat format_;
  FileSink sink_;
  std::vector<SeriesEntry> entries_;
  long last_vtk_step_ = -1;
  double seconds_ = 0;
};

}  // namespace imcol::flow
