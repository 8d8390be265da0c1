#include "uavmot/core/printed_number.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "uavmot/core/error.hpp"

namespace uavmot {
namespace {

// The integer form must print exactly what fmt prints for the double, whatever the double.
void expect_same_text(double v, int decimals) {
  const std::string expected = fmt::format("{:.{}f}", v, decimals);
  EXPECT_EQ(format_printed_fixed(printed_fixed(v, decimals), decimals), expected) << fmt::format("{:.17g}", v);
}

TEST(PrintedNumber, PrintsWhatFmtPrintsIncludingNegativeZeroAndTies) {
  for (int d : {0, 2, 3, 4}) {
    for (double v : {0.0, -0.0, 0.0004, -0.0004, -0.00049999, 0.0005, -0.0005, 0.0015, 2.675, -2.675, 1.0, -1.0,
                     12.3455, 999.9995, -999.9995, 1e9 + 0.25, -123456.789, 5e-324, -5e-324}) {
      expect_same_text(v, d);
    }
  }
  EXPECT_EQ(format_printed_fixed(printed_fixed(-0.0004, 3), 3), "-0.000");
  EXPECT_LT(printed_fixed(-0.0004, 3), 0);
  EXPECT_EQ(printed_fixed(0.0004, 3), 0);
  EXPECT_EQ(printed_fixed(12.3456, 3), 12346);
}

TEST(PrintedNumber, PrintsWhatFmtPrintsForRandomBoxCoordinates) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> wide(-2000.0, 2000.0), narrow(-0.01, 0.01);
  for (int i = 0; i < 200000; ++i) {
    expect_same_text(wide(rng), 3);
    expect_same_text(narrow(rng), 4);
  }
}

TEST(PrintedNumber, RefusesWhatAnIntegerCannotHold) {
  EXPECT_THROW(printed_fixed(std::nan(""), 3), InvalidArgument);
  EXPECT_THROW(printed_fixed(INFINITY, 3), InvalidArgument);
  EXPECT_THROW(printed_fixed(1e16, 3), InvalidArgument);
}

}  // namespace
}  // namespace uavmot
