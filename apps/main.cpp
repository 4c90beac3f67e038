#include <csignal>

#include "apps/commands.hpp"

int main(int argc, char** argv) {
  std::signal(SIGXFSZ, SIG_IGN);  // a file-size limit then fails the write (EFBIG), reported like any write error
  return imcol::run_cli(argc, argv);
}
