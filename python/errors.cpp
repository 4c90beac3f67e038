// SPDX-License-Identifier: BSD-3-Clause
// Errors at the module's boundary: bad input (InputError) raises ValueError with the command line's one-line
// message (without its "imcol: error: " prefix); a solver failure raises imcol.SolverError with the solver's message.
// Anything else a C++ call throws becomes a Python exception (pybind11's translation: RuntimeError, MemoryError).
#include "core/errors.hpp"
#include "python/bindings.hpp"

namespace py = pybind11;

namespace imcol::python {

void bind_errors(py::module_& m) {
  static py::exception<SolverError> solver_error(m, "SolverError", PyExc_RuntimeError);
  solver_error.doc() = "The time integrator failed: what failed, when, and which state components were to blame.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const SolverError& e) {
      PyErr_SetString(solver_error.ptr(), e.what());
    }
  });
}

}  // namespace imcol::python
