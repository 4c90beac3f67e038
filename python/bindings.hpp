// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The Python module's parts, one per concept: each adds its classes and functions to the module.
#include <pybind11/pybind11.h>

#include <string>

namespace imcol::python {

void bind_errors(pybind11::module_& m);  // InputError -> ValueError, SolverError -> imcol.SolverError
void bind_scene(pybind11::module_& m);   // imcol.Scene
void bind_run(pybind11::module_& m);     // imcol.run and imcol.Result
void bind_sweep(pybind11::module_& m);   // imcol.sweep and imcol.SweepResult
void bind_studies_precision(pybind11::module_& m);  // imcol.work_precision, imcol.validate_seed and their results
void bind_choices(pybind11::module_& m); // imcol.history_kernels(), …, imcol.scenes(), imcol.choices()
void bind_table(pybind11::module_& m);   // imcol.StudyTable
void bind_laws(pybind11::module_& m);    // imcol.laws
void bind_history(pybind11::module_& m); // imcol.history_compare
void bind_dem_fit(pybind11::module_& m); // imcol.dem_fit
void bind_data_dir(pybind11::module_& m); // imcol.data_dir, and the package's data folder setter
void bind_calibrate(pybind11::module_& m);  // imcol.calibrate and imcol.CalibrationResult

/// NumPy's C API table, made at the module's import under its GIL (python/numpy_api.cpp); without NumPy the module
/// still imports.
void init_numpy();
/// Returns when NumPy's arrays can be made; else raises ImportError: "`what` needs NumPy, …".
void require_numpy(const std::string& what);

}  // namespace imcol::python
