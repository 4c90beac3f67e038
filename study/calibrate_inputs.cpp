// SPDX-License-Identifier: BSD-3-Clause
#include "study/calibrate_inputs.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <tuple>
#include <variant>

#include "core/errors.hpp"
#include "core/text_file.hpp"
#include "study/scene_value.hpp"

namespace imcol::study {

using calib::FitParameter;
using calib::MeasuredTable;
using calib::MeasuredTrajectory;
using calib::Measurement;
using calib::TrajectoryWindow;

namespace {

std::optional<double> parse_number(const std::string& s) {
  const char* c = s.c_str();
  char* end = nullptr;
  const double v = std::strtod(c, &end);
  if (s.empty() || end == c || *end != '\0' || std::isspace(static_cast<unsigned char>(s[0])) || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// --window A:B: seconds before (A < 0) and after (B > 0) the measured contact.
std::pair<double, double> parse_window(const std::string& text) {
  auto bad = [&](const std::string& why) { throw InputError("command line", "--window", why + " (got '" + text + "')"); };
  const auto colon = text.find(':');
  if (colon == std::string::npos) bad("expected A:B, seconds before and after the measured contact (e.g. -0.01:0.02)");
  const auto a = parse_number(text.substr(0, colon)), b = parse_number(text.substr(colon + 1));
  if (!a || !b) bad("A and B must be finite numbers (seconds), as in -0.01:0.02");
  if (!(*a < 0)) bad("A must be negative: the window starts before the measured contact");
  if (!(*b > 0)) bad("B must be positive: the window ends after the measured contact");
  return {*a, *b};
}

/// A table's rows: no fitted key among its columns (a row's value would replace the fitted one), and every row's
/// scene valid (calib::check_table_keys: InputError naming the row's line).
void check_table(const MeasuredTable& t, const std::string& scene_path, const std::vector<Override>& overrides,
                 const std::vector<FitParameter>& params) {
  for (const auto& p : params)
    if (std::find(t.keys.begin(), t.keys.end(), p.key) != t.keys.end())
      throw InputError("command line", "--fit", p.key + " is a column of " + t.path + ": each row sets it, so it cannot be fitted");
  calib::check_table_keys(t, scene_path, overrides);
}

/// The search starts at the scene's own values, clamped into the bounds; a key the scene leaves to a default it does
/// not hold starts at the middle of its range (the geometric middle on a log scale).
std::vector<StartValue> start_values(const CalibrationInputs& in) {
  std::vector<StartValue> out;
  for (const auto& p : in.params) {
    StartValue s;
    if (const auto v = scene_value(in.scene_path, in.overrides, in.base, p.key)) {
      s.scene = *v;
      s.value = std::clamp(*v, p.lo, p.hi);
      s.from = *v == s.value ? "scene" : "scene, clamped to the bounds";
    } else {
      s.value = calib::value_of(p, 0.5);
      s.from = "middle of the bounds (the scene does not set the key)";
    }
    out.push_back(s);
  }
  return out;
}

/// The residuals the objective averages: the window's samples times the measured columns, or the table's rows.
std::size_t residual_count(const Measurement& m, const std::optional<TrajectoryWindow>& w) {
  if (const auto* t = std::get_if<MeasuredTrajectory>(&m)) {
    const auto [k0, k1] = calib::window_rows(*t, *w);
    return (k1 - k0) * t->columns.size();
  }
  return std::get<MeasuredTable>(m).e.size();
}

/// The fitted keys (--fit), each once.
void read_parameters(CalibrationInputs& in, const CalibrationOptions& opt) {
  if (opt.fits.empty()) throw InputError("command line", "--fit", "give at least one parameter: --fit KEY=LO:HI[:log]");
  for (const auto& f : opt.fits) {
    FitParameter p = calib::parse_fit_parameter(f, in.scene_path, in.overrides);
    for (const auto& q : in.params)
      if (q.key == p.key) throw InputError("command line", "--fit", p.key + " is given twice");
    in.params.push_back(p);
  }
  if (opt.search.profile_points == 1) throw InputError("command line", "--profile-points", "must be 0 (no profiles) or at least 2 (got 1)");
}

/// The window's bounds as given (--window), or none.
std::pair<std::optional<double>, std::optional<double>> window_bounds(const CalibrationOptions& opt) {
  std::optional<double> before, after;
  if (!opt.window.empty()) std::tie(before, after) = parse_window(opt.window);
  return {before, after};
}

/// The measurement (--data) and a trajectory's window, or a table's rows checked.
void read_data(CalibrationInputs& in, const CalibrationOptions& opt) {
  in.data_path = opt.data;
  in.data_text = read_text_file(opt.data, "measurement", calib::kMaxMeasurementBytes, "CSV");
  in.data = calib::parse_measurement(opt.data, in.data_text);
  if (!in.trajectory() && (!opt.window.empty() || opt.offset_max))
    throw InputError("command line", opt.window.empty() ? "--offset-max" : "--window",
                     "applies to a trajectory; " + opt.data + " is an e table");
  const auto [before, after] = window_bounds(opt);
  if (in.trajectory())
    in.window = calib::trajectory_window(std::get<MeasuredTrajectory>(in.data), in.base, before, after, opt.offset_max);
  else
    check_table(std::get<MeasuredTable>(in.data), in.scene_path, in.overrides, in.params);
}

/// The held-out measurement (--validate), of the same kind as the fitted one.
void read_held_out(CalibrationInputs& in, const CalibrationOptions& opt) {
  if (opt.validate.empty()) return;
  in.held_out_path = opt.validate;
  in.held_out = calib::read_measurement(opt.validate);
  if (in.held_out->index() != in.data.index())
    throw InputError("command line", "--validate",
                     opt.validate + " is " + kind_of(*in.held_out) + " but " + opt.data + " (--data) is " + kind_of(in.data) +
                         ": the validation is a measurement of the same kind");
  const auto [before, after] = window_bounds(opt);
  if (in.trajectory())
    in.held_window = calib::trajectory_window(std::get<MeasuredTrajectory>(*in.held_out), in.base, before, after, opt.offset_max);
  else
    check_table(std::get<MeasuredTable>(*in.held_out), in.scene_path, in.overrides, in.params);
}

/// The default interval estimates the noise from the best fit's residuals: more of them than fitted parameters.
void check_residuals(const CalibrationInputs& in, const CalibrationOptions& opt) {
  const bool trajectory = in.trajectory();
  const std::size_t n = residual_count(in.data, in.window), p = in.params.size() + (trajectory ? 1 : 0);
  if (opt.search.profile_points > 0 && !opt.search.factor && n <= p)
    throw InputError(opt.data, "",
                     std::to_string(n) + " residuals" + (trajectory ? " in the window" : "") + " for " + std::to_string(p) +
                         " fitted parameters" + (trajectory ? " (the time offset among them)" : "") +
                         ": too few to fit them and estimate the noise for the confidence interval; give more data, or "
                         "--factor F to set the interval's factor directly");
}

}  // namespace

bool CalibrationInputs::trajectory() const { return std::holds_alternative<MeasuredTrajectory>(data); }

const char* kind_of(const Measurement& m) { return std::holds_alternative<MeasuredTrajectory>(m) ? "a trajectory" : "an e table"; }

CalibrationInputs read_calibration_inputs(const std::string& scene_path, const std::vector<Override>& overrides,
                                          const CalibrationOptions& opt) {
  CalibrationInputs in;
  in.scene_path = scene_path;
  in.overrides = overrides;
  in.base = load_scene(scene_path, overrides);
  read_parameters(in, opt);
  read_data(in, opt);
  read_held_out(in, opt);
  check_residuals(in, opt);
  in.start = start_values(in);
  in.search = opt.search;
  in.search.inner_parameters = in.trajectory() ? 1 : 0;  // the time offset tau, fitted in every evaluation
  return in;
}

}  // namespace imcol::study
