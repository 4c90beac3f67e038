// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Long work called from Python, interruptible and followed: the work runs on a thread of its own, the GIL released,
// under a stop request and a progress meter (core/work_scope.hpp); the calling thread keeps the GIL's turn every
// 50 ms to check for signals (Ctrl-C, Jupyter's "interrupt kernel") and to call the progress callback.
#include <pybind11/pybind11.h>

#include <functional>

#include "study/executor.hpp"

namespace imcol::python {

/// Runs work() and returns when it ended, rethrowing what it threw. Called with the GIL held, which the work must not
/// need. At least every 50 ms the calling thread takes the GIL and calls PyErr_CheckSignals(), then, if `progress` is
/// a callable and the work advanced, progress(done, total, eta_s) (run/progress_estimate.hpp), and once more with
/// done == total when the work ended. On a Python exception there (KeyboardInterrupt from a signal, or one the
/// callback raised) it requests the stop, waits for the work to end (within one of its steps) and re-raises it.
void call_interruptibly(const std::function<void()>& work, const pybind11::object& progress);

/// A study's hooks for work run by call_interruptibly (make them on the work's thread): finished runs of all go to its
/// progress meter; its stop request reaches the runs in flight.
study::Hooks interruptible_hooks();

/// The `progress` argument's check: None or a callable; else ValueError naming `where`.
void check_progress_callable(const pybind11::object& progress, const char* where);

}  // namespace imcol::python
