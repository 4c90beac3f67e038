// SPDX-License-Identifier: BSD-3-Clause
#include <csignal>

#include "apps/commands.hpp"

int main(int argc, char** argv) {
  // A file-size limit (ulimit -f) must end a write with EFBIG, reported as an I/O error (exit 1), not kill the process.
  std::signal(SIGXFSZ, SIG_IGN);
  // A closed standard output (`imcol sweep … | head -1`) must not end the run before its folder is written: writes to
  // it fail instead, and the results are committed as usual.
  std::signal(SIGPIPE, SIG_IGN);
  return imcol::run_cli(argc, argv);
}
