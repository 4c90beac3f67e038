// SPDX-License-Identifier: BSD-3-Clause
#include "calibrate/evaluation_cache.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <sstream>
#include <utility>

#include "core/errors.hpp"

namespace imcol::calib {

namespace {

constexpr const char* kTag = "imcol_calibrate_cache";

std::string text_hash(const std::string& text) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016zx", std::hash<std::string>{}(text));
  return buf;
}

/// The header's fields after the tag, and what each says, for the message naming the one that differs.
const std::pair<const char*, const char*> kFields[] = {
    {"imcol", "imcol's version"},
    {"scene_text_hash", "scene file's text"},
    {"overrides", "overrides (--set and the tolerance options)"},
    {"fit", "fitted keys (--fit, in their order)"},
    {"measurement_text_hash", "measurement file's text (--data)"},
    {"window", "trajectory window (--window, --offset-max, the measured contact)"},
};

/// The message of a damaged line: what is wrong, and what to do.
std::string damaged(const std::string& problem) {
  return problem + "; the file is damaged: remove it, or give another --cache";
}

}  // namespace

nlohmann::ordered_json cache_header(const CacheContext& c) {
  return {{kTag, 1},
          {"imcol", c.imcol_version},
          {"scene_text_hash", text_hash(c.scene_text)},
          {"overrides", c.overrides},
          {"fit", c.fit_keys},
          {"measurement_text_hash", text_hash(c.measurement_text)},
          {"window", c.window}};
}

EvaluationCache::EvaluationCache(const std::string& path, const std::string& text, const CacheContext& context) {
  bytes_ = whole_bytes_ = text.size();
  if (text.empty()) return;
  const bool ends_in_newline = text.back() == '\n';
  unended_ = !ends_in_newline;
  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const std::string where = path + ":" + std::to_string(lineno);
    const bool last_unended = !ends_in_newline && in.peek() == std::char_traits<char>::eof();
    if (lineno == 1) {
      nlohmann::ordered_json h;
      try {
        h = nlohmann::ordered_json::parse(line);
      } catch (const nlohmann::json::exception&) {
      }
      if (!h.is_object() || !h.contains(kTag))
        throw InputError(where, "--cache", "not an imcol calibrate cache (its first line is not a cache header): give a new file or one an earlier --cache wrote");
      const auto want = cache_header(context);
      for (const auto& [field, what] : kFields)
        if (!h.contains(field) || h[field] != want[field])
          throw InputError(where, "--cache",
                           std::string("made for another calibration (not the same ") + what +
                               (std::string(field) == "imcol" && h[field].is_string() ? ": " + h[field].get<std::string>() : "") +
                               "): remove the file, or give another --cache");
      has_header_ = true;
      continue;
    }
    std::vector<ValuedEvaluation> evals;
    try {
      evals = evaluations_from_bytes(line);
    } catch (const std::exception& e) {
      if (last_unended && !nlohmann::json::accept(line)) {  // the last write of a killed run, cut inside its JSON
        unended_ = false;
        whole_bytes_ = text.size() - line.size();
        break;
      }
      throw InputError(where, "--cache", damaged(std::string("not a line of evaluations (") + e.what() + ")"));
    }
    for (std::size_t i = 0; i < evals.size(); ++i)
      if (evals[i].first.size() != context.fit_keys.size())
        throw InputError(where, "--cache", damaged("evaluation " + std::to_string(i + 1) + " has " + std::to_string(evals[i].first.size()) +
                                                   " parameter values for " + std::to_string(context.fit_keys.size()) + " fitted keys"));
    for (auto& [values, ev] : evals) entries_.emplace(std::move(values), std::move(ev));
  }
}

std::optional<Evaluation> EvaluationCache::find(const std::vector<double>& values) const {
  const auto it = entries_.find(values);
  if (it == entries_.end()) return std::nullopt;
  return it->second;
}

std::set<std::vector<double>> EvaluationCache::keys() const {
  std::set<std::vector<double>> k;
  for (const auto& e : entries_) k.insert(e.first);
  return k;
}

CacheWriter::CacheWriter(const std::string& path, const EvaluationCache& read, const CacheContext& context)
    : held_(read.keys()) {
  lock_fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) throw InputError("command line", "--cache", "cannot open '" + path + "': " + std::strerror(errno));
  struct stat st {};
  if (::fstat(lock_fd_, &st) != 0 || !S_ISREG(st.st_mode)) {  // made another kind of file since it was read
    ::close(lock_fd_);
    throw InputError(path, "--cache", "is not a regular file (a cache is a text file)");
  }
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(lock_fd_);
    throw InputError("command line", "--cache", "'" + path + "' is in use by another imcol calibrate: wait for it, or give another --cache");
  }
  try {
    std::error_code ec;
    if (std::filesystem::file_size(path, ec) != read.bytes())
      throw InputError("command line", "--cache", "'" + path + "' changed while it was read: another process is writing it");
    if (read.cut_short()) std::filesystem::resize_file(path, read.whole_bytes(), ec);
    if (ec) throw InputError("command line", "--cache", "cannot remove the last line, cut short, of '" + path + "': " + ec.message());
    out_.open(path, std::ios::app | std::ios::binary);
    if (!out_) throw InputError("command line", "--cache", "cannot open '" + path + "' for appending");
  } catch (...) {
    ::close(lock_fd_);
    throw;
  }
  if (read.unended()) out_ << '\n';  // a whole last line without its newline
  if (!read.has_header()) out_ << cache_header(context).dump() << '\n';
  out_.flush();
}

CacheWriter::~CacheWriter() {
  out_.close();
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

void CacheWriter::add_item(const std::string& item_bytes) {
  std::vector<ValuedEvaluation> fresh;
  std::lock_guard lock(mu_);
  for (auto& e : evaluations_from_bytes(item_bytes))
    if (held_.insert(e.first).second) fresh.push_back(std::move(e));
  if (fresh.empty()) return;
  out_ << evaluations_to_bytes(fresh) << '\n';
  out_.flush();
  added_ += fresh.size();
}

}  // namespace imcol::calib
