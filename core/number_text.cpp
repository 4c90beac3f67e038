// SPDX-License-Identifier: BSD-3-Clause
#include "core/number_text.hpp"

#include <array>
#include <bit>
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

/// 10^−k as the nearest double (with the products, a few roundings: far inside the 16 units of the last place below).
constexpr std::array<double, kMaxPow + 1> kNegPow10 = {1e0,  1e-1,  1e-2,  1e-3,  1e-4,  1e-5,  1e-6,  1e-7,
                                                      1e-8, 1e-9,  1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15,
                                                      1e-16, 1e-17, 1e-18, 1e-19, 1e-20, 1e-21, 1e-22};

/// a · 10^p for |p| ≤ 2 kMaxPow, by one or two powers of ten from the tables: at most three roundings.
double scaled(double a, int p) {
  if (p >= 0) return p <= kMaxPow ? a * kPow10[p] : a * kPow10[kMaxPow] * kPow10[p - kMaxPow];
  return -p <= kMaxPow ? a * kNegPow10[-p] : a * kNegPow10[kMaxPow] * kNegPow10[-p - kMaxPow];
}

/// |v| rounded to `digits` significant digits: the integer n in [10^(digits−1), 10^digits) and the decimal exponent
/// of its first digit. False where the rounding is not certain (the caller then uses std::to_chars).
bool significant_digits(double a, int digits, std::uint64_t& n, int& exp10) {
  const int biased = static_cast<int>(std::bit_cast<std::uint64_t>(a) >> 52) & 0x7ff;  // a > 0: no sign bit
  if (biased == 0 || biased == 0x7ff) return false;  // subnormal, inf or nan: std::to_chars
  // a in [2^(e−1), 2^e) with e = biased − 1022; floor((e − 1) log10 2) is log10(a) or one less.
  const double l = (biased - 1023) * 0.30102999566398120;
  exp10 = static_cast<int>(l) - (l < 0 && l != static_cast<int>(l) ? 1 : 0);
  const double lo = kPow10[digits - 1], hi = kPow10[digits];
  for (int attempt = 0; attempt < 3; ++attempt) {
    const int p = digits - 1 - exp10;
    if (p > 2 * kMaxPow || -p > 2 * kMaxPow) return false;
    const double y = scaled(a, p);
    const double err = y * 0x1p-49;  // 16 units of y's last place
    if (y < lo - err) { --exp10; continue; }
    if (y >= hi + err) { ++exp10; continue; }
    if (std::fabs(y - lo) <= err || std::fabs(y - hi) <= err) return false;
    const auto f = static_cast<std::uint64_t>(y);  // y < 10^12: the cast is floor
    const double frac = y - static_cast<double>(f);
    if (std::fabs(frac - 0.5) <= err) return false;  // at or next to a tie: printf's exact rule decides
    n = f + (frac > 0.5 ? 1 : 0);
    if (n >= static_cast<std::uint64_t>(hi)) {  // rounded up to the next power of ten
      n /= 10;
      ++exp10;
    }
    return true;
  }
  return false;
}

/// The decimal digits of n (exactly `count` of them, leading zeros kept) into d[0..count), two at a time.
void write_digits(std::uint64_t n, int count, char* d) {
  static constexpr char kPairs[] =
      "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
      "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
      "8081828384858687888990919293949596979899";
  int i = count;
  while (i >= 2) {
    const auto r = static_cast<unsigned>(n % 100);
    n /= 100;
    d[--i] = kPairs[2 * r + 1];
    d[--i] = kPairs[2 * r];
  }
  if (i == 1) d[0] = static_cast<char>('0' + n);
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
  if (a == 0 && digits >= 1) {  // %g of ±0 (2–3 % of a flow field's values; std::to_chars takes ~3000 instructions)
    out.append(std::signbit(v) ? "-0" : "0");
    return;
  }
  std::uint64_t n = 0;
  int x = 0;
  if (digits < 1 || digits > kMaxFastDigits || !(a > 0) || !std::isfinite(a) || !significant_digits(a, digits, n, x)) {
    append_number_exact(out, v, digits);
    return;
  }
  char d[kMaxFastDigits];
  write_digits(n, digits, d);
  int k = digits;
  while (k > 1 && d[k - 1] == '0') --k;
  char b[40];
  char* o = b;
  if (std::signbit(v)) *o++ = '-';
  out.append(b, layout(o, d, k, x, digits));
}

}  // namespace imcol
