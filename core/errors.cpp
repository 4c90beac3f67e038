#include "core/errors.hpp"

namespace imcol {

namespace {
std::string compose(const std::string& where, const std::string& key, const std::string& problem) {
  std::string s = where;
  if (!key.empty()) s += (s.empty() ? "" : ": ") + std::string("key '") + key + "'";
  if (!s.empty()) s += ": ";
  return s + problem;
}
}  // namespace

InputError::InputError(std::string where, std::string key, const std::string& problem)
    : std::runtime_error(compose(where, key, problem)), where_(std::move(where)), key_(std::move(key)) {}

}  // namespace imcol
