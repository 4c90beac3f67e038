// SPDX-License-Identifier: BSD-3-Clause
#include "apps/calibrate_progress.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "apps/format.hpp"

namespace imcol {

ProgressLine::ProgressLine(bool show, std::size_t d, const calib::SearchOptions& opt, int workers, std::string unit)
    : show_(show), d_(d), opt_(opt), workers_(std::max(1, workers)), unit_(std::move(unit)), start_(WallClock::now()) {}

void ProgressLine::add_evaluation(double wall_s) {
  std::lock_guard lock(mu_);
  eval_wall_ += wall_s;
  ++eval_count_;
}

calib::Progress ProgressLine::callback() {
  return [this](calib::Stage s, std::size_t done, std::size_t items, std::size_t evaluations, double best) {
    update(s, done, items, evaluations, best);
  };
}

/// The time left: the stage's remaining items at the pace of its finished ones (or, before one has finished, as
/// the later stages are estimated), then the later stages: each work item one evaluation (scan, the profile of one
/// parameter), or a local search of up to --max-evals evaluations (the profile of several parameters: a short one,
/// taken as a quarter of that), run `workers` at a time; the edges as `refine` rounds of 2 d profile points. A guide,
/// not a promise: local searches often stop early.
double ProgressLine::time_left(calib::Stage s, std::size_t done, std::size_t items, double t) const {
  const double t_eval = eval_count_ ? eval_wall_ / static_cast<double>(eval_count_) : 0;
  auto rounds = [&](double n) { return std::ceil(n / workers_); };
  const double local_evals = std::max(1, opt_.max_evals);
  const double profile_evals = d_ > 1 ? std::max(1.0, local_evals / 4) : 1.0;
  const double profile_items = opt_.profile_points > 0 ? static_cast<double>(d_) * opt_.profile_points : 0;
  const double local_items = opt_.starts;
  const double edge_items = opt_.profile_points > 0 ? 2.0 * static_cast<double>(d_) : 0;  // at most, each round
  double left = 0;
  // This stage, from the end of the one before it.
  study::StageTimes before = times_;
  before.end[static_cast<std::size_t>(s)] = NAN;
  double from = 0;
  for (double e : before.end)
    if (std::isfinite(e) && e < t) from = std::max(from, e);
  const double per_item = done ? (t - from) / static_cast<double>(done) : 0;
  left += per_item * static_cast<double>(items - std::min(done, items));
  // The stages after it.
  if (s == calib::Stage::start || s == calib::Stage::scan) left += rounds(local_items) * local_evals * t_eval;
  if (s != calib::Stage::profile && s != calib::Stage::edge) left += rounds(profile_items) * profile_evals * t_eval;
  if (s != calib::Stage::edge) left += opt_.refine * rounds(edge_items) * profile_evals * t_eval;
  return left;
}

void ProgressLine::update(calib::Stage s, std::size_t done, std::size_t items, std::size_t evaluations, double best) {
  std::lock_guard lock(mu_);
  const double t = seconds_since(start_);
  times_.end[static_cast<std::size_t>(s)] = t;
  if (!show_) return;
  std::ostringstream line;
  line << "\r  calibrate " << calib::stage_name(s) << ": " << done << "/" << items << " items, " << evaluations << " evaluations, best rms "
       << sci(std::isfinite(best) ? std::sqrt(best) : NAN, 2) << (unit_.empty() ? "" : " " + unit_) << ", " << fixed(t, 1) << " s, ~"
       << fixed(time_left(s, done, items, t), 0) << " s left   ";
  std::cerr << line.str() << std::flush;
  drawn_ = true;
}

void ProgressLine::finish() {
  std::lock_guard lock(mu_);
  if (drawn_) std::cerr << "\n";
  drawn_ = false;
}

}  // namespace imcol
