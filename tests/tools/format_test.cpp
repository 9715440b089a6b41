// The tool layer's formatting module (tools/format, issue 27): the command line's output stayed
// byte for byte what the snprintf calls and local helpers it replaced printed -- the same digits,
// the same padding, the same rounding of a tie as printf's %.*f (round half to even on the binary
// value), which the CLI tests, the docs' sessions and users' scripts compare against.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "ibs/tool/format.hpp"

namespace ibs::tool {
namespace {

std::string printf_fixed(double v, int decimals) {
  std::array<char, 64> b{};
  std::snprintf(b.data(), b.size(), "%.*f", decimals, v);
  return b.data();
}

TEST(ToolFormat, HexIsUpperCaseZeroPaddedToTheDigitsAndNeverCut) {
  EXPECT_EQ(hex(0x3E8, 4), "03E8");
  EXPECT_EQ(hex(0x373, 3), "373");
  EXPECT_EQ(hex(0xDD, 3), "0DD");
  EXPECT_EQ(hex(0x148000, 8), "00148000");
  EXPECT_EQ(hex(0x12345, 4), "12345");  // as %0*X: the width is a minimum
  EXPECT_EQ(hex2(0x0A), "0A");
  EXPECT_EQ(hex4(0xFFFF), "FFFF");
  EXPECT_EQ(hex4(0), "0000");
}

TEST(ToolFormat, BytesAreTwoDigitsWithOneSpaceBetween) {
  const std::vector<std::uint8_t> bytes = {0x40, 0x02, 0x00, 0xFF};
  EXPECT_EQ(hex_bytes(bytes), "40 02 00 FF");
  EXPECT_EQ(hex_bytes({}), "");
}

TEST(ToolFormat, FixedRoundsAsPrintfDoes) {
  // Ties on the binary value and values just beside them, negative zero, large numbers.
  const double values[] = {0.0,    -0.0,   0.5,     1.5,      2.5,       0.125,  0.375,   1.0005,
                           2.675,  50.5,   99.95,   -12.25,   1e15 + 0.5, 1234.5678, 0.0449999,
                           100.0 * 1.0 / 3.0, 20.5, -0.05};
  for (const double v : values) {
    for (int d = 0; d <= 6; ++d) EXPECT_EQ(fixed(v, d), printf_fixed(v, d)) << v << " with " << d << " decimals";
  }
  EXPECT_EQ(fixed(20.5, 2, "Hz"), "20.50 Hz");
  EXPECT_EQ(fixed(50.0, 1, "%"), "50.0 %");
}

TEST(ToolFormat, SecondsHaveMillisecondsAndTheUnit) {
  EXPECT_EQ(seconds(Time{0}), "0.000 s");
  EXPECT_EQ(seconds(std::chrono::microseconds(1234567)), "1.235 s");
  EXPECT_EQ(seconds(std::chrono::milliseconds(61500)), "61.500 s");
  // Half a millisecond: the binary value decides, as printf("%.3f s", ns / 1e9) did.
  for (const std::int64_t ns : {500000LL, 1500000LL, 2500000LL, 1000500000LL}) {
    EXPECT_EQ(seconds(Time{ns}), printf_fixed(static_cast<double>(ns) / 1e9, 3) + " s") << ns;
  }
}

}  // namespace
}  // namespace ibs::tool
