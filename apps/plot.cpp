#include "apps/plot.hpp"

#include <cstdio>
#include <iostream>
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

bool run_plot_script(const std::string& script, const std::filesystem::path& dir, const std::string& png, bool quiet) {
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
    if (!quiet) std::cout << "wrote " << (dir / png).string() << "\n";
    return true;
  }
  // The script's own last line (a Python exception names its type and cause), on one line.
  std::string last;
  for (std::size_t end = output.size(); end > 0 && last.empty();) {
    const std::size_t start = output.rfind('\n', end - 1 == 0 ? 0 : end - 2);
    const std::size_t b = start == std::string::npos ? 0 : start + 1;
    last = output.substr(b, end - b);
    while (!last.empty() && (last.back() == '\n' || last.back() == ' ')) last.pop_back();
    if (b == 0) break;
    end = b;
  }
  if (last.empty()) last = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status)) : "did not run";
  std::cerr << "imcol: warning: the plot " << (dir / png).string() << " failed (/usr/bin/python3 scripts/" << script << "): " << last
            << "; the data files are complete\n";
  return false;
}

}  // namespace imcol
