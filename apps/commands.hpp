// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The imcol command line: run, validate, bench. Exit status 0 ok, 2 bad input, 3 solver failure, 1 other.
namespace imcol {
int run_cli(int argc, char** argv);
}
