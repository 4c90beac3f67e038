// SPDX-License-Identifier: BSD-3-Clause
// The staged search: scan, local searches, profiles; each stage's work items run on the Runner, their evaluations
// travelling as bytes, the next stage's inputs shared from rank 0.
#include "calibrate/search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "calibrate/evaluation_bytes.hpp"
#include "calibrate/local_search.hpp"
#include "calibrate/profile.hpp"

namespace imcol::calib {

const char* stage_name(Stage s) {
  switch (s) {
    case Stage::start: return "start";
    case Stage::scan: return "scan";
    case Stage::local: return "local";
    case Stage::profile: return "profile";
  }
  return "?";
}

namespace {

/// The i-th (from 1) point of the Halton sequence in d dimensions (bases: the first primes).
std::vector<double> halton(std::size_t i, std::size_t d) {
  static const unsigned primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71};
  std::vector<double> u(d);
  for (std::size_t k = 0; k < d; ++k) {
    const unsigned b = primes[k % std::size(primes)];
    double f = 1, r = 0;
    for (std::size_t n = i; n > 0; n /= b) {
      f /= b;
      r += f * static_cast<double>(n % b);
    }
    u[k] = r;
  }
  return u;
}

struct Stages {
  const std::vector<FitParameter>& params;
  const std::function<Evaluation(const std::vector<double>&)>& evaluate;
  const Runner& runner;
  const Progress& progress;
  SearchResult& result;
  std::size_t evaluations = 0;
  double best = std::numeric_limits<double>::infinity();

  std::vector<double> values_of(const std::vector<double>& u) const {
    std::vector<double> v(u.size());
    for (std::size_t k = 0; k < u.size(); ++k) v[k] = value_of(params[k], u[k]);
    return v;
  }
  std::vector<double> unit_of_values(const std::vector<double>& v) const {
    std::vector<double> u(params.size(), 0.5);  // a missing value: the middle of its range
    for (std::size_t k = 0; k < v.size() && k < params.size(); ++k) u[k] = unit_of(params[k], v[k]);
    return u;
  }

  /// Runs n work items; work(i, eval) calls eval(u) for each evaluation. Returns each item's records (rank 0), in
  /// item order, and appends them to the result. `stage_of(i)` tells an item's stage, `item_of(i)` its number there.
  std::vector<std::vector<EvaluationRecord>> run(
      Stage stage, std::size_t n, const std::function<Stage(std::size_t)>& stage_of, const std::function<int(std::size_t)>& item_of,
      const std::function<void(std::size_t, const std::function<double(const std::vector<double>&)>&)>& work) {
    std::vector<std::vector<EvaluationRecord>> items(n);
    std::size_t done_items = 0;
    runner.run(
        n,
        [&](std::size_t i) {
          std::vector<ValuedEvaluation> evals;
          work(i, [&](const std::vector<double>& u) {
            std::vector<double> v = values_of(u);
            Evaluation ev = evaluate(v);
            const double f = ev.ok ? ev.objective : std::numeric_limits<double>::infinity();
            evals.emplace_back(std::move(v), std::move(ev));
            return f;
          });
          return evaluations_to_bytes(evals);
        },
        [&](std::size_t i, std::string bytes, int rank) {
          for (auto& [v, ev] : evaluations_from_bytes(bytes)) {
            EvaluationRecord rec;
            rec.stage = stage_of(i);
            rec.item = item_of(i);
            rec.values = std::move(v);
            rec.eval = std::move(ev);
            rec.rank = rank;
            ++evaluations;
            if (rec.eval.ok && rec.eval.objective < best) best = rec.eval.objective;
            items[i].push_back(std::move(rec));
          }
          if (progress) progress(stage, ++done_items, n, evaluations, best);
        });
    for (const auto& item : items)
      for (const auto& rec : item) result.evaluations.push_back(rec);
    return items;
  }

  /// The unit-cube points that rank 0 chose, made every rank's.
  std::vector<std::vector<double>> share(const std::vector<std::vector<double>>& points) const {
    std::string bytes = points_to_bytes(points);
    if (runner.share) runner.share(bytes);
    return points_from_bytes(bytes);
  }

  /// The best ok record so far (the first of equals, in the result's order); null without one.
  const EvaluationRecord* best_record() const {
    const EvaluationRecord* b = nullptr;
    for (const auto& r : result.evaluations)
      if (r.eval.ok && (!b || r.eval.objective < b->eval.objective)) b = &r;
    return b;
  }
};

}  // namespace

SearchResult search(const std::vector<FitParameter>& params, const std::vector<double>& start,
                    const std::function<Evaluation(const std::vector<double>&)>& evaluate, const SearchOptions& opt,
                    const Runner& runner, const Progress& progress) {
  SearchResult result;
  const std::size_t d = params.size();
  if (d == 0) return result;
  Stages st{params, evaluate, runner, progress, result};
  const std::vector<double> u_start = st.unit_of_values(start);

  // 1. The start and the scan points: a grid of cell centres for one parameter, a Halton set for more.
  const std::size_t n_scan = opt.scan < 0 ? 8 * d + 1 : static_cast<std::size_t>(opt.scan);
  std::vector<std::vector<double>> scan_u;
  for (std::size_t i = 0; i < n_scan; ++i)
    scan_u.push_back(d == 1 ? std::vector<double>{(static_cast<double>(i) + 0.5) / static_cast<double>(n_scan)} : halton(i + 1, d));
  st.run(
      Stage::scan, n_scan + 1, [](std::size_t i) { return i == 0 ? Stage::start : Stage::scan; },
      [](std::size_t i) { return i == 0 ? 0 : static_cast<int>(i - 1); },
      [&](std::size_t i, const auto& eval) { eval(i == 0 ? u_start : scan_u[i - 1]); });

  // 2. Local searches from the best `starts` distinct points of stage 1 (the start when none succeeded).
  std::vector<std::vector<double>> starts;
  {
    std::vector<const EvaluationRecord*> ok;
    for (const auto& r : result.evaluations)
      if (r.eval.ok) ok.push_back(&r);
    std::stable_sort(ok.begin(), ok.end(), [](auto* a, auto* b) { return a->eval.objective < b->eval.objective; });
    for (const auto* r : ok) {
      if (static_cast<int>(starts.size()) >= opt.starts) break;
      const auto u = st.unit_of_values(r->values);
      const bool seen = std::any_of(starts.begin(), starts.end(), [&](const auto& s) {
        for (std::size_t k = 0; k < d; ++k)
          if (std::abs(s[k] - u[k]) > opt.xtol) return false;
        return true;
      });
      if (!seen) starts.push_back(u);
    }
    if (starts.empty() && opt.starts > 0) starts.push_back(u_start);
  }
  starts = st.share(starts);
  // The first step: half the scan's spacing along each axis (a quarter of the range without a scan).
  const double per_axis = n_scan > 0 ? std::ceil(std::pow(static_cast<double>(n_scan), 1.0 / static_cast<double>(d))) : 1.0;
  const double step = std::clamp(0.5 / per_axis, 0.02, 0.25);
  st.run(
      Stage::local, starts.size(), [](std::size_t) { return Stage::local; }, [](std::size_t i) { return static_cast<int>(i); },
      [&](std::size_t i, const auto& eval) { local_search(starts[i], opt.max_evals, opt.xtol, step, eval); });

  // 3. Profiles: each parameter across its bounds, the others re-optimised from the best (more than one parameter).
  std::vector<double> u_best = u_start;
  if (const auto* b = st.best_record()) u_best = st.unit_of_values(b->values);
  u_best = st.share({u_best})[0];
  const std::size_t P = opt.profile_points > 0 ? static_cast<std::size_t>(opt.profile_points) : 0;
  auto profile_u = [&](std::size_t p) { return P == 1 ? 0.5 : static_cast<double>(p) / static_cast<double>(P - 1); };
  const int profile_evals = std::max(10, opt.max_evals / 4);  // per profile point, d > 1
  std::vector<std::vector<EvaluationRecord>> profile_items;
  if (P > 0)
    profile_items = st.run(
        Stage::profile, d * P, [](std::size_t) { return Stage::profile; }, [](std::size_t i) { return static_cast<int>(i); },
        [&](std::size_t i, const auto& eval) {
          const std::size_t j = i / P;
          std::vector<double> u = u_best;
          u[j] = profile_u(i % P);
          if (d == 1) {
            eval(u);
            return;
          }
          std::vector<double> others;
          for (std::size_t k = 0; k < d; ++k)
            if (k != j) others.push_back(u_best[k]);
          local_search(others, profile_evals, opt.xtol, step, [&](const std::vector<double>& o) {
            std::vector<double> full(d);
            for (std::size_t k = 0, m = 0; k < d; ++k) full[k] = k == j ? u[j] : o[m++];
            return eval(full);
          });
        });

  // The best of all evaluations, and each profile's interval within factor × best.
  for (const auto& r : result.evaluations) result.failed += !r.eval.ok;
  const EvaluationRecord* b = st.best_record();
  if (!b) return result;
  result.best = b->values;
  result.best_eval = b->eval;
  if (P == 0) return result;
  const std::vector<double> ub = st.unit_of_values(result.best);
  const double threshold = opt.factor * result.best_eval.objective;
  for (std::size_t j = 0; j < d; ++j) {
    // (u_j, objective): each profile point's best evaluation, and the overall best.
    std::vector<std::pair<double, double>> pts{{ub[j], result.best_eval.objective}};
    for (std::size_t p = 0; p < P; ++p) {
      double f = std::numeric_limits<double>::infinity();
      for (const auto& r : profile_items[j * P + p])
        if (r.eval.ok) f = std::min(f, r.eval.objective);
      pts.emplace_back(profile_u(p), f);
    }
    std::stable_sort(pts.begin(), pts.end(), [](const auto& a, const auto& c) { return a.first < c.first; });
    std::vector<double> u, f;
    Profile prof;
    for (const auto& [x, y] : pts) {
      u.push_back(x);
      f.push_back(y);
      prof.values.push_back(value_of(params[j], x));
      prof.objective.push_back(y);
    }
    const auto [lo, hi] = profile_interval(u, f, threshold);
    if (lo) prof.lo = value_of(params[j], *lo);
    if (hi) prof.hi = value_of(params[j], *hi);
    result.profiles.push_back(std::move(prof));
  }
  return result;
}

}  // namespace imcol::calib
