// The DFS-1 frame decoder (docs/dfs1.md, "Frame"), the controller's side and the host's side fed
// arbitrary line bytes.
//
// Asserts:
// - every decoded frame has at most 16 data bytes and a right checksum, and re-encodes to bytes
//   that decode to the same frame with no error and nothing left over; an encoding holds no lone
//   DLE (every 10H outside DLE STX / DLE ETX comes in pairs);
// - the emulated controller's every reply decodes to exactly one ACK or NAK frame; a NAK carries
//   one error code of 80..86; a reply only follows a frame for the controller's UID, never the
//   global 83 nor a frame for another UID;
// - the host never reports ACK or NAK from a frame with another UID, an ACK's data length is the
//   command's, a NAK carries one byte, and every transaction ends by the response timeout
//   (bytes arrive 1 ms apart; an inter-byte gap counts from the last byte);
// - a silence longer than the fragment timeout before any byte drops what was begun and nothing
//   else: the same invariants hold on the rest of the line, and no fragment is dropped without one.
//
// Input: byte 0 the controller's UID (0 taken as 1), byte 1 the host's UID, byte 2 the host's
// command (index into the command table); the rest is the line.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/devices/dfs1/controller.hpp"
#include "ibs/dfs1/frame.hpp"
#include "ibs/dfs1/host.hpp"

namespace {

using namespace ibs;
namespace proto = ibs::dfs1;

void check_frame(const proto::Frame& f) {
  IBS_FUZZ_REQUIRE(f.size <= proto::kMaxData, "data too long");
  const proto::EncodedFrame e = proto::encode(f);
  unsigned sum = f.uid + f.code;
  for (std::uint8_t b : f.payload()) sum += b;
  IBS_FUZZ_REQUIRE(((sum + proto::checksum(f)) & 0xFFU) == 0, "checksum");
  // No lone DLE: after DLE STX, every DLE is doubled until DLE ETX; the checksum likewise.
  const auto s = e.span();
  IBS_FUZZ_REQUIRE(s.size() >= 7 && s[0] == proto::kDle && s[1] == proto::kStx, "frame start");
  std::size_t i = 2;
  for (; i + 1 < s.size(); ++i) {
    if (s[i] != proto::kDle) continue;
    if (s[i + 1] == proto::kEtx) break;
    IBS_FUZZ_REQUIRE(s[i + 1] == proto::kDle, "lone DLE in an encoding");
    ++i;
  }
  proto::FrameDecoder d;
  int frames = 0;
  for (std::uint8_t b : s) {
    const proto::DecodeResult r = d.push(b);
    IBS_FUZZ_REQUIRE(r.status != proto::DecodeStatus::error,
                     "re-encoded frame does not decode: " + std::string(proto::to_string(r.error)));
    if (r.status == proto::DecodeStatus::frame) {
      ++frames;
      IBS_FUZZ_REQUIRE(d.frame() == f, "re-encoded frame decodes differently");
    }
  }
  IBS_FUZZ_REQUIRE(frames == 1 && !d.in_frame(), "re-encoded frame is not exactly one frame");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  const std::uint8_t controller_uid = data[0] == 0 ? 1 : data[0];
  const std::uint8_t host_uid = data[1] == 0 ? 1 : data[1];
  const proto::CommandInfo& cmd = proto::kCommandTable[data[2] % proto::kCommandTable.size()];
  const std::vector<std::uint8_t> line(data + 3, data + size);

  // 1. The decoder.
  proto::FrameDecoder decoder;
  for (std::uint8_t b : line) {
    if (decoder.push(b).status == proto::DecodeStatus::frame) check_frame(decoder.frame());
  }

  // 2. The controller side, one byte per millisecond; a second time with a silence longer than
  // the fragment timeout before the byte at `cut` (a host that died there, D13): what came
  // before it is dropped, so the judge's own decoder forgets it too.
  const std::size_t cut = data[1] % (line.size() + 1);
  for (const bool silent : {false, true}) {
    devices::dfs1::Controller controller({controller_uid});
    proto::FrameDecoder seen;  // what the controller has been told, to judge its replies
    Time now{};
    for (std::size_t i = 0; i < line.size(); ++i) {
      const std::uint8_t b = line[i];
      now += 1ms;
      if (silent && i == cut) now += proto::fragment_timeout(9600) + 1ms;
      const std::uint8_t uid_before = controller.uid();
      const std::uint64_t requests_before = controller.counters().requests;
      const std::uint64_t globals_before = controller.counters().globals;
      const std::uint64_t fragments_before = controller.counters().fragments;
      const std::optional<Time> deadline_before = controller.next_deadline();
      controller.receive(b, now);
      if (controller.counters().fragments != fragments_before) {
        IBS_FUZZ_REQUIRE(silent && i == cut, "a fragment dropped without a silence");
        seen.reset();
      }
      const bool frame = seen.push(b).status == proto::DecodeStatus::frame;
      if (controller.counters().requests != requests_before) {
        IBS_FUZZ_REQUIRE(frame, "a request handled without a frame");
        const bool global = controller.counters().globals != globals_before;
        IBS_FUZZ_REQUIRE(global ? seen.frame().uid == 0 : seen.frame().uid == uid_before,
                         "handled a frame for another UID");
        IBS_FUZZ_REQUIRE(!global || controller.next_deadline() == deadline_before,
                         "answered the global 83");
      } else if (frame) {
        IBS_FUZZ_REQUIRE(seen.frame().uid != uid_before || seen.frame().code == proto::kAck ||
                             seen.frame().code == proto::kNak,
                         "a frame for us was not handled");
      }
      if (auto due = controller.next_deadline(); due && *due <= now) {
        const auto reply = controller.pending(now);
        proto::FrameDecoder rd;
        int frames = 0;
        for (std::uint8_t r : reply) {
          const proto::DecodeResult res = rd.push(r);
          IBS_FUZZ_REQUIRE(res.status != proto::DecodeStatus::error, "reply does not decode");
          if (res.status == proto::DecodeStatus::frame) {
            ++frames;
            const proto::Frame& f = rd.frame();
            IBS_FUZZ_REQUIRE(f.is_ack() || f.is_nak(), "reply is neither ACK nor NAK");
            if (f.is_nak()) {
              IBS_FUZZ_REQUIRE(f.size == 1 && f.data[0] >= 0x80 && f.data[0] <= 0x86, "NAK code");
            }
          }
        }
        IBS_FUZZ_REQUIRE(frames == 1, "a reply is not exactly one frame");
        controller.consume(reply.size());
      }
    }
  }

  // 3. The host side: a request of the chosen command, the line as its answer.
  proto::Frame request = proto::make_frame(host_uid, static_cast<std::uint8_t>(cmd.command),
                                           std::vector<std::uint8_t>(cmd.request_size, 0x10));
  proto::HostTransaction host({100ms, 10ms});
  IBS_FUZZ_REQUIRE(host.start(request, 0ms) == proto::StartStatus::accepted, "request refused");
  host.transmitted(0ms);
  Time t{};
  Time last_byte{};
  for (std::uint8_t b : line) {
    if (host.done()) break;
    t += 1ms;
    host.receive(b, t);
    last_byte = t;
  }
  host.poll(last_byte + 100ms);
  IBS_FUZZ_REQUIRE(host.done(), "the transaction did not end by its timeouts");
  const auto result = host.take_result();
  IBS_FUZZ_REQUIRE(result.has_value(), "no result");
  if (result->outcome == proto::Outcome::ack || result->outcome == proto::Outcome::nak ||
      result->outcome == proto::Outcome::bad_response) {
    IBS_FUZZ_REQUIRE(result->response.uid == host_uid, "an answer from another UID was taken");
  }
  if (result->outcome == proto::Outcome::ack) {
    IBS_FUZZ_REQUIRE(result->response.is_ack() && result->response.size == cmd.response_size,
                     "ACK of the wrong length");
  }
  if (result->outcome == proto::Outcome::nak) {
    IBS_FUZZ_REQUIRE(result->response.is_nak() && result->response.size == 1, "NAK shape");
  }
  return 0;
}
