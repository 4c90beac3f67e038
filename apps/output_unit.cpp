// SPDX-License-Identifier: BSD-3-Clause
#include "apps/output_unit.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <random>
#include <stdexcept>
#include <sys/file.h>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

#include "core/errors.hpp"
#include "core/report.hpp"

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

/// Names of files a run of imcol writes (a folder holding only these may be replaced, even without a marker).
bool written_by_imcol(const fs::directory_entry& f) {
  const std::string n = f.path().filename().string();
  const std::string ext = f.path().extension().string();
  std::error_code ec;
  if (f.is_directory(ec) && !f.is_symlink(ec) && n == "vtk") {  // flow fields for ParaView: VTK files only
    for (const auto& g : fs::directory_iterator(f.path(), ec)) {
      const std::string e = g.path().extension().string();
      if (!g.is_regular_file(ec) || (e != ".vtu" && e != ".vtp" && e != ".vtm" && g.path().filename().string().find(".tmp.") == std::string::npos))
        return false;
    }
    return !ec;
  }
  if (!f.is_regular_file()) return false;
  return ext == ".csv" || ext == ".json" || ext == ".png" || ext == ".pvd" || n == "sweep.partial" || n.find(".tmp.") != std::string::npos;
}

bool is_within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

constexpr const char* kMarker = ".imcol-run.json";

}  // namespace

void set_command_line(int argc, char** argv) {
  std::string s = "imcol";
  for (int i = 1; i < argc; ++i) s.append(" ").append(shell_word(argv[i]));
  g_command_line = s;
}

OutputUnit::OutputUnit(const std::string& out, const fs::path& fallback, const std::string& scene_path)
    : place_(out.empty() && !scene_path.empty() ? scene_path : "command line"),
      key_(out.empty() && !scene_path.empty() ? "name" : "--out") {
  const fs::path given = out.empty() ? fallback : fs::path(out);
  std::error_code ec;
  if (given.empty()) throw InputError(place_, key_, "the output folder is empty: give a folder name");
  shown_ = given.lexically_normal();
  if (!shown_.has_filename() && shown_.has_parent_path()) shown_ = shown_.parent_path();
  target_ = fs::weakly_canonical(fs::absolute(given, ec), ec);
  if (ec) throw InputError(place_, key_, "cannot resolve the output folder '" + given.string() + "': " + ec.message());
  if (!target_.has_filename()) target_ = target_.parent_path();
  const fs::path cwd = fs::weakly_canonical(fs::current_path(ec), ec);
  if (!target_.has_relative_path() || (!ec && is_within(cwd, target_)))
    throw InputError(place_, key_, "'" + given.string() + "' is the current folder or contains it: a run replaces its whole output "
                                   "folder, so give it a folder of its own");
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
  if (fs::exists(target_ / kMarker, ec)) return;
  for (const auto& f : fs::directory_iterator(target_, ec))
    if (!written_by_imcol(f))
      throw InputError(place_, key_, "the output folder '" + shown_.string() + "' holds '" + f.path().filename().string() +
                                         "', which imcol did not write: a run replaces its whole output folder, so give a new or empty one");
  if (ec) throw InputError(place_, key_, "cannot read the output folder '" + shown_.string() + "': " + ec.message());
}

void OutputUnit::remove_leftovers() const {
  // Staging folders of runs that were killed (the lock says none of them is running).
  std::error_code ec;
  const std::string name = std::string(".").append(target_.filename().string()).append(".");
  std::vector<fs::path> stale;
  for (const auto& f : fs::directory_iterator(target_.parent_path(), ec)) {
    const std::string n = f.path().filename().string();
    if (n.rfind(name + "part-", 0) == 0 || n.rfind(name + "old-", 0) == 0) stale.push_back(f.path());
  }
  for (const auto& p : stale) fs::remove_all(p, ec);
}

void OutputUnit::commit() {
  std::error_code ec;
  nlohmann::ordered_json marker = run_;
  marker["finished_utc"] = utc(std::time(nullptr), kIsoUtc);
  std::vector<std::string> files;
  for (const auto& f : fs::directory_iterator(staging_, ec)) files.push_back(f.path().filename().string());
  std::sort(files.begin(), files.end());
  marker["files"] = files;
  write_file_atomic(staging_ / kMarker, marker.dump(2) + "\n");

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
      committed_ = true;  // keep the staged files: they are the run's complete result
      throw std::runtime_error("cannot move the results into '" + shown_.string() + "' (" + std::strerror(err) +
                               "); they are complete in '" + staging_.string() + "'");
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
    fs::remove_all(staging_, ec);
    for (const auto& p : created_)  // innermost first; only empty folders go
      if (!fs::is_directory(p, ec) || !fs::is_empty(p, ec) || !fs::remove(p, ec)) break;
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

}  // namespace imcol
