// SPDX-License-Identifier: BSD-3-Clause
#include "python/interrupt.hpp"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "core/errors.hpp"
#include "core/work_scope.hpp"
#include "run/progress_estimate.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace interrupt_impl {  // this file's helpers: named, as the module is one unity unit

constexpr auto kPoll = std::chrono::milliseconds(50);

/// The work's thread and how it ended: finished, and what it threw.
struct Worker {
  StopSource stop;
  ProgressMeter meter;
  std::mutex mu;
  std::condition_variable cv;
  bool finished = false;
  std::exception_ptr error;
  std::thread thread;

  void start(const std::function<void()>& work) {
    thread = std::thread([this, &work] {
      WorkScope scope({stop.token(), &meter});
      try {
        work();
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard lock(mu);
      finished = true;
      cv.notify_all();
    });
  }
  /// Waits up to one poll interval (the GIL released); true once the work ended.
  bool wait_a_little() {
    py::gil_scoped_release free;
    std::unique_lock lock(mu);
    return cv.wait_for(lock, kPoll, [this] { return finished; });
  }
  void join() {
    py::gil_scoped_release free;
    if (thread.joinable()) thread.join();
  }
};

/// The calling thread's loop: signals and the progress callback every poll until the work ended; throws
/// error_already_set on a Python exception.
void follow(Worker& w, const py::object& progress) {
  run::ProgressFollower follower(w.meter);
  while (!w.wait_a_little()) {
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (progress.is_none()) continue;
    if (const auto p = follower.poll()) progress(p->done, p->total, p->eta_s);
  }
  if (progress.is_none() || w.error) return;
  const double total = w.meter.read().second;
  if (total > 0) progress(total, total, 0.0);  // the work ended: done == total
}

}  // namespace interrupt_impl

void call_interruptibly(const std::function<void()>& work, const py::object& progress) {
  using namespace interrupt_impl;
  Worker w;
  w.start(work);
  try {
    follow(w, progress);
  } catch (...) {
    w.stop.request_stop();
    w.join();
    throw;
  }
  w.join();
  if (w.error) std::rethrow_exception(w.error);
}

study::Hooks interruptible_hooks() {
  study::Hooks h;
  h.stop = this_thread_work().stop;
  ProgressMeter* meter = this_thread_work().meter;
  h.progress = [meter](std::size_t done, std::size_t total) {
    if (meter) meter->set(static_cast<double>(done), static_cast<double>(total));
  };
  return h;
}

void check_progress_callable(const py::object& progress, const char* where) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw InputError(where, "progress", "must be None or a callable progress(done, total, eta_s)");
}

}  // namespace imcol::python
