// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The evaluation cache of `imcol calibrate --cache FILE` (docs/calibration.md): a text file whose first line (JSON)
// says what its evaluations were made for (imcol's version, the scene file's text, the overrides, the fitted keys,
// the measurement file's text, the trajectory window), then one line per finished work item: its new evaluations
// as calibrate/evaluation_bytes.hpp writes them. A search given the file takes each evaluation it holds instead
// of running it; the search is deterministic, so a calibration killed part-way, or run again with more profile
// points or refinement rounds, runs only the evaluations it has not seen.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "calibrate/evaluation_bytes.hpp"

namespace imcol::calib {

/// The largest cache file read (256 MiB: about a million evaluations of a trajectory fit).
inline constexpr std::uintmax_t kMaxCacheBytes = std::uintmax_t{256} << 20;

/// What a cache's evaluations depend on; each field's value is compared as it is (texts by a hash).
struct CacheContext {
  std::string imcol_version;
  std::string scene_text, measurement_text;
  std::vector<std::string> overrides;     // KEY=VALUE, in order
  std::vector<std::string> fit_keys;      // the order of an evaluation's values
  std::vector<double> window;             // t_contact, before, after, tau_max (s); empty for an e table
};

/// The header line of a cache made for `c`.
nlohmann::ordered_json cache_header(const CacheContext& c);

/// A cache file's evaluations, read once; find() is safe from any thread.
class EvaluationCache {
 public:
  EvaluationCache() = default;
  /// `text` is the file `path`'s content ("" for a file not there yet). InputError (the file, its header or line)
  /// for a header made for another context, naming what differs, or a line that is not an item's evaluations (not
  /// JSON, a field missing or of another type, a succeeded evaluation without a finite objective >= 0, another count
  /// of parameter values than the fitted keys), naming the evaluation and field; a last line without its newline that
  /// is not JSON (a write a kill cut short) is left out, and a writer drops it.
  EvaluationCache(const std::string& path, const std::string& text, const CacheContext& context);

  std::optional<Evaluation> find(const std::vector<double>& values) const;
  bool contains(const std::vector<double>& values) const { return entries_.count(values) > 0; }
  std::set<std::vector<double>> keys() const;
  std::size_t size() const { return entries_.size(); }
  bool has_header() const { return has_header_; }
  std::size_t bytes() const { return bytes_; }              // the text read
  std::size_t whole_bytes() const { return whole_bytes_; }  // the text up to the end of its last whole line
  bool cut_short() const { return whole_bytes_ < bytes_; }  // a last line was left out
  bool unended() const { return unended_; }                 // a whole last line lacks its newline

 private:
  std::map<std::vector<double>, Evaluation> entries_;
  bool has_header_ = false, unended_ = false;
  std::size_t bytes_ = 0, whole_bytes_ = 0;
};

/// Appends to a cache file (the deciding process alone): the header when the file has none, then each finished item's
/// evaluations that the file does not hold yet, flushed line by line. `read` is the file as read before.
class CacheWriter {
 public:
  /// Holds the file's lock (flock) while it lives. InputError(path) when another process holds it, when the file
  /// changed since `read`, or when it cannot be opened for appending. A line `read` left out is removed first.
  CacheWriter(const std::string& path, const EvaluationCache& read, const CacheContext& context);
  ~CacheWriter();
  CacheWriter(const CacheWriter&) = delete;
  CacheWriter& operator=(const CacheWriter&) = delete;
  void add_item(const std::string& item_bytes);
  std::size_t added() const { return added_; }

 private:
  int lock_fd_ = -1;
  std::ofstream out_;
  std::set<std::vector<double>> held_;  // the file's evaluations, read or written
  std::size_t added_ = 0;
  std::mutex mu_;
};

}  // namespace imcol::calib
