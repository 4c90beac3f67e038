// SPDX-License-Identifier: BSD-3-Clause
#include "core/number_text.hpp"

#include <array>
#include <cmath>
#include <cstdint>

namespace imcol {

namespace {

constexpr int kMaxFastDigits = 12;
constexpr int kMaxPow = 22;  // 10^k is exact in double for k ≤ 22 (5^22 < 2^53)

constexpr std::array<double, kMaxPow + 1> kPow10 = [] {
  std::array<double, kMaxPow + 1> t{};
  double x = 1;
  for (int i = 0; i <= kMaxPow; ++i, x *= 10) t[i] = x;
  return t;
}();

/// |v| rounded to `digits` significant digits: the integer n in [10^(digits−1), 10^digits) and the decimal exponent
/// of its first digit. False where the rounding is not certain (the caller then uses std::to_chars).
bool significant_digits(double a, int digits, std::uint64_t& n, int& exp10) {
  int e2 = 0;
  std::frexp(a, &e2);                                             // a in [2^(e2−1), 2^e2)
  exp10 = static_cast<int>(std::floor((e2 - 1) * 0.30102999566398120));  // log10(a) or one less
  const double lo = kPow10[digits - 1], hi = kPow10[digits];
  for (int attempt = 0; attempt < 3; ++attempt) {
    const int p = digits - 1 - exp10;
    if (p > kMaxPow || -p > kMaxPow) return false;
    const double y = p >= 0 ? a * kPow10[p] : a / kPow10[-p];  // one rounding: by an exact power of ten
    const double err = y * 0x1p-49;                             // 16 units of y's last place
    if (y < lo - err) { --exp10; continue; }
    if (y >= hi + err) { ++exp10; continue; }
    if (std::fabs(y - lo) <= err || std::fabs(y - hi) <= err) return false;
    const double f = std::floor(y), frac = y - f;
    if (std::fabs(frac - 0.5) <= err) return false;  // at or next to a tie: printf's exact rule decides
    n = static_cast<std::uint64_t>(f) + (frac > 0.5 ? 1 : 0);
    if (n >= static_cast<std::uint64_t>(hi)) {  // rounded up to the next power of ten
      n /= 10;
      ++exp10;
    }
    return true;
  }
  return false;
}

/// %g's layout of the significant digits d[0..k) (no trailing zeros) with the first digit's exponent x, precision P,
/// into o; returns the end.
char* layout(char* o, const char* d, int k, int x, int P) {
  auto copy = [&o](const char* from, int count) {
    for (int i = 0; i < count; ++i) *o++ = from[i];
  };
  if (x < -4 || x >= P) {  // scientific: d.ddde±XX
    *o++ = d[0];
    if (k > 1) {
      *o++ = '.';
      copy(d + 1, k - 1);
    }
    *o++ = 'e';
    *o++ = x < 0 ? '-' : '+';
    const int ax = x < 0 ? -x : x;
    if (ax >= 100) *o++ = static_cast<char>('0' + ax / 100);
    *o++ = static_cast<char>('0' + ax / 10 % 10);
    *o++ = static_cast<char>('0' + ax % 10);
  } else if (x < 0) {  // 0.000ddd
    *o++ = '0';
    *o++ = '.';
    for (int i = 0; i < -x - 1; ++i) *o++ = '0';
    copy(d, k);
  } else if (k <= x + 1) {  // ddd000
    copy(d, k);
    for (int i = k; i < x + 1; ++i) *o++ = '0';
  } else {  // ddd.ddd
    copy(d, x + 1);
    *o++ = '.';
    copy(d + x + 1, k - x - 1);
  }
  return o;
}

}  // namespace

void append_number(std::string& out, double v, int digits) {
  const double a = std::fabs(v);
  std::uint64_t n = 0;
  int x = 0;
  if (digits < 1 || digits > kMaxFastDigits || !(a > 0) || !std::isfinite(a) || !significant_digits(a, digits, n, x)) {
    append_number_exact(out, v, digits);
    return;
  }
  char d[kMaxFastDigits];
  for (int i = digits - 1; i >= 0; --i, n /= 10) d[i] = static_cast<char>('0' + n % 10);
  int k = digits;
  while (k > 1 && d[k - 1] == '0') --k;
  char b[40];
  char* o = b;
  if (std::signbit(v)) *o++ = '-';
  out.append(b, layout(o, d, k, x, digits));
}

}  // namespace imcol
