// SPDX-License-Identifier: BSD-3-Clause
#include "apps/plot.hpp"

#include <cstdio>
#include <iostream>
#include <sstream>
#include <sys/wait.h>

#include "core/materials.hpp"

namespace imcol {

namespace {
/// Quotes a path for /bin/sh.
std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

bool run_plot_script(const std::string& script, const OutputUnit& unit, const std::string& png, bool quiet) {
  const std::filesystem::path& dir = unit.dir();
  const auto path = std::filesystem::path(data_dir()).parent_path() / "scripts" / script;
  const std::string cmd = "/usr/bin/python3 " + shell_quote(path.string()) + " " + shell_quote(dir.string()) + " 2>&1";
  std::string output;
  int status = -1;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[4096];
    while (std::fgets(buf, sizeof buf, p)) output += buf;
    status = ::pclose(p);
  }
  if (status == 0) {
    if (!quiet) std::cout << "wrote " << (unit.target() / png).string() << "\n";
    return true;
  }
  // The script's own last non-empty line (a Python exception names its type and cause), on one line.
  std::string last;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  if (last.empty()) last = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status)) : "did not run";
  std::cerr << "imcol: warning: the plot " << (unit.target() / png).string() << " failed (/usr/bin/python3 scripts/" << script << "): " << last
            << "; the data files are complete\n";
  return false;
}

}  // namespace imcol
