// SPDX-License-Identifier: BSD-3-Clause
// The staged search: scan, local searches, profiles; each stage's work items run on the Runner, their evaluations
// travelling as bytes, the next stage's inputs shared from rank 0.
#include "calibrate/search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "calibrate/confidence.hpp"
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
    case Stage::edge: return "edge";
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
  const Stopped& stopped;
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
            if (stopped && stopped()) return std::numeric_limits<double>::infinity();  // not run, not recorded
            std::vector<double> v = values_of(u);
            Evaluation ev = evaluate(v);
            const double f = ev.ok ? ev.objective : std::numeric_limits<double>::infinity();
            evals.emplace_back(std::move(v), std::move(ev));
            return f;
          });
          return evals.empty() ? std::string() : evaluations_to_bytes(evals);  // empty: stopped before its first
        },
        [&](std::size_t i, std::string bytes, int rank) {
          for (auto& [v, ev] : bytes.empty() ? std::vector<ValuedEvaluation>{} : evaluations_from_bytes(bytes)) {
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

  /// Whether to end the search here: rank 0's answer, every rank's.
  bool halt() const {
    if (!stopped) return false;
    std::string flag = stopped() ? "1" : "0";
    if (runner.share) runner.share(flag);
    return flag == "1";
  }

  /// Counts the failed evaluations and sets the best; false without any success.
  bool set_best() {
    for (const auto& r : result.evaluations) result.failed += !r.eval.ok;
    const EvaluationRecord* b = best_record();
    if (!b) return false;
    result.best = b->values;
    result.best_eval = b->eval;
    return true;
  }
};

/// A work item's best objective (+inf: none succeeded).
double item_best(const std::vector<EvaluationRecord>& item) {
  double f = std::numeric_limits<double>::infinity();
  for (const auto& r : item)
    if (r.eval.ok) f = std::min(f, r.eval.objective);
  return f;
}

/// Rows sorted by u (stable).
void sort_by_u(std::vector<std::pair<double, double>>& p) {
  std::stable_sort(p.begin(), p.end(), [](const auto& a, const auto& c) { return a.first < c.first; });
}

/// Per parameter and side, the bracket (u inside, u outside) of an interval's finite end.
struct Bracket {
  std::size_t j;
  double in, out;
};

/// The stages in order, over the state they share.
struct StagedSearch {
  using Eval = std::function<double(const std::vector<double>&)>;
  Stages& st;
  const SearchOptions& opt;
  std::size_t d;
  std::vector<double> u_start, u_best;
  std::size_t n_scan = 0, P = 0;
  double step = 0;
  int profile_evals = 0;
  std::vector<std::vector<std::pair<double, double>>> pts;  // (u_j, objective) of each parameter's profile (rank 0)
  std::vector<Bracket> brackets;
  std::vector<double> ub;  // the best point when the brackets were set

  StagedSearch(Stages& s, const SearchOptions& o, const std::vector<double>& start)
      : st(s), opt(o), d(s.params.size()), u_start(s.unit_of_values(start)), pts(d) {}

  /// 1. The start and the scan points: a grid of cell centres for one parameter, a Halton set for more.
  void scan() {
    n_scan = opt.scan < 0 ? 8 * d + 1 : static_cast<std::size_t>(opt.scan);
    std::vector<std::vector<double>> scan_u;
    for (std::size_t i = 0; i < n_scan; ++i)
      scan_u.push_back(d == 1 ? std::vector<double>{(static_cast<double>(i) + 0.5) / static_cast<double>(n_scan)} : halton(i + 1, d));
    st.run(
        Stage::scan, n_scan + 1, [](std::size_t i) { return i == 0 ? Stage::start : Stage::scan; },
        [](std::size_t i) { return i == 0 ? 0 : static_cast<int>(i - 1); },
        [&](std::size_t i, const auto& eval) { eval(i == 0 ? u_start : scan_u[i - 1]); });
  }

  /// The best `starts` distinct points of stage 1 (the start when none succeeded), rank 0's.
  std::vector<std::vector<double>> local_starts() const {
    std::vector<std::vector<double>> starts;
    std::vector<const EvaluationRecord*> ok;
    for (const auto& r : st.result.evaluations)
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
    return starts;
  }

  /// 2. Local searches from the shared starts; the first step: half the scan's spacing along each axis (a quarter
  /// of the range without a scan).
  void local() {
    const std::vector<std::vector<double>> starts = st.share(local_starts());
    const double per_axis = n_scan > 0 ? std::ceil(std::pow(static_cast<double>(n_scan), 1.0 / static_cast<double>(d))) : 1.0;
    step = std::clamp(0.5 / per_axis, 0.02, 0.25);
    st.run(
        Stage::local, starts.size(), [](std::size_t) { return Stage::local; }, [](std::size_t i) { return static_cast<int>(i); },
        [&](std::size_t i, const auto& eval) { local_search(starts[i], opt.max_evals, opt.xtol, step, eval); });
  }

  double profile_u(std::size_t p) const { return P == 1 ? 0.5 : static_cast<double>(p) / static_cast<double>(P - 1); }

  /// One profile point: parameter j at u_j, the others at their best (one parameter) or re-optimised from there.
  void profile_point(std::size_t j, double uj, const Eval& eval) const {
    std::vector<double> u = u_best;
    u[j] = uj;
    if (d == 1) {
      eval(u);
      return;
    }
    std::vector<double> others;
    for (std::size_t k = 0; k < d; ++k)
      if (k != j) others.push_back(u_best[k]);
    local_search(others, profile_evals, opt.xtol, step, [&](const std::vector<double>& o) {
      std::vector<double> full(d);
      for (std::size_t k = 0, m = 0; k < d; ++k) full[k] = k == j ? uj : o[m++];
      return eval(full);
    });
  }

  /// 3. Profiles: each parameter across its bounds, the others re-optimised from the best (more than one parameter).
  void profiles() {
    u_best = u_start;
    if (const auto* b = st.best_record()) u_best = st.unit_of_values(b->values);
    u_best = st.share({u_best})[0];
    P = opt.profile_points > 0 ? static_cast<std::size_t>(opt.profile_points) : 0;
    profile_evals = std::max(10, opt.max_evals / 4);  // per profile point, d > 1
    if (P == 0) return;
    const auto items = st.run(
        Stage::profile, d * P, [](std::size_t) { return Stage::profile; }, [](std::size_t i) { return static_cast<int>(i); },
        [&](std::size_t i, const auto& eval) { profile_point(i / P, profile_u(i % P), eval); });
    for (std::size_t i = 0; i < items.size(); ++i) pts[i / P].emplace_back(profile_u(i % P), item_best(items[i]));
  }

  /// The threshold rule: factor × the best so far, the factor given or 1 + q / (n - p).
  void init_rule() {
    FactorRule& rule = st.result.rule;
    rule.given = opt.factor.has_value();
    rule.p = d + static_cast<std::size_t>(std::max(0, opt.inner_parameters));
    if (!rule.given) {
      rule.confidence = opt.confidence;
      rule.q = chi2_1_quantile(opt.confidence);
    }
  }

  void set_threshold(const EvaluationRecord& b) {
    FactorRule& rule = st.result.rule;
    rule.n = b.eval.residuals;
    rule.factor = rule.given ? *opt.factor : confidence_factor(opt.confidence, rule.n, rule.p);
    rule.threshold = rule.factor * b.eval.objective;
  }

  /// Parameter j's brackets from its profile's points so far and the best so far.
  void add_brackets(std::size_t j, const EvaluationRecord& b) {
    const double threshold = st.result.rule.threshold;
    auto p = pts[j];
    p.emplace_back(ub[j], b.eval.objective);
    sort_by_u(p);
    std::size_t m = 0;
    for (std::size_t i = 1; i < p.size(); ++i)
      if (p[i].second < p[m].second) m = i;
    if (!(p[m].second <= threshold)) return;
    for (std::size_t i = m; i-- > 0;)
      if (!(p[i].second <= threshold)) {
        brackets.push_back({j, p[i + 1].first, p[i].first});
        break;
      }
    for (std::size_t i = m + 1; i < p.size(); ++i)
      if (!(p[i].second <= threshold)) {
        brackets.push_back({j, p[i - 1].first, p[i].first});
        break;
      }
  }

  /// The brackets from the best so far (which sets the threshold); none on a rank other than 0.
  void set_brackets() {
    brackets.clear();
    const EvaluationRecord* b = st.best_record();
    if (!b) return;  // none succeeded, or a rank other than 0: rank 0's brackets come shared
    set_threshold(*b);
    ub = st.unit_of_values(b->values);
    for (std::size_t j = 0; j < d; ++j) add_brackets(j, *b);
  }

  /// A bracket is fine enough once it is refine_to of its interval's width, which is at least the span of the
  /// interval's inside points (its ends' inside points and the best).
  bool too_wide(const Bracket& b) const {
    double lo = ub[b.j], hi = ub[b.j];
    for (const auto& c : brackets)
      if (c.j == b.j) lo = std::min(lo, c.in), hi = std::max(hi, c.in);
    return std::abs(b.out - b.in) > opt.refine_to * (hi - lo);
  }

  /// This round's points (j, u_j): the middles of the brackets still too wide, rank 0's, made every rank's.
  std::vector<std::vector<double>> bracket_middles() const {
    std::vector<std::vector<double>> mids;
    for (const auto& b : brackets)
      if (too_wide(b)) mids.push_back({static_cast<double>(b.j), 0.5 * (b.in + b.out)});
    return st.share(mids);
  }

  /// 4. Edges: each round sets the brackets from the profiles and the threshold of the best so far (an edge point
  /// may improve the best, which lowers the threshold) and evaluates their middles as profile points, which join
  /// the profile.
  void edges() {
    int edge_item = 0;
    for (int round = 0;; ++round) {
      set_brackets();
      if (round >= opt.refine) break;
      const std::vector<std::vector<double>> mids = bracket_middles();
      if (mids.empty()) break;
      const int first = edge_item;
      const auto items = st.run(
          Stage::edge, mids.size(), [](std::size_t) { return Stage::edge; }, [first](std::size_t i) { return first + static_cast<int>(i); },
          [&](std::size_t i, const auto& eval) { profile_point(static_cast<std::size_t>(mids[i][0]), mids[i][1], eval); });
      edge_item += static_cast<int>(mids.size());
      for (std::size_t i = 0; i < items.size(); ++i) pts[static_cast<std::size_t>(mids[i][0])].emplace_back(mids[i][1], item_best(items[i]));
    }
  }

  /// Parameter j's profile and its interval within factor × best: the profile's points and the refined ends' (an
  /// end's last bracket holds no other point, so the end is interpolated inside it).
  Profile profile_of(std::size_t j, const std::vector<double>& u_final) const {
    const FitParameter& param = st.params[j];
    auto p = pts[j];
    p.emplace_back(u_final[j], st.result.best_eval.objective);
    sort_by_u(p);
    std::vector<double> u, f;
    Profile prof;
    for (const auto& [x, y] : p) {
      u.push_back(x);
      f.push_back(y);
      prof.values.push_back(value_of(param, x));
      prof.objective.push_back(y);
    }
    const auto [lo, hi] = profile_interval(u, f, st.result.rule.threshold);
    if (lo) prof.lo = value_of(param, *lo);
    if (hi) prof.hi = value_of(param, *hi);
    for (const auto& b : brackets)
      if (b.j == j && too_wide(b)) prof.resolved = false;
    return prof;
  }

  void intervals() {
    const std::vector<double> u_final = st.unit_of_values(st.result.best);
    for (std::size_t j = 0; j < d; ++j) st.result.profiles.push_back(profile_of(j, u_final));
  }
};

}  // namespace

SearchResult search(const std::vector<FitParameter>& params, const std::vector<double>& start,
                    const std::function<Evaluation(const std::vector<double>&)>& evaluate, const SearchOptions& opt,
                    const Runner& runner, const Progress& progress, const Stopped& stopped) {
  SearchResult result;
  if (params.empty()) return result;
  Stages st{params, evaluate, runner, progress, stopped, result};
  StagedSearch s(st, opt, start);
  auto stop_here = [&] {
    if (!st.halt()) return false;
    st.set_best();
    result.stopped = true;
    return true;
  };
  s.scan();
  if (stop_here()) return result;
  s.local();
  if (stop_here()) return result;
  s.profiles();
  if (s.P == 0) {
    st.set_best();
    return result;
  }
  if (stop_here()) return result;
  s.init_rule();
  s.edges();
  if (stop_here()) return result;
  if (st.set_best()) s.intervals();
  return result;
}

}  // namespace imcol::calib
