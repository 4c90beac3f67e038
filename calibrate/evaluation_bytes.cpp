// SPDX-License-Identifier: BSD-3-Clause
#include "calibrate/evaluation_bytes.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

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
  std::vector<ValuedEvaluation> out;
  for (const auto& j : nlohmann::json::parse(bytes)) {
    Evaluation ev;
    ev.ok = j.at("ok").get<bool>();
    ev.objective = number_or(j.at("objective"), inf);
    ev.rms = number_or(j.at("rms"), inf);
    if (j.at("tau").is_number()) ev.tau = j["tau"].get<double>();
    ev.residuals = j.at("residuals").get<std::size_t>();
    for (const auto& e : j.at("e_sim")) ev.e_sim.push_back(number_or(e, nan));
    ev.message = j.at("message").get<std::string>();
    ev.wall_s = j.at("wall_s").get<double>();
    out.emplace_back(j.at("values").get<std::vector<double>>(), std::move(ev));
  }
  return out;
}

std::string points_to_bytes(const std::vector<std::vector<double>>& points) { return nlohmann::json(points).dump(); }

std::vector<std::vector<double>> points_from_bytes(const std::string& bytes) {
  return nlohmann::json::parse(bytes).get<std::vector<std::vector<double>>>();
}

}  // namespace imcol::calib
