// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A study's runs on its Executor (study/executor.hpp), typed: run(i) → T on any thread or rank, take(i, T) on the
// deciding process one at a time, in the order the runs finish. Across ranks a T travels as CBOR bytes of its JSON
// (to_json/from_json found by argument-dependent lookup); doubles keep every bit.
#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "study/executor.hpp"
#include "study/parallel_runs.hpp"

namespace imcol::study {

/// T as the bytes that cross ranks, and back.
template <class T>
std::string to_bytes(const T& x) {
  const auto v = nlohmann::ordered_json::to_cbor(nlohmann::ordered_json(x));
  return std::string(v.begin(), v.end());
}
template <class T>
T from_bytes(const std::string& bytes) {
  return nlohmann::ordered_json::from_cbor(bytes).get<T>();
}

/// Runs run(i) for i < n on `ex`; take(i, T&&) on the deciding process as each finishes (returns false to hand out no
/// further runs). hooks.progress after each take, hooks.cancelled before each run is handed out. The runs work under
/// run_control(hooks): a run that throws Interrupted (a stop request) is dropped, no further runs are handed out and
/// this returns once the runs in flight ended.
/// Returns true when every run was handed out and taken (not cancelled, stopped by take or interrupted). `run` must
/// throw nothing else.
template <class T, class Run, class Take>
bool run_all(const Executor& ex, std::size_t n, Run run, Take take, const Hooks& hooks = {}) {
  WorkScope scope(run_control(hooks));
  const StopToken stop = this_thread_work().stop;
  std::size_t done = 0;
  bool stopped = false;
  auto accept = [&](std::size_t i, T&& x) {
    const bool more = take(i, std::move(x));
    ++done;
    if (hooks.progress) hooks.progress(done, n);
    if (!more || stop.stop_requested() || hooks.cancel_requested()) stopped = true;
    return !stopped;
  };
  const int jobs = std::max(1, job_count(ex.jobs, n));
  if (stop.stop_requested() || hooks.cancel_requested()) return false;
  try {  // run_parallel's threads (and so the executors') rethrow an Interrupted run once the others ended
    if (!ex.distribute) {
      run_parallel(n, jobs, [&](std::size_t i) { return T(run(i)); }, accept);
    } else {
      ex.distribute(n, jobs, [&](std::size_t i) { return to_bytes<T>(run(i)); },
                    [&](std::size_t i, std::string bytes, int) { return accept(i, from_bytes<T>(bytes)); });
    }
  } catch (const Interrupted&) {
    stopped = true;
  }
  return !stopped || done == n;
}

}  // namespace imcol::study
