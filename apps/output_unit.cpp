// SPDX-License-Identifier: BSD-3-Clause
#include "apps/output_unit.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <fstream>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>
#include <sys/file.h>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

#include "core/errors.hpp"
#include "core/report.hpp"
#include "core/work_scope.hpp"

namespace imcol {

namespace fs = std::filesystem;

namespace {

std::string g_command_line = "imcol";

/// An argument as /bin/sh reads it back (quoted only when it needs to be).
std::string shell_word(const std::string& s) {
  const bool plain = !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("-_./=,:+@%", c) != nullptr;
  });
  if (plain) return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// The time t in UTC, formatted by strftime's `format`.
std::string utc(std::time_t t, const char* format) {
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, format, &tm);
  return buf;
}

constexpr const char* kIsoUtc = "%Y-%m-%dT%H:%M:%SZ";

/// A run's id: its start (UTC), the pid and 16 random bits.
std::string run_id(std::time_t start) {
  std::random_device rd;
  char tail[16];
  std::snprintf(tail, sizeof tail, "%04x", static_cast<unsigned>(rd() & 0xffffu));
  return utc(start, "%Y%m%dT%H%M%SZ") + "-" + std::to_string(::getpid()) + "-" + tail;
}

std::string host_name() {
  char buf[256] = {0};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "";
  return buf;
}

bool is_within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

constexpr const char* kMarker = ".imcol-run.json";

/// The names a folder's marker lists as its run's files; nothing when there is no marker that imcol wrote (not a
/// regular file, over 1 MiB, not JSON, or without `imcol` and `files`).
std::optional<std::set<std::string>> marker_files(const fs::path& marker) {
  std::error_code ec;
  const auto st = fs::symlink_status(marker, ec);
  if (ec || !fs::is_regular_file(st) || fs::file_size(marker, ec) > (1u << 20) || ec) return std::nullopt;
  std::ifstream in(marker, std::ios::binary);
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object() || !j.contains("imcol") || !j["imcol"].is_string() || !j.contains("files") || !j["files"].is_array())
    return std::nullopt;
  std::set<std::string> names;
  for (const auto& f : j["files"]) {
    if (!f.is_string()) return std::nullopt;
    names.insert(f.get<std::string>());
  }
  return names;
}

/// `.NAME.part-N` or `.NAME.old-N` (N digits): the form of the folders a run stages in and moves aside.
bool staging_form(const std::string& n) {
  if (n.size() < 2 || n[0] != '.') return false;
  for (const std::string kind : {".part-", ".old-"}) {
    const auto at = n.rfind(kind);
    if (at == std::string::npos || at == 0 || at + kind.size() == n.size()) continue;
    if (std::all_of(n.begin() + static_cast<std::ptrdiff_t>(at + kind.size()), n.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return true;
  }
  return false;
}

}  // namespace

void set_command_line(int argc, char** argv) {
  std::string s = "imcol";
  for (int i = 1; i < argc; ++i) s.append(" ").append(shell_word(argv[i]));
  g_command_line = s;
}

OutputUnit::OutputUnit(const std::string& out, const fs::path& fallback, const std::string& scene_path,
                       const std::vector<RunInput>& inputs)
    : place_(out.empty() && !scene_path.empty() ? scene_path : "command line"),
      key_(out.empty() && !scene_path.empty() ? "name" : "--out") {
  const fs::path given = out.empty() ? fallback : fs::path(out);
  std::error_code ec;
  if (given.empty()) throw InputError(place_, key_, "the output folder is empty: give a folder name");
  shown_ = given.lexically_normal();
  if (!shown_.has_filename() && shown_.has_parent_path()) shown_ = shown_.parent_path();
  if (fs::is_symlink(fs::symlink_status(shown_, ec)) && !fs::exists(shown_, ec))
    throw InputError(place_, key_, "'" + shown_.string() + "' is a symbolic link to '" + fs::read_symlink(shown_, ec).string() +
                                       "', which does not exist: create that folder, or give another output folder");
  target_ = fs::weakly_canonical(fs::absolute(given, ec), ec);
  if (ec) throw InputError(place_, key_, "cannot resolve the output folder '" + given.string() + "': " + ec.message());
  if (!target_.has_filename()) target_ = target_.parent_path();
  const fs::path cwd = fs::weakly_canonical(fs::current_path(ec), ec);
  if (!target_.has_relative_path() || (!ec && is_within(cwd, target_)))
    throw InputError(place_, key_, "'" + given.string() + "' is the current folder or contains it: a run replaces its whole output "
                                   "folder, so give it a folder of its own");
  refuse_staging_name();
  refuse_inputs_inside(scene_path, inputs);
  try {
    lock_target();
    check_contents();
    remove_leftovers();
    staging_ = sibling("part", ::getpid());
    fs::create_directory(staging_, ec);
    if (ec) throw InputError(place_, key_, "cannot write beside the output folder '" + shown_.string() + "': " + ec.message());
  } catch (...) {
    // Folders this created go again only if it held the lock: otherwise another writer may be using them.
    if (lock_fd_ >= 0) {
      for (const auto& p : created_)
        if (!fs::is_directory(p, ec) || !fs::is_empty(p, ec) || !fs::remove(p, ec)) break;
      ::close(lock_fd_);
    }
    throw;
  }
  const std::time_t start = std::time(nullptr);
  run_["id"] = run_id(start);
  run_["command"] = g_command_line;
  run_["imcol"] = IMCOL_VERSION;
  run_["host"] = host_name();
  run_["pid"] = static_cast<long>(::getpid());
  run_["started_utc"] = utc(start, kIsoUtc);
}

fs::path OutputUnit::sibling(const std::string& kind, long pid) const {
  std::string name = ".";
  name.append(target_.filename().string()).append(".").append(kind).append("-").append(std::to_string(pid));
  return target_.parent_path() / name;
}

void OutputUnit::refuse_staging_name() const {
  if (staging_form(target_.filename().string()))
    throw InputError(place_, key_, "'" + target_.filename().string() + "' has the form of the folders imcol stages a run in (.NAME.part-N, "
                                   ".NAME.old-N), which a later run into NAME removes: choose another name");
}

void OutputUnit::refuse_inputs_inside(const std::string& scene_path, const std::vector<RunInput>& inputs) const {
  std::vector<RunInput> all = inputs;
  if (!scene_path.empty()) all.insert(all.begin(), RunInput{"the scene file", scene_path});
  for (const auto& in : all) {
    if (in.path.empty()) continue;
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(fs::absolute(in.path, ec), ec);
    if (!ec && is_within(p, target_))
      throw InputError(place_, key_, "the output folder '" + shown_.string() + "' holds '" + in.path + "' (" + in.what +
                                         "), an input of this run: a run replaces its whole output folder, so keep its inputs outside it");
  }
}

void OutputUnit::lock_target() {
  std::error_code ec;
  for (int attempt = 0; attempt < 100; ++attempt) {
    for (fs::path p = target_; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
      if (std::find(created_.begin(), created_.end(), p) == created_.end()) created_.push_back(p);
      if (p == p.parent_path()) break;
    }
    fs::create_directories(target_, ec);
    if (ec || !fs::is_directory(target_))
      throw InputError(place_, key_, "cannot create the output folder '" + shown_.string() + "'" + (ec ? ": " + ec.message() : ""));
    const int fd = ::open(target_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) throw InputError(place_, key_, "cannot open the output folder '" + shown_.string() + "': " + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      ::close(fd);
      if (err != EWOULDBLOCK) throw InputError(place_, key_, "cannot lock the output folder '" + shown_.string() + "': " + std::strerror(err));
      std::string holder;
      const std::string prefix = std::string(".").append(target_.filename().string()).append(".part-");
      for (const auto& f : fs::directory_iterator(target_.parent_path(), ec)) {
        const std::string n = f.path().filename().string();
        if (n.rfind(prefix, 0) == 0) holder = " (pid " + n.substr(prefix.size()) + ")";
      }
      throw InputError(place_, key_, "the output folder '" + shown_.string() + "' is being written by another imcol process" + holder +
                                         ": wait for it to finish, or choose another folder");
    }
    // The lock holds only if the folder at the path is still the one locked (a finishing run swaps it).
    struct stat locked{}, now{};
    if (::fstat(fd, &locked) == 0 && ::stat(target_.c_str(), &now) == 0 && locked.st_dev == now.st_dev && locked.st_ino == now.st_ino) {
      lock_fd_ = fd;
      return;
    }
    ::close(fd);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  throw InputError(place_, key_, "the output folder '" + shown_.string() + "' keeps changing: another process is replacing it");
}

void OutputUnit::check_contents() const {
  std::error_code ec;
  std::set<std::string> present;
  for (const auto& f : fs::directory_iterator(target_, ec)) present.insert(f.path().filename().string());
  if (ec) throw InputError(place_, key_, "cannot read the output folder '" + shown_.string() + "': " + ec.message());
  present.erase(kMarker);
  if (present.empty()) return;
  const auto listed = marker_files(target_ / kMarker);
  if (!listed)
    throw InputError(place_, key_, "the output folder '" + shown_.string() + "' holds '" + *present.begin() +
                                       "', which imcol did not write (no " + kMarker + " of an imcol run lists it): a run "
                                       "replaces its whole output folder, so give a new or empty one");
  for (const auto& n : present)
    if (!listed->count(n))
      throw InputError(place_, key_, "the output folder '" + shown_.string() + "' holds '" + n + "', which imcol did not write (the run "
                                         "that wrote the folder lists its files in " + kMarker + "): a run replaces its whole output "
                                         "folder, so move that file or give another folder");
}

void OutputUnit::remove_leftovers() const {
  // Staging folders of runs that were killed (the lock says none of them is running).
  std::error_code ec;
  const std::string name = std::string(".").append(target_.filename().string()).append(".");
  std::vector<fs::path> stale;
  for (const auto& f : fs::directory_iterator(target_.parent_path(), ec)) {
    const std::string n = f.path().filename().string();
    if (n.rfind(name, 0) != 0 || !staging_form(n) || f.is_symlink(ec) || !f.is_directory(ec)) continue;
    const std::string rest = n.substr(name.size());
    if (rest.rfind("part-", 0) == 0 || rest.rfind("old-", 0) == 0) stale.push_back(f.path());
  }
  for (const auto& p : stale) fs::remove_all(p, ec);
}

void OutputUnit::write_marker(bool complete) const {
  std::error_code ec;
  nlohmann::ordered_json marker = run_;
  marker["finished_utc"] = utc(std::time(nullptr), kIsoUtc);
  if (!complete) marker["complete"] = false;
  std::vector<std::string> files;
  for (const auto& f : fs::directory_iterator(staging_, ec))
    if (f.path().filename() != kMarker) files.push_back(f.path().filename().string());
  std::sort(files.begin(), files.end());
  marker["files"] = files;
  write_file_atomic(staging_ / kMarker, marker.dump(2) + "\n");
}

fs::path OutputUnit::keep_beside() {
  try {
    write_marker(false);
  } catch (const std::exception&) {  // the files are kept without it (a full disk, a file-size limit)
  }
  return move_beside("partial");
}

fs::path OutputUnit::move_beside(const std::string& kind) {
  const std::string name = target_.filename().string() + "." + kind + "-" + run_["id"].get<std::string>();
  if (::rename(staging_.c_str(), (target_.parent_path() / name).c_str()) != 0)
    throw std::runtime_error("cannot keep them beside '" + shown_.string() + "' as '" + name + "': " + std::strerror(errno));
  staging_.clear();
  return shown_.parent_path() / name;
}

void OutputUnit::commit() {
  this_thread_work().stop.throw_if_requested();  // stopped work leaves nothing: the destructor removes the staged files
  std::error_code ec;
  write_marker(true);

  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0) {
    const int err = errno;
    bool moved = false;
    if (err == ENOENT && ::rename(staging_.c_str(), target_.c_str()) == 0) {
      moved = true;  // the target folder was removed meanwhile: the staged one takes its place
      staging_.clear();
    } else if (err == EINVAL || err == ENOSYS || err == ENOTSUP) {
      // No atomic exchange on this file system: move the old folder aside, then the new one in.
      const fs::path old = sibling("old", ::getpid());
      if (::rename(target_.c_str(), old.c_str()) == 0) {
        if (::rename(staging_.c_str(), target_.c_str()) == 0) {
          moved = true;
          staging_ = old;
        } else {
          ::rename(old.c_str(), target_.c_str());
        }
      }
    }
    if (!moved) {
      // The staged files are the run's complete result: kept under a name no later run removes.
      std::string kept;
      try {
        kept = move_beside("complete").string();
      } catch (const std::exception&) {
        committed_ = true;
        kept = staging_.string();
      }
      throw std::runtime_error("cannot move the results into '" + shown_.string() + "' (" + std::strerror(err) +
                               "); they are complete in '" + kept + "'");
    }
  }
  committed_ = true;
  if (!staging_.empty()) fs::remove_all(staging_, ec);  // the previous content
  ::close(lock_fd_);
  lock_fd_ = -1;
}

OutputUnit::~OutputUnit() {
  std::error_code ec;
  if (!committed_) {
    if (!staging_.empty()) fs::remove_all(staging_, ec);
    for (const auto& p : created_)  // innermost first; only empty folders go
      if (!fs::is_directory(p, ec) || !fs::is_empty(p, ec) || !fs::remove(p, ec)) break;
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

}  // namespace imcol
