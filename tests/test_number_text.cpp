// SPDX-License-Identifier: BSD-3-Clause
// append_number (core/number_text.hpp) writes %.<digits>g byte for byte as std::to_chars does, on random values
// of every magnitude, values next to rounding ties and powers of ten, and the special values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/number_text.hpp"

namespace {

std::string number_text_fast(double v, int digits) {
  std::string s;
  imcol::append_number(s, v, digits);
  return s;
}

std::string number_text_exact(double v, int digits) {
  std::string s;
  imcol::append_number_exact(s, v, digits);
  return s;
}

}  // namespace

TEST(NumberText, RandomValuesMatchToChars) {
  std::mt19937_64 rng(20261129);
  std::uniform_real_distribution<double> mant(1.0, 10.0), expo(-40.0, 40.0);
  int mismatches = 0;
  for (int i = 0; i < 400000; ++i) {
    const double v = (i % 2 ? -1 : 1) * mant(rng) * std::pow(10.0, std::floor(expo(rng)));
    for (int digits : {1, 6, 9, 12, 17})
      if (number_text_fast(v, digits) != number_text_exact(v, digits)) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(NumberText, TiesPowersAndSpecialValues) {
  std::vector<double> v = {0.0, -0.0, 1.0, 0.5, 0.125, 0.25, 2.5, 1e8, 1e9, 999999999.5, 99999999.95, 0.000123456789,
                           1e-5, 9.9999999995e-5, 123456789012.5, 1.5e300, 4.9e-324, 2.2250738585072014e-308,
                           std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()};
  for (int k = -30; k <= 30; ++k) {  // powers of ten and their neighbours, and halves of the last digit
    const double p = std::pow(10.0, k);
    v.insert(v.end(), {p, std::nextafter(p, 0.0), std::nextafter(p, 2 * p), 1.5 * p, 1.05 * p, 9.5 * p, 0.999999999 * p});
  }
  for (double x : v)
    for (int digits = 1; digits <= 17; ++digits) EXPECT_EQ(number_text_fast(x, digits), number_text_exact(x, digits)) << x << " " << digits;
  EXPECT_EQ(number_text_fast(0.000123456789, 9), "0.000123456789");
  EXPECT_EQ(number_text_fast(-1.5e-7, 9), "-1.5e-07");
  EXPECT_EQ(number_text_fast(1234567890.0, 9), "1.23456789e+09");
}
