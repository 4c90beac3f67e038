// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a run threw, as data: a study's run on another MPI rank (study/executor.hpp) reports its exception to the
// deciding rank so (as JSON: to_json/from_json), which rethrows it as the same kind (InputError exit 2, SolverError
// exit 3, anything else exit 1).
#include <exception>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

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

/// Its kind and text cross ranks; the exception itself stays where it was thrown.
inline void to_json(nlohmann::ordered_json& j, const RunFailure& f) {
  j = {{"kind", f.kind}, {"what", f.what}, {"where", f.where}, {"key", f.key}, {"problem", f.problem}};
}
inline void from_json(const nlohmann::ordered_json& j, RunFailure& f) {
  f.kind = j.at("kind").get<int>();
  j.at("what").get_to(f.what), j.at("where").get_to(f.where), j.at("key").get_to(f.key), j.at("problem").get_to(f.problem);
}

}  // namespace imcol
