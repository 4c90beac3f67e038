// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON edge's small pieces: a measured value or JSON null ("not measured"; JSON has no NaN or infinity either),
// optional keys written only when present, and the same read back.
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/choices.hpp"

namespace imcol::run {

using Json = nlohmann::ordered_json;

inline Json or_null(const std::optional<double>& v) { return v ? Json(*v) : Json(nullptr); }
inline Json or_null(const std::optional<std::string>& v) { return v ? Json(*v) : Json(nullptr); }

inline Json finite_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

inline Json finite_or_null(const std::optional<double>& v) { return v ? finite_or_null(*v) : Json(nullptr); }

/// A choice (core/choices.hpp) from its name in JSON; an unknown name is std::invalid_argument.
template <class E>
E choice_of(const Json& j) {
  const auto s = j.get<std::string>();
  if (const auto v = choice_from_string<E>(s)) return *v;
  throw std::invalid_argument("unknown name in a run's summary: " + s);
}

/// j[key] = *v when v holds a value; nothing otherwise.
template <class T>
void put_if(Json& j, const char* key, const std::optional<T>& v) {
  if (v) j[key] = *v;
}

/// j[key] as T; none when the key is absent or null.
template <class T>
std::optional<T> get_opt(const Json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return std::nullopt;
  return it->template get<T>();
}

}  // namespace imcol::run
