// The controller's receiver: which frames it answers, NAK 86 for unknown commands and wrong
// lengths, the turnaround delay before the reply, the global 83 without an answer.
#include <gtest/gtest.h>

#include <vector>

#include "ibs/dfs1/controller.hpp"

namespace ibs::dfs1 {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes bytes_of(const Frame& f) {
  const EncodedFrame e = encode(f);
  return {e.span().begin(), e.span().end()};
}

class RecordingHandler final : public RequestHandler {
 public:
  Reply handle(const Frame& request, bool global, Time) override {
    seen.push_back(request);
    globals += global ? 1 : 0;
    return Reply::ack();
  }
  std::vector<Frame> seen;
  int globals = 0;
};

TEST(Dfs1Receiver, AnswersItsUidAfterTheTurnaround) {
  RecordingHandler h;
  ControllerReceiver rx(5, 2ms);
  rx.receive(bytes_of(make_frame(5, 0x81)), 10ms, h);
  ASSERT_EQ(h.seen.size(), 1U);
  EXPECT_TRUE(rx.pending(11ms).empty());
  EXPECT_EQ(rx.next_deadline(), Time(12ms));
  const auto p = rx.pending(12ms);
  EXPECT_EQ(Bytes(p.begin(), p.end()), bytes_of(make_ack(5)));
  rx.consume(3);
  EXPECT_EQ(rx.pending(12ms).size(), p.size() - 3);
  rx.consume(100);
  EXPECT_FALSE(rx.replying());
}

TEST(Dfs1Receiver, UnknownCommandIsNak86WithoutTheHandler) {
  RecordingHandler h;
  ControllerReceiver rx(5, 0ms);
  rx.receive(bytes_of(make_frame(5, 0x90)), 0ms, h);
  EXPECT_TRUE(h.seen.empty());
  const auto p = rx.pending(0ms);
  EXPECT_EQ(Bytes(p.begin(), p.end()), bytes_of(make_nak(5, ErrorCode::illegal_command)));
}

TEST(Dfs1Receiver, WrongDataLengthIsNak86) {
  RecordingHandler h;
  ControllerReceiver rx(5, 0ms);
  rx.receive(bytes_of(make_frame(5, 0x85)), 0ms, h);  // read parameter without its number
  EXPECT_TRUE(h.seen.empty());
  const auto p = rx.pending(0ms);
  EXPECT_EQ(Bytes(p.begin(), p.end()), bytes_of(make_nak(5, ErrorCode::illegal_command)));
}

TEST(Dfs1Receiver, FramesForAnotherUidGetNoAnswer) {
  RecordingHandler h;
  ControllerReceiver rx(5, 0ms);
  rx.receive(bytes_of(make_frame(6, 0x81)), 0ms, h);
  rx.receive(bytes_of(make_frame(6, 0x90)), 0ms, h);
  rx.receive(bytes_of(make_ack(5)), 0ms, h);  // another controller's answer with our UID
  EXPECT_TRUE(h.seen.empty());
  EXPECT_FALSE(rx.replying());
  EXPECT_EQ(rx.counters().foreign, 3U);
}

TEST(Dfs1Receiver, GlobalExecuteSpeedIsHandledWithoutAnswer) {
  RecordingHandler h;
  ControllerReceiver rx(5, 0ms);
  rx.receive(bytes_of(make_frame(0, 0x83)), 0ms, h);
  EXPECT_EQ(h.globals, 1);
  EXPECT_FALSE(rx.replying());
  // UID 0 with any other command is ignored (notes: UID 00 only with 83).
  rx.receive(bytes_of(make_frame(0, 0x81)), 0ms, h);
  rx.receive(bytes_of(make_frame(0, 0x90)), 0ms, h);
  EXPECT_EQ(h.seen.size(), 1U);
  EXPECT_FALSE(rx.replying());
}

TEST(Dfs1Receiver, CorruptFramesAreCountedAndNotAnswered) {
  RecordingHandler h;
  ControllerReceiver rx(5, 0ms);
  Bytes b = bytes_of(make_frame(5, 0x81));
  b.back() ^= 0xFF;
  rx.receive(b, 0ms, h);
  EXPECT_TRUE(h.seen.empty());
  EXPECT_FALSE(rx.replying());
  EXPECT_EQ(rx.counters().decode_errors, 1U);
}

}  // namespace
}  // namespace ibs::dfs1
