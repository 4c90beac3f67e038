// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// imcol.StudyTable: a study's table (study/table.hpp) as NumPy arrays, one per column of the command's CSV (numbers
// as float64 with NaN for an empty cell, words as str arrays), with what the study says besides (`info`).
#include <pybind11/pybind11.h>

#include <string>

#include "python/scene.hpp"
#include "study/table.hpp"

namespace imcol::python {

struct PyTable {
  std::string kind;        // laws | history | history_sweep | dem
  pybind11::list columns;  // the names, in the CSV's order
  pybind11::dict table;    // name -> array
  pybind11::dict info;     // the study's other results (e_is, fits, ...)
};

/// dir() of a result whose columns are attributes: the object's own names and the columns that are identifiers.
pybind11::list dir_with_columns(const pybind11::handle& self, const pybind11::list& columns);

/// The table's columns as arrays (call with the GIL held).
PyTable make_table(const std::string& kind, const study::Table& t, pybind11::dict info);

}  // namespace imcol::python
