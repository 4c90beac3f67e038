// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The search `imcol calibrate` runs, on the unit cube of the parameters (calibrate/fit_parameter.hpp), in
// stages whose work items are independent and may run anywhere (threads, MPI ranks):
//  1. scan: `scan` points (a grid for one parameter, a Halton set for more) and the scene's own values (the start);
//  2. local: bounded derivative-free local searches (NLopt LN_BOBYQA) from the best `starts` points of stage 1, each
//     one work item (its evaluations run one after another);
//  3. profile: for each parameter, `profile_points` values across its bounds, the others re-optimised (a short local
//     search from the best) when there are more than one; the interval where the objective stays within a factor
//     of the best (calibrate/confidence.hpp, or given);
//  4. edge: each finite end of an interval refined by bisection between the profile point inside and its neighbour
//     outside until the bracket is `refine_to` of the interval's width, `refine` rounds at most (one work item per
//     end still too wide and round, a profile point each), the end interpolated linearly inside the last bracket.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/fit_parameter.hpp"
#include "calibrate/objective.hpp"

namespace imcol::calib {

struct SearchOptions {
  int scan = -1;                // stage-1 points; -1 = 8 d + 1 for d parameters; 0 = none (only the start)
  int starts = 2;               // stage-2 local searches
  int max_evals = 40;           // per local search
  double xtol = 1e-3;           // local searches stop when a step changes u by less than this
  int profile_points = 15;      // per parameter; 0 = no profiles
  std::optional<double> factor; // profile interval: objective <= factor * best; none: from `confidence`
  double confidence = 0.95;     // the default factor 1 + q / (n - p), q the chi^2(1) quantile at this probability
  int inner_parameters = 0;     // parameters each evaluation fits itself (a trajectory's time offset: 1), counted in p
  int refine = 16;              // most bisection rounds for each finite interval end; 0 = none
  double refine_to = 1.0 / 64;  // an end is refined until its bracket is this fraction of the interval's width
};

enum class Stage { start, scan, local, profile, edge };
const char* stage_name(Stage s);

/// One evaluation of the search, in the order done.
struct EvaluationRecord {
  Stage stage = Stage::scan;
  int item = 0;                 // the work item (scan point, local search, profile point) it belongs to
  std::vector<double> values;   // parameter values
  Evaluation eval;
  int rank = 0;                 // the MPI rank that ran it
};

struct Profile {
  std::vector<double> values, objective;  // along the parameter (others at their best or re-optimised), the refined
                                          // ends' points among them, sorted by value
  std::optional<double> lo, hi;           // the interval within factor * best; none: it reaches the bound
  bool resolved = true;                   // every finite end's last bracket within refine_to of the interval's width
};

/// How the profile threshold was chosen: factor × the best objective.
struct FactorRule {
  bool given = false;        // SearchOptions::factor; else the confidence rule
  double confidence = 0, q = 0;  // the rule's probability and chi^2(1) quantile
  std::size_t n = 0, p = 0;  // residuals of the best evaluation; fitted parameters (the inner ones among them)
  double factor = 0;
  double threshold = 0;      // factor × the best objective
};

struct SearchResult {
  std::vector<double> best;               // parameter values
  Evaluation best_eval;
  std::vector<EvaluationRecord> evaluations;
  std::vector<Profile> profiles;          // per parameter (empty without profiles)
  FactorRule rule;                        // with profiles
  int failed = 0;                         // evaluations that failed
  bool stopped = false;                   // ended early by `stopped`: the stages that finished and what ran of the next
};

/// Where the work items run: run(n, work, done) runs work(i) for every i < n anywhere and calls done(i, bytes, rank)
/// on the deciding process (rank 0); share(bytes) makes rank 0's bytes every rank's. With threads only, share is
/// the identity. apps/calibrate.cpp gives one over cluster::run_distributed.
struct Runner {
  std::function<void(std::size_t, const std::function<std::string(std::size_t)>&,
                     const std::function<void(std::size_t, std::string, int)>&)> run;
  std::function<void(std::string&)> share;
};

/// Progress after each finished work item: the stage, items done and in the stage, evaluations so far, best so far.
using Progress = std::function<void(Stage, std::size_t done, std::size_t items, std::size_t evaluations, double best)>;

/// Asked (from any thread) before each evaluation, and (rank 0's answer shared) after each stage: true ends the search.
using Stopped = std::function<bool()>;

/// Runs the stages. `evaluate(values)` scores one set of parameter values; it must be thread-safe and must
/// not throw. Every rank calls search with the same arguments; the result is complete on rank 0 only. Once `stopped`
/// says so, no evaluation starts and the search returns what finished, its best among them, without intervals.
SearchResult search(const std::vector<FitParameter>& params, const std::vector<double>& start,
                    const std::function<Evaluation(const std::vector<double>&)>& evaluate, const SearchOptions& opt,
                    const Runner& runner, const Progress& progress = {}, const Stopped& stopped = {});

}  // namespace imcol::calib
