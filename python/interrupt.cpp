// SPDX-License-Identifier: BSD-3-Clause
#include "python/interrupt.hpp"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include <pthread.h>

#include "core/errors.hpp"
#include "core/work_scope.hpp"
#include "run/progress_estimate.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace interrupt_impl {  // this file's helpers: named, as the module is one unity unit

constexpr auto kPoll = std::chrono::milliseconds(50);

/// Threads kept across calls: starting a thread for each call cost 0.27 ms of CPU on our machine, more than a short
/// run. A call takes an idle thread or starts one; the thread waits for the next call afterwards. The pool is never
/// destroyed (its idle threads wait until the process ends); a forked child starts with an empty one.
class ThreadPool {
 public:
  static ThreadPool& instance() {
    static const bool hooked = [] { return pthread_atfork(nullptr, nullptr, [] { pool() = new ThreadPool; }) == 0; }();
    (void)hooked;
    return *pool();
  }
  /// Runs task() on an idle or new thread; task must not throw.
  void run(std::function<void()> task) {
    std::unique_lock lock(mu_);
    if (idle_.empty()) {
      auto* slot = new Slot;  // owned by its thread, which never ends
      slot->task = std::move(task);
      std::thread([this, slot] { serve(*slot); }).detach();
      return;
    }
    Slot* slot = idle_.back();
    idle_.pop_back();
    lock.unlock();
    {
      std::lock_guard slot_lock(slot->mu);
      slot->task = std::move(task);
    }
    slot->cv.notify_one();
  }

 private:
  struct Slot {
    std::mutex mu;
    std::condition_variable cv;
    std::function<void()> task;
  };
  static ThreadPool*& pool() {
    static ThreadPool* p = new ThreadPool;
    return p;
  }
  void serve(Slot& slot) {
    for (;;) {
      std::function<void()> task;
      {
        std::unique_lock lock(slot.mu);
        slot.cv.wait(lock, [&slot] { return static_cast<bool>(slot.task); });
        task = std::move(slot.task);
        slot.task = nullptr;
      }
      task();
      task = nullptr;  // its captures released before the thread is idle again
      std::lock_guard lock(mu_);
      idle_.push_back(&slot);
    }
  }
  std::mutex mu_;
  std::vector<Slot*> idle_;
};

/// The work, on a pooled thread, and how it ended: finished, and what it threw.
struct Worker {
  StopSource stop;
  ProgressMeter meter;
  std::mutex mu;
  std::condition_variable cv;
  bool finished = false;
  std::exception_ptr error;

  void start(const std::function<void()>& work) {
    ThreadPool::instance().run([this, &work] {
      {
        WorkScope scope({stop.token(), &meter});
        try {
          work();
        } catch (...) {
          error = std::current_exception();
        }
      }
      std::lock_guard lock(mu);  // the last touch of this Worker: join() may return and free it right after
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
  /// Waits until the work ended (the GIL released).
  void join() {
    py::gil_scoped_release free;
    std::unique_lock lock(mu);
    cv.wait(lock, [this] { return finished; });
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
