// SPDX-License-Identifier: BSD-3-Clause
// Errors at the module's boundary: bad input (InputError) raises ValueError with the command line's one-line
// message (without its "imcol: error: " prefix); a solver failure raises imcol.SolverError with the solver's message
// and, when the integrator failed, its facts as attributes (core/errors.hpp SolverFailure).
// Anything else a C++ call throws becomes a Python exception (pybind11's translation: RuntimeError, MemoryError).
#include <pybind11/stl.h>

#include "core/errors.hpp"
#include "core/stop.hpp"
#include "core/toml_reader.hpp"
#include "python/bindings.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace errors_impl {  // this file's helpers: named, as the module is one unity unit

/// The place a ValueError names for a value given through the module (the program's is the command line).
constexpr const char* kPythonOverridePlace = "imcol (Scene.set, or rtol/atol/integrator of run or sweep)";

/// The integrator's facts as the exception's attributes (None where there are none).
void set_facts(py::object& exc, const SolverFailure* f) {
  if (!f) return;
  exc.attr("integrator") = f->integrator;
  exc.attr("time") = f->time;
  if (f->flag != 0) {
    exc.attr("flag") = f->flag;
    exc.attr("flag_name") = f->flag_name;
  }
  py::dict state;
  for (std::size_t i = 0; i < f->names.size() && i < f->state.size(); ++i) state[py::str(f->names[i])] = f->state[i];
  exc.attr("state") = state;
  py::dict errors;
  for (const auto& [name, err] : f->local_errors) errors[py::str(name)] = err;
  exc.attr("local_errors") = errors;
}

}  // namespace errors_impl

void bind_errors(py::module_& m) {
  using namespace errors_impl;
  // The type is kept by a handle that is never released: a static py::object would drop its reference when the
  // process exits, after the interpreter has been finalized.
  static py::handle solver_error;
  solver_error = py::exception<SolverError>(m, "SolverError", PyExc_RuntimeError).release();
  solver_error.attr("__doc__") =
      "The time integrator failed: what failed, when, and which state components were to blame. str(error) is the "
      "command line's message. When the integrator failed, the facts are attributes too: integrator ('cvode', "
      "'ida'), flag (the SUNDIALS return flag, an int) and flag_name ('CV_TOO_MUCH_WORK'), time (s, the last time "
      "reached), state (component name -> value there), local_errors (the largest weighted local errors, name -> "
      "value; empty when the model itself failed). Each is None where it does not apply: all of them for a failure that is "
      "not the integrator's (a coupled run's flow kernel or coupling), flag and flag_name when no solver call returned "
      "a flag.";
  for (const char* a : {"integrator", "flag", "flag_name", "time", "state", "local_errors"}) solver_error.attr(a) = py::none();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      // A value given through the module has no command line: name the calls that take values instead.
      if (e.where() == kOverridePlace)
        PyErr_SetString(PyExc_ValueError, InputError(kPythonOverridePlace, e.key(), e.problem()).what());
      else
        PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const SolverError& e) {
      py::object exc = solver_error(e.what());  // an instance, its attributes set before raising
      set_facts(exc, e.failure());
      PyErr_SetObject(solver_error.ptr(), exc.ptr());
    } catch (const Interrupted&) {  // work stopped at a request (python/interrupt.hpp re-raises the request's own exception)
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });
}

}  // namespace imcol::python
