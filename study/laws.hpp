// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The solid contact laws (contact.law) compared on one scene, or at each point of a sweep of one quantity: a run per
// law (and point), one after the other (each run's CPU time is the process's).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "run/simulate.hpp"
#include "study/executor.hpp"
#include "study/sweep_points.hpp"
#include "study/table.hpp"

namespace imcol::study {

/// One law's run (at one point), or why there is none.
struct LawRun {
  std::string law;
  std::string status = "ran";  // ran | refused (bad input for this law) | failed (the solver)
  std::string message;         // refused/failed: the error; ran: why e is missing, if it is
  std::optional<InputError> refusal;
  std::optional<SolverError> failure;
  RunResult run;       // a sweep's point keeps its summary only
  double cpu_s = NAN;  // process CPU time of the whole run (model set-up included), s
  int point = -1;      // a sweep's point (-1: the scene alone) and the varied quantity's value there
  double value = NAN;
  bool ran() const { return status == "ran"; }
};

struct LawsResult {
  std::vector<std::string> laws;
  std::string vary, column;     // the varied quantity and its CSV column; empty: the scene alone
  std::vector<double> values;   // the points' values ({NaN}: the scene alone)
  std::vector<LawRun> rows;     // point by point, law by law
  bool cancelled = false;       // some runs were not started
  int first_ran = -1;           // the first row that ran
  std::string e_is;             // e's named measure (the first run's, else the scene's measure.e)
  std::optional<ContactSummary> contact;  // the first run's: e_dry and delta_SS
};

/// The laws to compare: `given` (unknown names refused as InputError(where, key), repeats dropped), or every shipped law.
std::vector<std::string> laws_to_compare(const std::vector<std::string>& given, const std::string& where, const std::string& key);

/// Runs the scene (`load` with `overrides`, then contact.law) with each law; with `vary` (a sweep quantity), at each
/// of `values` of it (empty `vary`: the scene alone). `progress`: a long run's progress line on a terminal. A law
/// that refuses the scene, or whose run fails, gets a row saying why. Throws InputError for a free sphere.
LawsResult compare_laws(const SceneLoader& load, const std::vector<Override>& overrides, const std::vector<std::string>& laws,
                        const std::string& vary, const std::vector<double>& values, bool progress = false, const Hooks& hooks = {});

/// laws.csv's table: a row per law (and point); the named measures and the laws' numbers as columns of their own.
Table laws_table(const LawsResult& r);

// A row's measured quantities (nullopt where it has none).
std::optional<double> law_e(const LawRun& r);
std::optional<double> contact_time(const LawRun& r);  // below δ_SS in the first contact, s
std::optional<double> max_overlap(const LawRun& r);   // δ_SS − min gap, m
std::optional<double> peak_force(const LawRun& r);    // N
/// e of the ramp (the default law) at the same point, if it ran there.
std::optional<double> ramp_e(const std::vector<LawRun>& rows, int point);

/// a − b; none when either is missing.
inline std::optional<double> minus(const std::optional<double>& a, const std::optional<double>& b) {
  return a && b ? std::optional<double>(*a - *b) : std::nullopt;
}

/// The value under `name` in a list of named values (the named measures of e, a law's numbers); none if absent.
template <class K>
std::optional<double> lookup(const std::vector<std::pair<K, std::optional<double>>>& list, const K& name) {
  for (const auto& [k, v] : list)
    if (k == name) return v;
  return std::nullopt;
}
/// The law's own summary numbers (ContactLaw::summary), name → value; the named measures of e.
const std::vector<std::pair<std::string, std::optional<double>>>& law_numbers(const LawRun& r);
const std::vector<std::pair<EMeasure, std::optional<double>>>& law_measures(const LawRun& r);
std::vector<EMeasure> measure_names(const std::vector<LawRun>& rows);  // in first-seen order over every row

}  // namespace imcol::study
