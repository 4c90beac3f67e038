#include "apps/commands.hpp"

int main(int argc, char** argv) { return imcol::run_cli(argc, argv); }
