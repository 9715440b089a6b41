// candump -l's log format (can-utils): `(SECONDS.MICROS) IFACE ID#DATA`, written and read back,
// remote, extended and CAN FD frames, and every malformed line refused with what is wrong and
// where.
#include "ibs/can/candump.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace ibs::can {
namespace {

using canlust::CanFrame;

const auto kAt = std::chrono::system_clock::time_point(std::chrono::microseconds(1795431275322679LL));

TEST(CandumpFormat, WritesSecondsMicrosIfaceIdHashData) {
  EXPECT_EQ(candump_line(CanFrame::make(0x297, {0x0F, 0x00, 0x00, 0x80, 0x14, 0x00}), kAt, "can0"),
            "(1795431275.322679) can0 297#0F0000801400");
  EXPECT_EQ(candump_line(CanFrame::make(0x7FF, {}), kAt, "vcan1"), "(1795431275.322679) vcan1 7FF#");
  // Leading zeros: three identifier digits, six of microseconds.
  const auto early = std::chrono::system_clock::time_point(std::chrono::microseconds(5000007));
  EXPECT_EQ(candump_line(CanFrame::make(0x21, {0xAB}), early, "c"), "(5.000007) c 021#AB");
  CanFrame rtr;
  rtr.id = 0x123;
  rtr.rtr = true;
  EXPECT_EQ(candump_line(rtr, kAt, "c"), "(1795431275.322679) c 123#R");
  rtr.dlc = 2;
  EXPECT_EQ(candump_line(rtr, kAt, "c"), "(1795431275.322679) c 123#R2");
}

TEST(CandumpFormat, ReadsWhatItWrites) {
  for (const CanFrame& f : {CanFrame::make(0x297, {1, 2, 3, 4, 5, 6, 7, 8}), CanFrame::make(0, {})}) {
    const auto r = parse_candump_line(candump_line(f, kAt, "can0"));
    ASSERT_TRUE(r);
    EXPECT_TRUE(r->classic);
    EXPECT_EQ(r->frame, f);
    EXPECT_EQ(r->time, "1795431275.322679");
    EXPECT_EQ(r->interface_name, "can0");
  }
  const auto r = parse_candump_line("(1.5) can0 123#r8\r ");  // lower case, CR and blanks at the end
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->frame.rtr);
  EXPECT_EQ(r->frame.dlc, 8);
}

TEST(CandumpFormat, ExtendedAndFdFramesAreLinesButNoCanlustFrames) {
  const auto ext = parse_candump_line("(1.5) can0 12345678#00");
  ASSERT_TRUE(ext);
  EXPECT_FALSE(ext->classic);
  EXPECT_EQ(ext->frame, CanFrame{});
  const auto fd = parse_candump_line("(1.5) can0 123##1001122");
  ASSERT_TRUE(fd);
  EXPECT_FALSE(fd->classic);
}

TEST(CandumpFormat, MalformedLinesSayWhatIsWrong) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"not a line", "it does not begin with '(' and the time"},
      {"(1.5 can0 297#00", "no ')' after the time"},
      {"(15) can0 297#00", "the time is not SECONDS.MICROS"},
      {"(1.x) can0 297#00", "the time is not SECONDS.MICROS"},
      {"(1.5)can0 297#00", "no blank after the time"},
      {"(1.5) can0", "no interface name and frame after the time"},
      {"(1.5) can0 29700", "the frame is not ID#DATA"},
      {"(1.5) can0 #00", "the frame is not ID#DATA"},
      {"(1.5) can0 zz#00", "the identifier is not hex"},
      {"(1.5) can0 800#00", "a three-digit identifier above 7FF"},
      {"(1.5) can0 297#R9", "a remote frame's length is not one digit 0..8"},
      {"(1.5) can0 297#0F0", "the data is not 0..8 bytes of two hex digits each"},
      {"(1.5) can0 297#000102030405060708", "the data is not 0..8 bytes of two hex digits each"},
      {"(1.5) can0 297#0G", "the data is not 0..8 bytes of two hex digits each"},
  };
  for (const auto& [line, why] : bad) {
    const CandumpParsed p = read_candump_line(line);
    EXPECT_FALSE(p.record) << line;
    EXPECT_EQ(p.error, why) << line;
  }
}

TEST(CandumpFormat, LogSkipsBlankLinesAndNamesTheFirstBadOne) {
  const std::vector<std::string> lines = {"", "(1.000001) can0 297#0F00  \r", "  ", "(2.000000) can0 zz#00",
                                          "(3.000000) can0 297#00"};
  EXPECT_TRUE(is_candump_log(lines));
  const CandumpLog log = read_candump_log(lines);
  ASSERT_EQ(log.entries.size(), 1U);
  EXPECT_EQ(log.entries[0].line, 2U);
  EXPECT_EQ(log.entries[0].text, "(1.000001) can0 297#0F00");
  EXPECT_EQ(log.entries[0].record.frame, CanFrame::make(0x297, {0x0F, 0x00}));
  ASSERT_TRUE(log.error);
  EXPECT_EQ(log.error->line, 4U);
  EXPECT_EQ(log.error->text, "(2.000000) can0 zz#00");
  EXPECT_EQ(log.error->what, "the identifier is not hex");

  const std::vector<std::string> good = {"(1.000001) can0 297#0F00", "(2.000000) can0 12345678#00"};
  const CandumpLog ok = read_candump_log(good);
  EXPECT_FALSE(ok.error);
  ASSERT_EQ(ok.entries.size(), 2U);
  EXPECT_FALSE(ok.entries[1].record.classic);
}

TEST(CandumpFormat, ALogIsOneWhoseFirstLineIsACandumpLine) {
  EXPECT_FALSE(is_candump_log(std::vector<std::string>{}));
  EXPECT_FALSE(is_candump_log(std::vector<std::string>{" ", ""}));
  EXPECT_FALSE(is_candump_log(std::vector<std::string>{"# a trace", "(1.5) can0 297#00"}));
  EXPECT_TRUE(is_candump_log(std::vector<std::string>{"\r", "(1.5) can0 297#00", "garbage"}));
}

}  // namespace
}  // namespace ibs::can
