// SPDX-License-Identifier: BSD-3-Clause
// Errors at the module's boundary: bad input (InputError) raises ValueError with a one-line message in Python's words
// (python/call.hpp: the call and the key, or the scene file's line; never the command line's options); a solver
// failure raises imcol.SolverError with the solver's message and, when the integrator failed, its facts as attributes
// (core/errors.hpp SolverFailure).
// Anything else a C++ call throws becomes a Python exception (pybind11's translation: RuntimeError, MemoryError).
#include <pybind11/stl.h>

#include "core/errors.hpp"
#include "core/stop.hpp"
#include "core/toml_reader.hpp"
#include "python/bindings.hpp"
#include "python/call.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace errors_impl {  // this file's helpers: named, as the module is one unity unit

/// Whether an error's place is a value given to a call rather than a scene file's line: an override or a scene's
/// name (the command line's names for them).
bool given_to_call(const std::string& where) { return where == kOverridePlace || where == "--set" || where == "command line"; }

/// Whether `name` is a command's option ("--rtols").
bool is_option(const std::string& name) { return name.rfind("--", 0) == 0 && name.size() > 2; }

/// The argument a command's option stands for: "--ref-rtol" -> "ref_rtol".
std::string argument_of(const std::string& option) {
  std::string arg = option.substr(2);
  for (char& c : arg)
    if (c == '-') c = '_';
  return arg;
}

/// The key as a call names it: "Scene.set('fluid.viscosity')" names its key.
bool call_names_key(const std::string& call, const std::string& key) { return call.find("('" + key + "')") != std::string::npos; }

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

std::string call_message(const std::string& call, const InputError& e) {
  using namespace errors_impl;
  if (e.where() == call) return e.what();  // a check of the call's own argument names the call already
  // A command's option is the call's argument of that name (--ref-rtol: ref_rtol); its key, when another, the value.
  if (is_option(e.where()) && e.where() != "--set") {
    const std::string arg = argument_of(e.where());
    return call + ": key '" + arg + "': " + (e.key() == arg || e.key().empty() ? "" : "'" + e.key() + "': ") + e.problem();
  }
  if (!given_to_call(e.where())) return call + ": " + e.what();
  const std::string key = is_option(e.key()) ? argument_of(e.key()) : e.key();
  if (key.empty() || call_names_key(call, key)) return call + ": " + e.problem();
  return call + ": key '" + key + "': " + e.problem();
}

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
      // A call not bound with in_call: the module's name in the place of the command line's.
      const bool named = e.where().rfind("imcol", 0) == 0;
      PyErr_SetString(PyExc_ValueError, named ? e.what() : call_message("imcol", e).c_str());
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
