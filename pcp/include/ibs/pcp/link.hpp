// Segmentation of PMS messages over the MC6000's PCP channel of 1, 2 or 4 words (INTERBUS manual,
// 3.2.2) — the project's own design, because the chip's administrative byte is not public
// (public-facts.md, PCP). docs/pcp.md specifies it; this header is its one interface.
//
// INTERBUS manual 3.2.2 puts the channel on the servo's *INTERBUS CPU*: both ends of the link run at the
// bus cycle (the servo's interface side, not its 1 ms control sample), so every cycle each side
// shows one frame: the administrative byte (high byte of the first channel word) and
// 2 * words - 1 data bytes. The administrative byte:
//
//     bit  7     DIR   0 = master -> servo, 1 = servo -> master
//     bits 6..5  TYPE  00 control, 01 first fragment, 10 continuation, 11 last (or only) fragment
//     bits 4..3  SEQ   data frames: sequence counter (mod 4)
//                      control frames: 00 IDLE, 01 ABORT, 10 ABORT-ACK, 11 invalid
//     bits 2..1  ACK   data and IDLE frames: SEQ of the last data frame accepted from the peer
//                      ABORT: this side's abort number (mod 4, one more with every abort)
//                      ABORT-ACK: the abort number of the peer's ABORT it answers
//     bit  0     P     odd parity over the byte (00H and FFH are never valid)
//
// Go-back-N with a window of two fragments: a sender shows fragment s+1 in the cycle after s,
// before s is acknowledged (an answer takes a cycle each way on INTERBUS's summation frame, so a
// window of one would halve the rate), shows nothing newer until s is acknowledged, and shows s
// again when no acknowledgement came. The receiver takes only the next SEQ in order. A message is
// its PDU bytes alone: INTERBUS checks every cycle with its own frame check and delivers a cycle
// whole or not at all (public-facts.md, INTERBUS bus), so the link adds no CRC of its own; its
// length follows from the PDU's count word and the last fragment is padded with zeros. A lost,
// repeated or discarded cycle shows the receiver an old frame again, which the SEQ rule ignores;
// a message is delivered only when its length and padding check. ABORT / ABORT-ACK resynchronise
// both sides (start, restart, timeout, protocol violation) and drop every message in transfer.
// The abort number ties an ABORT-ACK to the ABORT it answers, and `acking` ends only on IDLE or a
// FIRST (or only) s0 frame, so a frame shown before an abort but seen after it never counts for
// the new link; when both sides abort at once the master's abort is answered first, then the
// servo's (docs/pcp.md, "Link").
//
// The cycle path (receive, transmit, send) allocates nothing, throws nothing, reads no clock.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/base/error.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/pcp/pdu.hpp"

namespace ibs::pcp {

// A message on the channel is its PDU: no link CRC (INTERBUS's frame check covers every cycle).
inline constexpr std::size_t kMaxMessageSize = kMaxPduSize;
inline constexpr int kMaxChannelWords = 4;
inline constexpr std::size_t kMaxFrameBytes = 2 * static_cast<std::size_t>(kMaxChannelWords);
inline constexpr std::size_t kMaxFrameData = kMaxFrameBytes - 1;
// The count word (PDU bytes 2..3) lies in the first frame only at 4 words, and only there does a
// message (the 6-byte Identify and Status requests) fit one frame: it goes as a LAST frame alone.
static_assert(kMinPduSize <= kMaxFrameData);

enum class Direction : std::uint8_t { to_server = 0, to_client = 1 };
enum class FrameType : std::uint8_t { control = 0, first = 1, middle = 2, last = 3 };
enum class ControlCode : std::uint8_t { idle = 0, abort = 1, abort_ack = 2 };

struct AdminByte {
  Direction dir = Direction::to_server;
  FrameType type = FrameType::control;
  std::uint8_t seq = 0;  // data: sequence counter; control: ControlCode
  std::uint8_t ack = 0;
  friend bool operator==(const AdminByte&, const AdminByte&) = default;
};

std::uint8_t encode_admin(AdminByte a);
// nullopt for a parity error or the invalid control code 11.
std::optional<AdminByte> decode_admin(std::uint8_t b);

constexpr bool valid_channel_words(int words) {
  return words == 1 || words == 2 || words == 4;
}
constexpr std::size_t frame_data_size(int words) {
  return static_cast<std::size_t>(2 * words - 1);
}

enum class LinkState : std::uint8_t {
  aborting,  // showing ABORT until the peer answers ABORT-ACK (after start, restart, abort)
  acking,    // the peer aborts: showing ABORT-ACK until it shows something else
  ready,
};
std::string_view to_string(LinkState s);

struct LinkConfig {
  int channel_words = 1;                       // 1, 2 or 4 (405-SUPI)
  Direction direction = Direction::to_server;  // DIR of the frames this side sends
  // A data frame the peer does not acknowledge within this time ends in a link abort.
  Duration ack_timeout = 100ms;
  // Start in `ready` instead of `aborting`: a side that was running before a recording starts
  // (trace `init: operational`). A restarting side must not use it.
  bool start_ready = false;
};

struct LinkStats {
  std::uint32_t frames_invalid = 0;      // parity, direction or control-code errors
  std::uint32_t frames_repeated = 0;     // a data frame seen again, or an older one (stale cycle)
  std::uint32_t frames_ahead = 0;        // a data frame one beyond the next: the next was missed
  std::uint32_t frames_refused = 0;      // a new data frame not taken while a message waits
  std::uint32_t fragments_orphaned = 0;  // continuation/last without a first
  std::uint32_t messages_sent = 0;
  std::uint32_t messages_received = 0;
  std::uint32_t messages_dropped = 0;  // length or padding check failed
  std::uint32_t sequence_errors = 0;     // an ACK naming a fragment this side never showed
  std::uint32_t ack_timeouts = 0;
  std::uint32_t aborts_local = 0;  // aborts this side started
  std::uint32_t aborts_peer = 0;   // aborts the peer started
  friend bool operator==(const LinkStats&, const LinkStats&) = default;
};

// What one receive() brought. Four bytes (alignas), so that it is returned as one register value
// instead of being assembled from three bytes on every receive().
struct alignas(4) LinkEvents {
  bool reset = false;             // all transfers were dropped (peer abort, timeout, protocol)
  bool message_sent = false;      // the peer acknowledged the last fragment of our message
  bool message_received = false;  // a checked message waits in message()
  friend bool operator==(const LinkEvents&, const LinkEvents&) = default;
};

class Link {
 public:
  // Refuses a width other than 1, 2 or 4 (ErrorCode::channel_width_invalid) and an ack_timeout
  // that is not positive (ErrorCode::channel_timeout_not_positive).
  [[nodiscard]] static Error validate(const LinkConfig& cfg);
  // A link of a configuration validate() accepts: otherwise it throws std::invalid_argument with
  // validate()'s message (configuration time), or, in the embedded build, aborts.
  explicit Link(const LinkConfig& cfg);

  [[nodiscard]] const LinkConfig& config() const { return cfg_; }
  [[nodiscard]] LinkState state() const { return state_; }
  [[nodiscard]] const LinkStats& stats() const { return stats_; }

  // Drops everything and resynchronises with the peer (ABORT until ABORT-ACK).
  void abort();

  // Reads the peer's frame of this cycle.
  LinkEvents receive(Time now, std::span<const Word> in);
  // Writes this side's frame for this cycle (channel_words words).
  void transmit(Time now, std::span<Word> out);

  // receive() and transmit() without their shortcut (the ready link's IDLE and data frames read
  // from and written to the words directly): every frame through the general decisions. The same
  // events, state, counters and words as receive() and transmit(); LinkShortcuts.* and the fuzz
  // target pcp_link_fuzz compare the two at random.
  LinkEvents receive_general(Time now, std::span<const Word> in);
  void transmit_general(Time now, std::span<Word> out);

  // Starts sending a PDU (kMinPduSize..kMaxPduSize bytes); false while not ready or busy.
  [[nodiscard]] bool can_send() const { return state_ == LinkState::ready && !tx_active_; }
  bool send(std::span<const std::uint8_t> pdu);
  [[nodiscard]] bool sending() const { return tx_active_; }

  // The received message (its PDU) until release_message().
  [[nodiscard]] bool has_message() const { return rx_complete_; }
  // Inline (as has_message): the server and client call them on every message they take.
  [[nodiscard]] std::span<const std::uint8_t> message() const {
    if (!rx_complete_) return {};
    return {rx_.data(), rx_expected_};
  }
  void release_message() {
    rx_complete_ = false;
    rx_size_ = 0;
    rx_expected_ = 0;
  }

 private:
  void reset_transfers();
  void enter_acking(std::uint8_t peer_abort_number);
  void leave_acking();
  // False: the ACK names a fragment this side never showed (a sequence error).
  bool take_ack(Time now, std::uint8_t ack, LinkEvents& ev);
  // Moves the base on by `advance` (1 or 2) acknowledged fragments; true: the message is sent.
  bool move_window(Time now, std::uint8_t advance);
  [[nodiscard]] std::size_t fragment_size(std::size_t offset) const {
    return std::min(data_size_, tx_size_ - offset);
  }
  void process_data(const AdminByte& a, std::span<const std::uint8_t> data, LinkEvents& ev);
  // The shortcuts of a ready link over N channel words (link.cpp).
  template <std::size_t N>
  LinkEvents receive_ready(Time now, std::span<const Word> in);
  template <std::size_t N>
  void transmit_ready(Time now, std::span<Word> out);
  // Ends the message at its LAST fragment; true: it checked and waits in message().
  bool finish_message();
  // The shortcut's events of a LAST fragment (a call of its own, so that the shortcut's other
  // frames save no registers for it).
  LinkEvents finish_ready(bool message_sent);

  LinkConfig cfg_;
  std::size_t data_size_;
  Direction peer_dir_;
  LinkState state_ = LinkState::aborting;
  LinkStats stats_{};
  // Abort numbers: this side's (the first ABORT after construction carries 3, then 0, 1, ...) and
  // the one of the peer's ABORT being answered.
  std::uint8_t abort_number_ = 3;
  std::uint8_t peer_abort_number_ = 3;
  // Both sides aborted at once (the master's goes first): the servo answers the master's abort and
  // waits for the answer to its own (own_abort_pending_); the master has noted the servo's abort
  // and answers it after its own (peer_abort_waiting_).
  bool own_abort_pending_ = false;
  bool peer_abort_waiting_ = false;

  // Sending. The PDU, then zeros up to a whole frame's data beyond it (send() clears them), so
  // that a LAST fragment's padding is always the bytes after the PDU.
  std::array<std::uint8_t, kMaxMessageSize + kMaxFrameData> tx_{};
  std::size_t tx_size_ = 0;
  std::size_t tx_offset_ = 0;  // first byte of the oldest unacknowledged fragment (the base)
  bool tx_active_ = false;
  // The window: the base (SEQ tx_seq_) and the fragment after it; which of them has been on the
  // channel, and which was shown last (-1: one before the base, after the base moved on).
  std::array<bool, 2> tx_shown_{};
  int tx_last_shown_ = -1;
  // Went back to the base: show it until it is acknowledged (a peer slower than this side would
  // otherwise always see the same one of two alternating fragments).
  bool tx_back_ = false;
  Time tx_since_{};  // when the base was first shown or last acknowledged progress came
  std::uint8_t tx_seq_ = 0;

  // Receiving. A message and the last frame's padding fit kRxLimit bytes; rx_ has one more, so
  // that the 4-word shortcut stores a frame's data and finish_message reads the padding as 8.
  static constexpr std::size_t kRxLimit = kMaxMessageSize + kMaxFrameData;
  std::array<std::uint8_t, kRxLimit + 1> rx_{};
  std::size_t rx_size_ = 0;
  std::size_t rx_expected_ = 0;  // message size once the count word is in, else 0
  bool rx_in_message_ = false;
  bool rx_complete_ = false;
  std::uint8_t rx_last_ = 3;
};

}  // namespace ibs::pcp
