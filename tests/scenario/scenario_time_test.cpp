// Times in scenario files: a number, optional spaces, a unit (ns, us, ms, s); whole nanoseconds,
// 0 .. 24 h; numbers without a unit are refused (docs/scenarios.md, "Times").
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "ibs/sim/scenario.hpp"

namespace ibs::sim {
namespace {

std::string time_error(const std::string& text) {
  try {
    (void)parse_time(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(ScenarioTime, EveryUnitWithAndWithoutSpace) {
  EXPECT_EQ(parse_time("6 s"), 6s);
  EXPECT_EQ(parse_time("6s"), 6s);
  EXPECT_EQ(parse_time("250 ms"), 250ms);
  EXPECT_EQ(parse_time("726 us"), 726us);
  EXPECT_EQ(parse_time("100 ns"), 100ns);
  EXPECT_EQ(parse_time("100   ns"), 100ns);
  EXPECT_EQ(parse_time("0 s"), 0s);
  EXPECT_EQ(parse_time("007 ms"), 7ms);
}

TEST(ScenarioTime, FractionsDownToWholeNanoseconds) {
  EXPECT_EQ(parse_time("8.2 ms"), 8200us);
  EXPECT_EQ(parse_time("1.5 s"), 1500ms);
  EXPECT_EQ(parse_time("0.000000001 s"), 1ns);
  EXPECT_EQ(parse_time("1.250 us"), 1250ns);
  EXPECT_EQ(parse_time("3.000000000000 ns"), 3ns);  // trailing zeros are no extra precision
  EXPECT_EQ(time_error("1.5 ns"), "\"1.5 ns\" is not a whole number of nanoseconds");
  EXPECT_EQ(time_error("0.0000000001 s"),
            "\"0.0000000001 s\" is not a whole number of nanoseconds");
}

TEST(ScenarioTime, RefusalsSayWhatIsWrong) {
  EXPECT_EQ(time_error(""),
            "an empty time: write a number and a unit (ns, us, ms, s), e.g. "
            "\"250 ms\" or \"8.2 ms\"");
  EXPECT_EQ(time_error("6"), "\"6\" has no unit: write \"6 s\" (or ms, us, ns)");
  EXPECT_EQ(time_error("2.5"), "\"2.5\" has no unit: write \"2.5 s\" (or ms, us, ns)");
  EXPECT_EQ(time_error("6 sec"), "\"6 sec\" has the unknown unit 'sec' (ns, us, ms, s)");
  EXPECT_EQ(time_error("6 S"), "\"6 S\" has the unknown unit 'S' (ns, us, ms, s)");
  EXPECT_EQ(time_error("6 s "), "\"6 s \" has the unknown unit 's ' (ns, us, ms, s)");
  EXPECT_EQ(time_error("-1 s"), "\"-1 s\" is negative: times here are never negative");
  EXPECT_EQ(time_error("fast"),
            "\"fast\" is not a time: write a number and a unit (ns, us, ms, "
            "s), e.g. \"250 ms\" or \"8.2 ms\"");
  EXPECT_EQ(time_error(" 6 s"), time_error("fast").replace(0, 6, "\" 6 s\""));
  EXPECT_EQ(time_error(".5 s"),
            "\".5 s\" is not a time: write a number and a unit (ns, us, ms, "
            "s), e.g. \"250 ms\" or \"8.2 ms\"");
  EXPECT_EQ(time_error("5. s"),
            "\"5. s\" is not a time: write a number and a unit (ns, us, ms, "
            "s), e.g. \"250 ms\" or \"8.2 ms\"");
  EXPECT_EQ(time_error("1e3 ms"), "\"1e3 ms\" has the unknown unit 'e3 ms' (ns, us, ms, s)");
  EXPECT_EQ(time_error("+1 s"), time_error("fast").replace(0, 6, "\"+1 s\""));
}

TEST(ScenarioTime, AtMost24Hours) {
  EXPECT_EQ(parse_time("24 s") * 3600, parse_time("86400 s"));
  EXPECT_EQ(parse_time("86400000 ms"), parse_time("86400 s"));
  EXPECT_EQ(time_error("86400.000000001 s"), "\"86400.000000001 s\" is longer than 24 h");
  EXPECT_EQ(time_error("86401 s"), "\"86401 s\" is longer than 24 h");
  EXPECT_EQ(time_error("99999999999999999999 ns"),
            "\"99999999999999999999 ns\" is longer than 24 h");
  EXPECT_EQ(parse_time("00000000000000000000001 ns"), 1ns);  // leading zeros are not length
}

TEST(ScenarioTime, FormatPicksTheLargestUnitNotAboveTheValue) {
  EXPECT_EQ(format_time(0s), "0 s");
  EXPECT_EQ(format_time(6s), "6 s");
  EXPECT_EQ(format_time(1500ms), "1.5 s");
  EXPECT_EQ(format_time(250ms), "250 ms");
  EXPECT_EQ(format_time(8200us), "8.2 ms");
  EXPECT_EQ(format_time(726us), "726 us");
  EXPECT_EQ(format_time(1001ns), "1.001 us");
  EXPECT_EQ(format_time(100ns), "100 ns");
  EXPECT_EQ(format_time(1s + 1ns), "1.000000001 s");
  EXPECT_EQ(format_time(-5ms), "-5 ms");
}

TEST(ScenarioTime, FormatReadsBackExactly) {
  for (std::int64_t ns : {1LL, 9LL, 10LL, 999LL, 1000LL, 1001LL, 123456789LL, 999999999LL,
                          1000000000LL, 1000000001LL, 86399999999999LL, 86400000000000LL}) {
    EXPECT_EQ(parse_time(format_time(Duration{ns})), Duration{ns}) << ns;
  }
  for (std::int64_t ns = 1; ns < 86'400'000'000'000LL; ns = ns * 7 + 3) {
    EXPECT_EQ(parse_time(format_time(Duration{ns})), Duration{ns}) << ns;
  }
}

}  // namespace
}  // namespace ibs::sim
