// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A struct's fields to JSON and back with one list of them: fields(io, s) calls io("name", s.name) for each, and
// FieldsOut / FieldsIn write or read them. std::optional is null or its value; pairs are arrays of two; enums numbers.
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace imcol::study {

template <class T> nlohmann::json field_out(const T& v);
template <class T> nlohmann::json field_out(const std::optional<T>& v);
template <class A, class B> nlohmann::json field_out(const std::pair<A, B>& v);
template <class T> nlohmann::json field_out(const std::vector<T>& v);
template <class T> void field_in(const nlohmann::json& j, T& v);
template <class T> void field_in(const nlohmann::json& j, std::optional<T>& v);
template <class A, class B> void field_in(const nlohmann::json& j, std::pair<A, B>& v);
template <class T> void field_in(const nlohmann::json& j, std::vector<T>& v);

template <class T>
nlohmann::json field_out(const T& v) {
  if constexpr (std::is_enum_v<T>) return static_cast<std::underlying_type_t<T>>(v);
  else return nlohmann::json(v);
}
template <class T>
nlohmann::json field_out(const std::optional<T>& v) {
  return v ? field_out(*v) : nlohmann::json(nullptr);
}
template <class A, class B>
nlohmann::json field_out(const std::pair<A, B>& v) {
  return nlohmann::json::array({field_out(v.first), field_out(v.second)});
}
template <class T>
nlohmann::json field_out(const std::vector<T>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& x : v) a.push_back(field_out(x));
  return a;
}

template <class T>
void field_in(const nlohmann::json& j, T& v) {
  if constexpr (std::is_enum_v<T>) v = static_cast<T>(j.get<std::underlying_type_t<T>>());
  else j.get_to(v);
}
template <class T>
void field_in(const nlohmann::json& j, std::optional<T>& v) {
  if (j.is_null()) return v.reset();
  field_in(j, v.emplace());
}
template <class A, class B>
void field_in(const nlohmann::json& j, std::pair<A, B>& v) {
  field_in(j.at(0), v.first);
  field_in(j.at(1), v.second);
}
template <class T>
void field_in(const nlohmann::json& j, std::vector<T>& v) {
  v.assign(j.size(), T{});
  for (std::size_t i = 0; i < v.size(); ++i) field_in(j[i], v[i]);
}

struct FieldsOut {
  nlohmann::json& j;
  template <class T>
  void operator()(const char* name, const T& v) { j[name] = field_out(v); }
};
struct FieldsIn {
  const nlohmann::json& j;
  template <class T>
  void operator()(const char* name, T& v) { field_in(j.at(name), v); }
};

}  // namespace imcol::study
