// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A stop request for long work (Ctrl-C, a Python KeyboardInterrupt, a cancelled study): a StopSource requests it, the
// work polls a StopToken between its steps (one relaxed atomic load) and ends by throwing Interrupted. The token of
// the work a thread is doing is installed for a scope (WorkScope, core/work_scope.hpp), so no signature below the
// caller carries it.
#include <atomic>
#include <memory>

namespace imcol {

/// Thrown by work that was asked to stop. Deliberately not a std::exception: no handler of failures (a solver
/// failure, a failed sweep point) catches it; the caller that requested the stop does (exit 130, KeyboardInterrupt).
struct Interrupted {
  const char* what() const noexcept { return "interrupted"; }
};

/// Reads a stop request (copyable; default-constructed: never requested).
class StopToken {
 public:
  StopToken() = default;
  explicit StopToken(std::shared_ptr<const std::atomic<bool>> flag) : flag_(std::move(flag)) {}
  bool stop_possible() const { return flag_ != nullptr; }
  bool stop_requested() const { return flag_ && flag_->load(std::memory_order_relaxed); }
  /// Throws Interrupted when the stop was requested.
  void throw_if_requested() const {
    if (stop_requested()) throw Interrupted{};
  }

 private:
  std::shared_ptr<const std::atomic<bool>> flag_;
};

/// Requests a stop; request_stop() is async-signal-safe (a lock-free atomic store).
class StopSource {
 public:
  StopSource() : flag_(std::make_shared<std::atomic<bool>>(false)) {}
  void request_stop() const noexcept { flag_->store(true, std::memory_order_relaxed); }
  bool stop_requested() const { return flag_->load(std::memory_order_relaxed); }
  StopToken token() const { return StopToken(flag_); }

 private:
  std::shared_ptr<std::atomic<bool>> flag_;
};

static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler requests the stop");

}  // namespace imcol
