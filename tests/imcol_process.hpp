// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The imcol program run by a test (IMCOL_BINARY, set by tests/CMakeLists.txt): its exit status, stdout and stderr.
#include <spawn.h>
#include <unistd.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace imcol::test {

struct Outcome {
  int status;  // the exit status; -1 when the process did not exit (a signal)
  std::string out, err;
};

/// A file's whole content ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs `imcol ARGS` in folder `dir` (empty: the test's own), its stdout and stderr kept through the files
/// SCRATCH.stdout and SCRATCH.stderr, which it removes.
inline Outcome run_imcol(const std::string& args, const std::filesystem::path& scratch, const std::string& dir = "") {
  const std::filesystem::path o = scratch.string() + ".stdout", e = scratch.string() + ".stderr";
  std::string cmd = dir.empty() ? std::string() : "cd '" + dir + "' && ";
  cmd += std::string(IMCOL_BINARY) + " " + args + " >" + o.string() + " 2>" + e.string();
  const int raw = std::system(cmd.c_str());
  Outcome r{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(o), slurp(e)};
  std::filesystem::remove(o);
  std::filesystem::remove(e);
  return r;
}

/// Starts `imcol ARGS` in folder `dir` as a child of the test, its output discarded; returns its pid (-1 when it
/// cannot start). The caller waits for it with waitpid, which returns only once all its threads, and so its files
/// and locks, are gone.
inline pid_t start_imcol(const std::string& args, const std::string& dir) {
  std::string cmd = "cd '" + dir + "' && exec " + std::string(IMCOL_BINARY) + " " + args + " >/dev/null 2>&1";
  char sh[] = "/bin/sh", c[] = "-c";
  char* argv[] = {sh, c, cmd.data(), nullptr};
  pid_t pid = -1;
  return ::posix_spawn(&pid, "/bin/sh", nullptr, nullptr, argv, environ) == 0 ? pid : -1;
}

}  // namespace imcol::test
