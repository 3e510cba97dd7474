#pragma once
/// \file
/// The one comparison helper of the unit tests: a relative-tolerance check that reports both
/// values and the relative error when it fails.

#include <cmath>
#include <iomanip>
#include <limits>

#include <catch2/catch.hpp>

namespace pamkit_test {

/// |actual - expected| / |expected|; infinite if expected is 0 and actual is not.
inline double relative_error(double actual, double expected) {
  if (actual == expected) return 0.0;
  if (expected == 0.0) return std::numeric_limits<double>::infinity();
  return std::abs(actual - expected) / std::abs(expected);
}

}  // namespace pamkit_test

/// CHECK that `actual` is within relative tolerance `rel` of `expected` (NaN always fails).
#define CHECK_REL(actual, expected, rel)                                                                  \
  do {                                                                                                    \
    const double check_rel_a_ = (actual);                                                                 \
    const double check_rel_e_ = (expected);                                                               \
    const double check_rel_err_ = ::pamkit_test::relative_error(check_rel_a_, check_rel_e_);              \
    INFO(std::setprecision(12) << #actual " = " << check_rel_a_ << ", " #expected " = " << check_rel_e_   \
                               << ", relative error " << check_rel_err_ << " (allowed " << (rel) << ")"); \
    CHECK(check_rel_err_ <= (rel));                                                                       \
  } while (false)
