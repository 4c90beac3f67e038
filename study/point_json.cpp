// SPDX-License-Identifier: BSD-3-Clause
#include "study/point_json.hpp"

namespace imcol::study {

namespace {

/// The summary of a run that ran; null otherwise.
run::Json summary_or_null(bool ran, const RunSummary& s) { return ran ? run::Json(s) : run::Json(nullptr); }

RunSummary summary_of(const run::Json& j) { return j.is_null() ? RunSummary{} : j.get<RunSummary>(); }

}  // namespace

void to_json(run::Json& j, const SweepPoint& p) {
  j = {{"ok", p.ok}, {"value", p.value}, {"message", p.message}, {"summary", summary_or_null(p.ok, p.summary)}};
}

void from_json(const run::Json& j, SweepPoint& p) {
  p.ok = j.at("ok").get<bool>();
  p.value = j.at("value").get<double>();
  p.message = j.at("message").get<std::string>();
  p.summary = summary_of(j.at("summary"));
}

void to_json(run::Json& j, const HistoryCell& c) {
  j = {{"point", c.point},         {"value", c.value},     {"kernel", c.series.kernel},
       {"evaluator", c.series.evaluator}, {"status", c.status}, {"message", c.message},
       {"summary", summary_or_null(c.ok(), c.summary)}};
}

void from_json(const run::Json& j, HistoryCell& c) {
  c.point = j.at("point").get<int>();
  c.value = j.at("value").get<double>();
  c.series.kernel = j.at("kernel").get<std::string>();
  c.series.evaluator = j.at("evaluator").get<std::string>();
  c.status = j.at("status").get<std::string>();
  c.message = j.at("message").get<std::string>();
  c.summary = summary_of(j.at("summary"));
}

}  // namespace imcol::study
