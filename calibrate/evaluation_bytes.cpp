// SPDX-License-Identifier: BSD-3-Clause
#include "calibrate/evaluation_bytes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace imcol::calib {

namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
double number_or(const nlohmann::json& j, double missing) { return j.is_number() ? j.get<double>() : missing; }

}  // namespace

std::string evaluations_to_bytes(const std::vector<ValuedEvaluation>& evals) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& [values, ev] : evals) {
    nlohmann::json e_sim = nlohmann::json::array();
    for (double e : ev.e_sim) e_sim.push_back(number(e));
    a.push_back({{"values", values},
                 {"ok", ev.ok},
                 {"objective", number(ev.objective)},
                 {"rms", number(ev.rms)},
                 {"tau", ev.tau ? number(*ev.tau) : nlohmann::json(nullptr)},
                 {"residuals", ev.residuals},
                 {"e_sim", e_sim},
                 {"message", ev.message},
                 {"wall_s", ev.wall_s}});
  }
  // Invalid UTF-8 in a message (a path) is replaced rather than thrown.
  return a.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::vector<ValuedEvaluation> evaluations_from_bytes(const std::string& bytes) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  nlohmann::json all;
  try {
    all = nlohmann::json::parse(bytes);
  } catch (const nlohmann::json::exception&) {
    throw std::invalid_argument("not JSON");
  }
  if (!all.is_array() || all.empty()) throw std::invalid_argument("not a list of evaluations");
  std::vector<ValuedEvaluation> out;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto& j = all[i];
    const std::string which = "evaluation " + std::to_string(i + 1);
    auto bad = [&](const std::string& field, const std::string& must) {
      const std::string got = j.is_object() && j.contains(field) ? j[field].dump() : "nothing";
      throw std::invalid_argument(which + ": '" + field + "' must be " + must + " (got " + got + ")");
    };
    auto field = [&](const char* name) -> const nlohmann::json& {
      if (!j.is_object() || !j.contains(name)) bad(name, "given");
      return j[name];
    };
    auto finite = [](const nlohmann::json& v) { return v.is_number() && std::isfinite(v.get<double>()); };
    auto measure = [&](const char* name) {  // an objective or rms: a number >= 0 of an evaluation that succeeded
      const auto& v = field(name);
      if (!finite(v) || v.get<double>() < 0) bad(name, "a finite number >= 0 in an evaluation that succeeded");
      return v.get<double>();
    };
    Evaluation ev;
    if (!field("ok").is_boolean()) bad("ok", "true or false");
    ev.ok = j["ok"].get<bool>();
    // A failed evaluation has no objective: whatever stands there, it counts as none.
    ev.objective = ev.ok ? measure("objective") : inf;
    ev.rms = ev.ok ? measure("rms") : inf;
    if (finite(field("tau"))) ev.tau = j["tau"].get<double>();
    else if (!j["tau"].is_null()) bad("tau", "a finite number or null");
    if (!field("residuals").is_number_unsigned()) bad("residuals", "a count");
    ev.residuals = j["residuals"].get<std::size_t>();
    if (!field("e_sim").is_array()) bad("e_sim", "a list of numbers or null");
    for (const auto& e : j["e_sim"]) {
      if (!e.is_null() && !finite(e)) bad("e_sim", "a list of numbers or null");
      ev.e_sim.push_back(number_or(e, nan));
    }
    if (!field("message").is_string()) bad("message", "a string");
    ev.message = j["message"].get<std::string>();
    if (!finite(field("wall_s")) || j["wall_s"].get<double>() < 0) bad("wall_s", "a finite number >= 0");
    ev.wall_s = j["wall_s"].get<double>();
    const auto& values = field("values");
    if (!values.is_array() || values.empty() || !std::all_of(values.begin(), values.end(), finite))
      bad("values", "a list of finite parameter values");
    out.emplace_back(values.get<std::vector<double>>(), std::move(ev));
  }
  return out;
}

std::string points_to_bytes(const std::vector<std::vector<double>>& points) { return nlohmann::json(points).dump(); }

std::vector<std::vector<double>> points_from_bytes(const std::string& bytes) {
  return nlohmann::json::parse(bytes).get<std::vector<std::vector<double>>>();
}

}  // namespace imcol::calib
