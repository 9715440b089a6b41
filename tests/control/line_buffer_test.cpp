// One client's input of the control channel (transports/control, line_buffer.hpp): bytes in,
// bounded lines out, numbered in this input; a line too long is reported once, at once, and
// skipped to its newline, and the input goes on (issue 41).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "ibs/control/line_buffer.hpp"

namespace ibs::control {
namespace {

// What came out of a buffer: "N:text" for a line, "N:overlong" for a report.
struct Feed {
  explicit Feed(std::size_t max_line) : buffer(max_line) {}
  LineBuffer buffer;
  std::vector<std::string> out;

  void drain() {
    while (const auto item = buffer.next()) record(item);
  }
  void record(const LineBuffer::Item& item) {
    out.push_back(std::to_string(item.number) + ":" +
                  (item.kind == LineBuffer::Kind::line ? std::string(item.text) : std::string("overlong")));
  }
  // Feeds `bytes` in pieces of at most `chunk` bytes (and at most what space() offers).
  void feed(const std::string& bytes, std::size_t chunk = 1 << 20) {
    std::size_t at = 0;
    while (at < bytes.size()) {
      drain();
      const auto room = buffer.space();
      ASSERT_FALSE(room.empty());
      const std::size_t n = std::min({chunk, room.size(), bytes.size() - at});
      std::copy_n(bytes.data() + at, n, room.data());
      buffer.commit(n);
      at += n;
    }
    drain();
  }
  void finish() {
    if (const auto last = buffer.finish()) record(last);
  }
};

TEST(LineBuffer, LinesAreNumberedInTheirInputBlankAndCommentLinesCounted) {
  for (const std::size_t chunk : {1U, 2U, 7U, 4096U}) {
    Feed f(64);
    f.feed("first\r\n\n  # a comment\n\t\nsecond\nlast without newline", chunk);
    f.finish();
    EXPECT_EQ(f.out, (std::vector<std::string>{"1:first", "5:second", "6:last without newline"})) << chunk;
  }
}

TEST(LineBuffer, ALineOfMaxLineCharactersIsALineOneMoreIsReportedAtOnceAndSkipped) {
  Feed f(8);
  f.feed("12345678\n");
  EXPECT_EQ(f.out, (std::vector<std::string>{"1:12345678"}));
  // Nine characters and no newline yet: reported now, not when (if ever) the line ends.
  f.feed("123456789");
  EXPECT_EQ(f.out.back(), "2:overlong");
  // The rest of it, however long, is dropped up to its newline; the next line is the third.
  f.feed(std::string(100000, 'x'), 3);
  EXPECT_EQ(f.out.size(), 2U);
  f.feed("tail\nnext\n");
  EXPECT_EQ(f.out, (std::vector<std::string>{"1:12345678", "2:overlong", "3:next"}));
}

TEST(LineBuffer, AnOverlongLastLineIsReportedOnceEvenWithoutItsNewline) {
  Feed f(4);
  f.feed("ok\n0123456789");
  f.finish();
  EXPECT_EQ(f.out, (std::vector<std::string>{"1:ok", "2:overlong"}));
  // finish() starts a new input: numbering from 1 again.
  f.feed("again\n");
  EXPECT_EQ(f.out.back(), "1:overlong");  // "again" is five characters: too long for 4
  f.feed("abc\n");
  EXPECT_EQ(f.out.back(), "2:abc");
}

TEST(LineBuffer, ManyLinesInOneReadComeOutInOrderAndSpaceIsNeverEmpty) {
  Feed f(16);
  std::string text;
  std::vector<std::string> want;
  for (int i = 1; i <= 500; ++i) {
    text += "line " + std::to_string(i) + "\n";
    want.push_back(std::to_string(i) + ":line " + std::to_string(i));
  }
  f.feed(text, 13);
  EXPECT_EQ(f.out, want);
  EXPECT_EQ(f.buffer.buffered(), 0U);
}

TEST(LineBuffer, RefusesAZeroLimitAndACommitBeyondItsSpace) {
  EXPECT_THROW(LineBuffer(0), std::invalid_argument);
  LineBuffer b(4);
  EXPECT_EQ(b.space().size(), 5U);
  EXPECT_THROW(b.commit(6), std::logic_error);
}

}  // namespace
}  // namespace ibs::control
