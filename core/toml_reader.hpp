// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading one TOML table with checks (toml++): every error names the file and line (or the command
// line, for an override without a source) and the dotted key; keys never read are reported as unknown.
// Shared by the collision-scene reader (core/scene.cpp) and the flow-scene reader (flow/flow_scene.cpp).
#include <toml++/toml.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <algorithm>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/choices.hpp"
#include "core/close_names.hpp"
#include "core/errors.hpp"
#include "core/text_file.hpp"

namespace imcol {

/// The text of a scene file: a regular file of at most 1 MiB (a directory, a device such as /dev/zero, a FIFO or
/// a huge file is refused with exit status 2 before anything is read into memory).
inline constexpr std::uintmax_t kMaxSceneBytes = 1u << 20;
inline std::string read_scene_file(const std::string& path) { return read_text_file(path, "scene", kMaxSceneBytes, "TOML"); }

/// The place an error names for a value that has no line in the scene file: an override (--set, --rtol, ...).
inline constexpr const char* kOverridePlace = "command line (--set/--rtol/--atol/--integrator)";

class TableReader {
 public:
  /// `unsourced`: the place named for a value that has no line in the file (a command-line override).
  TableReader(const toml::table& t, std::string prefix, const std::string& file, std::string unsourced = kOverridePlace)
      : t_(t), prefix_(std::move(prefix)), file_(file), unsourced_(std::move(unsourced)) {}
  /// A table whose keys are `known`: a key not among them is reported at once, before any other key is read (so a
  /// misspelt key is named, not the key it was meant to be as missing); reading a key not declared is a logic error.
  TableReader(const toml::table& t, std::string prefix, const std::string& file, const std::vector<std::string>& known)
      : TableReader(t, std::move(prefix), file) {
    known_ = &known;
    for (auto&& [k, v] : t_)
      if (!declared(std::string(k.str()))) unknown(std::string(k.str()), v);
  }

  std::string full(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }

  std::string where(const toml::node* n) const {
    const toml::node* at = n ? n : &t_;
    auto line = at->source().begin.line;
    if (line == 0) return n ? unsourced_ : file_;
    return file_ + ":" + std::to_string(line);
  }

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw InputError(where(t_.get(key)), full(key), problem);
  }

  const toml::node* node(const std::string& key) {
    check_declared(key);
    used_.insert(key);
    return t_.get(key);
  }
  bool has(const std::string& key) const {
    check_declared(key);
    return t_.contains(key);
  }

  std::optional<double> number(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (n->is_number()) {
      // An integer beyond 2^53 is still a number: round it (toml++'s value<double>() refuses it).
      const double v = n->is_integer() ? static_cast<double>(*n->value<int64_t>()) : *n->value<double>();
      if (!std::isfinite(v) || std::abs(v) > 1e30) fail(key, "must be a finite number of magnitude at most 1e30");
      // A nonzero magnitude below 1e-30 is no physical quantity of a scene, and squares or products of it underflow.
      if (v != 0 && std::abs(v) < 1e-30) fail(key, "must be 0 or of magnitude at least 1e-30 (got " + fmt_number(v) + ")");
      return v;
    }
    fail(key, "must be a number");
  }
  double number(const std::string& key, double fallback) { return number(key).value_or(fallback); }
  double required_number(const std::string& key) {
    auto v = number(key);
    if (!v) throw InputError(where(nullptr), full(key), "missing (required)");
    return *v;
  }
  double required_positive(const std::string& key) {
    const double v = required_number(key);
    positive(key, v);
    return v;
  }
  std::optional<std::string> string(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (auto v = n->value<std::string>(); v && n->is_string()) return *v;
    fail(key, "must be a string");
  }
  std::optional<long> integer(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (n->is_integer()) return static_cast<long>(*n->value<int64_t>());
    fail(key, "must be an integer");
  }
  long integer(const std::string& key, long fallback) { return integer(key).value_or(fallback); }
  bool boolean(const std::string& key, bool fallback) {
    const toml::node* n = node(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(key, "must be true or false");
    return *n->value<bool>();
  }
  const toml::table* table(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return nullptr;
    if (!n->is_table()) fail(key, "must be a table");
    return n->as_table();
  }
  void finish() const {
    for (auto&& [k, v] : t_) {
      std::string key(k.str());
      if (!used_.count(key)) unknown(key, v);
    }
  }

  // Checks
  void positive(const std::string& key, double v) const {
    if (!(v > 0)) fail(key, "must be > 0 (got " + fmt_number(v) + ")");
    if (v < 1e-30) fail(key, "must be at least 1e-30 (got " + fmt_number(v) + ")");
  }
  void in_range(const std::string& key, double v, double lo, double hi, bool lo_open, bool hi_open) const {
    bool ok = (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    if (!ok)
      fail(key, "must be in " + std::string(lo_open ? "(" : "[") + fmt_number(lo) + ", " + fmt_number(hi) + (hi_open ? ")" : "]") +
                    " (got " + fmt_number(v) + ")");
  }
  /// Reads the number `key` into `field` (kept when the key is absent) and checks it lies in the stated interval.
  void number_in(const std::string& key, double& field, double lo, double hi, bool lo_open, bool hi_open) {
    field = number(key, field);
    in_range(key, field, lo, hi, lo_open, hi_open);
  }
  /// Reads the choice `key` into `out` (kept when the key is absent); an unknown spelling fails with the options.
  template <class E>
  void choice(const std::string& key, E& out) {
    const auto v = string(key);
    if (!v) return;
    if (auto e = choice_from_string<E>(*v)) {
      out = *e;
      return;
    }
    std::string list;
    for (const auto& [e, name] : ChoiceNames<E>::list) list += (list.empty() ? "" : " | ") + std::string(name);
    fail(key, "unknown choice '" + *v + "' (expected " + list + ")" + did_you_mean(*v, choice_names<E>()));
  }


 private:
  const toml::table& t_;
  std::string prefix_;
  const std::string& file_;
  std::string unsourced_;
  std::set<std::string> used_;
  const std::vector<std::string>* known_ = nullptr;  // the table's keys, when declared

  bool declared(const std::string& key) const { return !known_ || std::find(known_->begin(), known_->end(), key) != known_->end(); }
  void check_declared(const std::string& key) const {
    if (!declared(key)) throw std::logic_error("the reader of table '" + prefix_ + "' reads the undeclared key '" + key + "'");
  }
  /// An unknown key, at its line, with the close keys of the table (the declared ones, else those read so far).
  [[noreturn]] void unknown(const std::string& key, const toml::node& at) const {
    const std::vector<std::string> keys = known_ ? *known_ : std::vector<std::string>(used_.begin(), used_.end());
    throw InputError(where(&at), full(key), "unknown key" + did_you_mean(key, keys));
  }
};

}  // namespace imcol
