// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Error types shared by all modules. InputError -> exit status 2, SolverError -> exit status 3.
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace imcol {

/// A number as messages write it (shortest default formatting).
inline std::string fmt_number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

/// Bad input: names the place (file[:line] or "--set"), the key and the problem, on one line
/// (control characters in any part are written as escapes such as \n).
class InputError : public std::runtime_error {
 public:
  InputError(std::string where, std::string key, const std::string& problem);
  const std::string& where() const { return where_; }
  const std::string& key() const { return key_; }
  const std::string& problem() const { return problem_; }  // the message without its place and key

 private:
  std::string where_, key_, problem_;
};

/// What a failed time integrator reports, as data (the facts its SolverError's message states, and the state).
struct SolverFailure {
  std::string integrator;  // cvode | ida
  int flag = 0;            // the SUNDIALS return flag (CV_TOO_MUCH_WORK = -1, ...); 0: none (the model threw outside a solver call)
  std::string flag_name;   // its name, e.g. CV_TOO_MUCH_WORK; empty without a flag
  double time = 0;         // s: the last time the integrator reached
  std::vector<std::string> names;  // the state's components (the model's component names)
  std::vector<double> state;       // their values at `time`
  std::vector<std::pair<std::string, double>> local_errors;  // the largest weighted local errors, largest first
};

/// The time integrator failed: what failed, when, and which state components were to blame. Thrown by the
/// integrator, it carries those facts as data too (failure()); other solver failures (the flow kernel, set-up) do not.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  SolverError(const std::string& message, SolverFailure failure)
      : std::runtime_error(message), failure_(std::make_shared<const SolverFailure>(std::move(failure))) {}
  /// Another message, the facts of `cause` kept (a caller that names a cause of the failure before the solver's).
  SolverError(const std::string& message, const SolverError& cause) : std::runtime_error(message), failure_(cause.failure_) {}
  /// The integrator's facts; null when the failure was not the integrator's.
  const SolverFailure* failure() const { return failure_.get(); }

 private:
  std::shared_ptr<const SolverFailure> failure_;  // shared: exceptions are copied
};

}  // namespace imcol
