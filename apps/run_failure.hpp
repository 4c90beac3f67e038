// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a run threw, as data: a run on another MPI rank (apps/cluster.hpp) reports its exception to rank 0 so, and
// rank 0 rethrows it as the same kind (InputError exit 2, SolverError exit 3, anything else exit 1).
#include <exception>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"

namespace imcol {

struct RunFailure {
  enum Kind : int { none = 0, solver = 1, input = 2, other = 3 };
  int kind = none;
  std::string what, where, key, problem;  // what(); for an InputError its parts too
  std::exception_ptr thrown;              // the exception itself, where it was thrown (not sent)

  /// The exception being handled (call in a catch block).
  static RunFailure current() {
    RunFailure f;
    f.thrown = std::current_exception();
    try {
      throw;
    } catch (const SolverError& e) {
      f.kind = solver, f.what = e.what();
    } catch (const InputError& e) {
      f.kind = input, f.what = e.what(), f.where = e.where(), f.key = e.key(), f.problem = e.problem();
    } catch (const std::exception& e) {
      f.kind = other, f.what = e.what();
    }
    return f;
  }

  /// Rethrows the exception itself where it was thrown, else one of the same kind and message.
  [[noreturn]] void rethrow() const {
    if (thrown) std::rethrow_exception(thrown);
    if (kind == solver) throw SolverError(what);
    if (kind == input) throw InputError(where, key, problem);
    throw std::runtime_error(what);
  }
};

}  // namespace imcol
