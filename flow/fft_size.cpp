// SPDX-License-Identifier: BSD-3-Clause
#include "flow/fft_size.hpp"

namespace imcol::flow {

namespace {
bool seven_smooth(int n) {
  for (int p : {2, 3, 5, 7})
    while (n % p == 0) n /= p;
  return n == 1;
}
}  // namespace

int fft_friendly_cells(int n, int multiple) {
  int m = multiple > 0 ? multiple : 1;
  int c = ((n + m - 1) / m) * m;
  while (!seven_smooth(c)) c += m;
  return c;
}

}  // namespace imcol::flow
