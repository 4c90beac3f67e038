// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// imcol.SweepResult's content (python/sweep.cpp), which imcol.dem_fit (python/dem_fit.cpp) reads too.
#include <pybind11/pybind11.h>

#include <string>

#include "core/scene.hpp"
#include "study/sweep.hpp"

namespace imcol::python {

/// A sweep's points as columns: name -> 1-D array, in sweep.csv's order (`point`, the varied quantity's, then
/// sweep_columns(): numbers as float64 with NaN where the point has none, words as str arrays).
struct PySweepResult {
  std::string vary, column;
  pybind11::list columns;
  pybind11::dict table;
  study::SweepResult result;     // the points as run (imcol.dem_fit reads them)
  Scene base;                    // the scene before the varied value (imcol.dem_fit replays its contact)
  bool liquid = false, pair = false;  // the scene has a liquid; two spheres
};

}  // namespace imcol::python
