#include "ibs/pcp/link.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ibs::pcp {

namespace {

constexpr std::uint8_t kSeqMask = 0x03;

constexpr std::uint8_t next_seq(std::uint8_t s) {
  return static_cast<std::uint8_t>((s + 1U) & kSeqMask);
}

// The administrative byte's rules as tables (docs/pcp.md, "Administrative byte"), so that a frame
// costs a load instead of a bit count. kParityBit[b >> 1]: the P bit that gives bits 7..1 of b odd
// parity. kAdminValid[b]: odd parity, and not the invalid control code 11.
constexpr std::array<std::uint8_t, 128> kParityBit = [] {
  std::array<std::uint8_t, 128> t{};
  for (unsigned i = 0; i < t.size(); ++i) t[i] = std::popcount(i) % 2 == 0 ? 1 : 0;
  return t;
}();
constexpr std::array<bool, 256> kAdminValid = [] {
  std::array<bool, 256> t{};
  for (unsigned b = 0; b < t.size(); ++b) {
    t[b] = std::popcount(b) % 2 == 1 && !(((b >> 5U) & 3U) == 0 && ((b >> 3U) & 3U) == 3);
  }
  return t;
}();

// A frame of 4 words as one 64-bit number (little-endian host): the words' bytes swapped give the
// frame's bytes in channel order (each word high byte first, docs/pcp.md "Frame"), and back.
constexpr bool kWholeFrames = std::endian::native == std::endian::little;
constexpr std::uint64_t kLowBytes = 0x00FF00FF00FF00FFULL;
constexpr std::uint64_t swap_word_bytes(std::uint64_t x) {
  return ((x >> 8U) & kLowBytes) | ((x & kLowBytes) << 8U);
}

}  // namespace

std::uint8_t encode_admin(AdminByte a) {
  unsigned b = (static_cast<unsigned>(a.dir) & 1U) << 7U;
  b |= (static_cast<unsigned>(a.type) & 3U) << 5U;
  b |= (static_cast<unsigned>(a.seq) & 3U) << 3U;
  b |= (static_cast<unsigned>(a.ack) & 3U) << 1U;
  // Odd parity: the byte always has an odd number of ones.
  b |= kParityBit[b >> 1U];
  return static_cast<std::uint8_t>(b);
}

std::optional<AdminByte> decode_admin(std::uint8_t b) {
  if (!kAdminValid[b]) return std::nullopt;  // even parity, or the control code 11
  AdminByte a;
  a.dir = static_cast<Direction>((b >> 7U) & 1U);
  a.type = static_cast<FrameType>((b >> 5U) & 3U);
  a.seq = static_cast<std::uint8_t>((b >> 3U) & 3U);
  a.ack = static_cast<std::uint8_t>((b >> 1U) & 3U);
  return a;
}

std::string_view to_string(LinkState s) {
  switch (s) {
    case LinkState::aborting:
      return "aborting";
    case LinkState::acking:
      return "acking";
    case LinkState::ready:
      return "ready";
  }
  return "?";
}

Error Link::validate(const LinkConfig& cfg) {
  if (!valid_channel_words(cfg.channel_words)) {
    return {ErrorCode::channel_width_invalid,
            "PCP channel of " + std::to_string(cfg.channel_words) +
                " words: the MC6000 offers 1, 2 or 4 (405-SUPI, INTERBUS manual 3.2.2)"};
  }
  if (cfg.ack_timeout <= Duration::zero()) {
    return {ErrorCode::channel_timeout_not_positive, "PCP link ack_timeout must be positive"};
  }
  return {};
}

namespace {
const LinkConfig& checked(const LinkConfig& cfg) {
  detail::require<std::invalid_argument>(Link::validate(cfg));
  return cfg;
}
}  // namespace

Link::Link(const LinkConfig& cfg)
    : cfg_(checked(cfg)),
      data_size_(frame_data_size(cfg.channel_words)),
      peer_dir_(cfg.direction == Direction::to_server ? Direction::to_client
                                                      : Direction::to_server) {
  reset_transfers();
  if (cfg.start_ready) state_ = LinkState::ready;
}

void Link::reset_transfers() {
  tx_size_ = 0;
  tx_offset_ = 0;
  tx_active_ = false;
  tx_shown_ = {false, false};
  tx_last_shown_ = -1;
  tx_back_ = false;
  tx_seq_ = 0;
  rx_size_ = 0;
  rx_expected_ = 0;
  rx_in_message_ = false;
  rx_complete_ = false;
  rx_last_ = 3;  // the first data frame after a reset carries SEQ 0
}

void Link::abort() {
  reset_transfers();
  own_abort_pending_ = false;
  // A new abort gets the next number; aborting again before the peer answered is the same abort
  // (nothing can have crossed meanwhile), so that an old ABORT-ACK on a channel the peer stopped
  // updating cannot come round again as the answer after four quick aborts.
  if (state_ != LinkState::aborting) abort_number_ = next_seq(abort_number_);
  state_ = LinkState::aborting;
  ++stats_.aborts_local;
}

void Link::enter_acking(std::uint8_t peer_abort_number) {
  reset_transfers();
  peer_abort_number_ = peer_abort_number;
  peer_abort_waiting_ = false;
  state_ = LinkState::acking;
  ++stats_.aborts_peer;
}

void Link::leave_acking() {
  if (own_abort_pending_) {
    abort();  // the master never answered the servo's own abort: announce it again
  } else {
    state_ = LinkState::ready;
  }
}

bool Link::send(std::span<const std::uint8_t> pdu) {
  if (!can_send() || pdu.size() < kMinPduSize || pdu.size() > kMaxPduSize) return false;
  // The receiver delimits the message by its count word, so it must be right (decode_header's
  // count check; the size is in range here).
  if (pdu.size() != 4U + 2U * make_word(pdu[2], pdu[3])) return false;
  std::copy(pdu.begin(), pdu.end(), tx_.begin());
  std::fill_n(tx_.begin() + static_cast<std::ptrdiff_t>(pdu.size()), kMaxFrameData,
              std::uint8_t{0});
  tx_size_ = pdu.size();
  tx_offset_ = 0;
  tx_active_ = true;
  tx_shown_ = {false, false};
  tx_last_shown_ = -1;
  tx_back_ = false;
  return true;
}

LinkEvents Link::receive(Time now, std::span<const Word> in) {
  // The shortcut: a ready link, no ack timeout due, and a valid IDLE or data frame of the peer --
  // every cycle of a transfer. It decides as receive_general does (docs/pcp.md, "Go-back-N"),
  // reading the words directly (receive_ready); anything else (another state, a timeout, a short,
  // invalid or foreign frame, ABORT, ABORT-ACK, a control frame with data) goes the general way.
  if (state_ == LinkState::ready &&
      !(tx_active_ && tx_shown_[0] && now - tx_since_ >= cfg_.ack_timeout)) {
    const auto words = static_cast<std::size_t>(cfg_.channel_words);  // 1, 2 or 4 (validate)
    if (in.size() >= words) {
      if (words == 4) return receive_ready<4>(now, in);
      if (words == 2) return receive_ready<2>(now, in);
      return receive_ready<1>(now, in);
    }
  }
  return receive_general(now, in);
}

// Inline: the shortcut moves the window in most data frames of a transfer.
inline bool Link::move_window(Time now, std::uint8_t advance) {
  for (std::uint8_t k = 0; k < advance; ++k) {
    tx_offset_ += fragment_size(tx_offset_);
    tx_seq_ = next_seq(tx_seq_);
  }
  if (tx_offset_ >= tx_size_) {
    tx_active_ = false;
    ++stats_.messages_sent;
    return true;
  }
  // The window moves on: the new base may already have been shown (it was the fragment after).
  tx_shown_ = {advance == 1 && tx_shown_[1], false};
  tx_last_shown_ -= advance;
  tx_back_ = false;
  tx_since_ = now;
  return false;
}

template <std::size_t N>
LinkEvents Link::receive_ready(Time now, std::span<const Word> in) {
  // Whatever this does not decide itself it hands to receive_general before changing anything, so
  // that the general way decides that frame from the same state.
  std::array<Word, N> w;
  for (std::size_t i = 0; i < N; ++i) w[i] = in[i];
  const std::uint8_t admin = high_byte(w[0]);
  if (!kAdminValid[admin] || static_cast<Direction>(admin >> 7U) != peer_dir_) {
    return receive_general(now, in);
  }
  const auto type = static_cast<FrameType>((admin >> 5U) & 3U);
  const auto seq = static_cast<std::uint8_t>((admin >> 3U) & 3U);
  const auto ack = static_cast<std::uint8_t>((admin >> 1U) & 3U);
  if (type == FrameType::control) {
    unsigned data = low_byte(w[0]);  // IDLE carries zero data bytes only
    for (std::size_t i = 1; i < N; ++i) data |= w[i];
    if (seq != static_cast<std::uint8_t>(ControlCode::idle) || data != 0) {
      return receive_general(now, in);
    }
  }
  // The ACK (take_ack; an idle peer still acknowledges our fragments): mostly the base's
  // predecessor, nothing new. One naming a fragment never shown is a sequence error.
  LinkEvents ev;
  const auto advance = static_cast<std::uint8_t>((ack - tx_seq_ + 1U) & kSeqMask);
  if (advance != 0) {
    if (!tx_active_ || advance == 3 || !tx_shown_[advance - 1U]) return receive_general(now, in);
    ev.message_sent = move_window(now, advance);
  }
  if (type == FrameType::control) return ev;

  // A data frame (process_data): only the next SEQ is new; the one before and the one before that
  // are old frames seen again, the one after the second of a window whose first we missed.
  const std::uint8_t last = rx_last_;
  if (seq != next_seq(last)) {
    if (seq == next_seq(next_seq(last))) {
      ++stats_.frames_ahead;
    } else {
      ++stats_.frames_repeated;
    }
    return ev;
  }
  if (rx_complete_) {
    ++stats_.frames_refused;  // not acknowledged: the peer repeats it until we take it
    return ev;
  }
  rx_last_ = seq;
  constexpr std::size_t kData = 2 * N - 1;
  if (type == FrameType::first ||
      (type == FrameType::last && !rx_in_message_ && kData >= kMinPduSize)) {
    rx_size_ = 0;  // FIRST opens a message; over 4 words a LAST outside one is a message alone
    rx_expected_ = 0;
    rx_in_message_ = true;
  } else if (!rx_in_message_) {
    ++stats_.fragments_orphaned;
    return ev;
  }
  std::size_t size = rx_size_;
  if (size + kData > kRxLimit) {
    rx_in_message_ = false;
    ++stats_.messages_dropped;
    return ev;
  }
  std::uint8_t* p = rx_.data() + size;
  if constexpr (N == 4 && kWholeFrames) {
    // The whole frame at once: its bytes without the admin byte, and a zero after them (rx_ has
    // the room; nothing reads past rx_size_).
    std::uint64_t x = 0;
    std::memcpy(&x, w.data(), sizeof x);
    const std::uint64_t data = swap_word_bytes(x) >> 8U;
    std::memcpy(p, &data, sizeof data);
  } else {
    p[0] = low_byte(w[0]);
    for (std::size_t i = 1; i < N; ++i) {
      p[2 * i - 1] = high_byte(w[i]);
      p[2 * i] = low_byte(w[i]);
    }
  }
  size += kData;
  rx_size_ = size;
  if (rx_expected_ == 0 && size >= 4) {
    const std::size_t pdu = 4U + 2U * make_word(rx_[2], rx_[3]);
    if (pdu < kMinPduSize || pdu > kMaxPduSize) {
      rx_in_message_ = false;
      ++stats_.messages_dropped;
      return ev;
    }
    rx_expected_ = pdu;
  }
  if (type == FrameType::last) return finish_ready(ev.message_sent);
  if (rx_expected_ != 0 && size >= rx_expected_) {
    rx_in_message_ = false;  // the message is complete but its fragment does not say LAST
    ++stats_.messages_dropped;
  }
  return ev;
}

LinkEvents Link::finish_ready(bool message_sent) {
  LinkEvents ev;
  ev.message_sent = message_sent;
  ev.message_received = finish_message();
  return ev;
}

// Out of line, so that the shortcuts' common case saves no registers for it.
[[gnu::noinline]] LinkEvents Link::receive_general(Time now, std::span<const Word> in) {
  LinkEvents ev;
  if (state_ == LinkState::ready && tx_active_ && tx_shown_[0] &&
      now - tx_since_ >= cfg_.ack_timeout) {
    ++stats_.ack_timeouts;
    abort();
    ev.reset = true;
    return ev;
  }
  const auto words = static_cast<std::size_t>(cfg_.channel_words);
  if (in.size() < words) {
    ++stats_.frames_invalid;
    return ev;
  }
  std::array<std::uint8_t, kMaxFrameBytes> b{};
  for (std::size_t i = 0; i < words; ++i) {
    b[2 * i] = high_byte(in[i]);
    b[2 * i + 1] = low_byte(in[i]);
  }
  const std::optional<AdminByte> a = decode_admin(b[0]);
  const std::span<const std::uint8_t> data(b.data() + 1, data_size_);
  if (!a || a->dir != peer_dir_) {
    ++stats_.frames_invalid;
    return ev;
  }

  if (a->type == FrameType::control) {
    if (std::any_of(data.begin(), data.end(), [](std::uint8_t x) { return x != 0; })) {
      ++stats_.frames_invalid;
      return ev;
    }
    const auto code = static_cast<ControlCode>(a->seq);
    switch (state_) {
      case LinkState::aborting:
        if (code == ControlCode::abort_ack && a->ack == abort_number_) {
          // The answer to this abort (an ABORT-ACK of an earlier one may still be on the channel,
          // a repeated cycle). The master then answers the servo's abort it saw meanwhile.
          if (peer_abort_waiting_) {
            enter_acking(peer_abort_number_);
          } else {
            state_ = LinkState::ready;
          }
        } else if (code == ControlCode::abort) {
          // Both sides abort: the master's goes first. The servo answers it and waits for the
          // master's answer to its own; the master notes the servo's and answers it after.
          if (cfg_.direction == Direction::to_client) {
            enter_acking(a->ack);
            own_abort_pending_ = true;
          } else {
            peer_abort_waiting_ = true;
            peer_abort_number_ = a->ack;
          }
        }
        break;
      case LinkState::acking:
        if (code == ControlCode::abort && a->ack != peer_abort_number_) {
          enter_acking(a->ack);  // the peer aborted once more
          ev.reset = true;
        } else if (code == ControlCode::abort_ack && cfg_.direction == Direction::to_client &&
                   a->ack == abort_number_) {
          // The master answers the servo's abort after its own: both have dropped everything.
          own_abort_pending_ = false;
          state_ = LinkState::ready;
        } else if (code == ControlCode::idle) {
          // The peer took our ABORT-ACK. A servo whose own abort is unanswered announces it again:
          // the master's ABORT it answered may have been an old one on a repeated cycle.
          leave_acking();
        }
        break;
      case LinkState::ready:
        if (code == ControlCode::abort) {
          enter_acking(a->ack);
          ev.reset = true;
        } else if (code == ControlCode::idle) {
          // An idle peer still acknowledges our fragments.
          if (!take_ack(now, a->ack, ev)) {
            ++stats_.sequence_errors;
            abort();
            ev.reset = true;
          }
        }
        break;
    }
    return ev;
  }

  // A data frame.
  if (state_ == LinkState::aborting) return ev;  // the peer has not seen our ABORT yet
  if (state_ == LinkState::acking) {
    // The peer took our ABORT-ACK and starts its first message (FIRST s0, or LAST s0 for a
    // message of one frame); any other data frame is from before its abort, or the second of
    // the peer's window while we missed its first.
    const bool only = a->type == FrameType::last && data_size_ >= kMinPduSize;
    if ((a->type != FrameType::first && !only) || a->seq != 0) return ev;
    leave_acking();
    if (state_ != LinkState::ready) return ev;
  }
  if (!take_ack(now, a->ack, ev)) {
    // Between two correct peers an ACK names the base's predecessor or a fragment shown since:
    // the peer's state is not ours. Resynchronise.
    ++stats_.sequence_errors;
    abort();
    ev.reset = true;
    return ev;
  }
  process_data(*a, data, ev);
  return ev;
}

bool Link::take_ack(Time now, std::uint8_t ack, LinkEvents& ev) {
  // The peer's ACK names the last fragment it accepted: the base's predecessor (nothing new), the
  // base, or the fragment after it -- only ones that have been on the channel (docs/pcp.md,
  // "Go-back-N"). Idle, the base is the next SEQ to use and only its predecessor is valid.
  const auto advance = static_cast<std::uint8_t>((ack - tx_seq_ + 1U) & kSeqMask);  // 0, 1, 2
  if (advance == 0) return true;
  if (!tx_active_ || advance == 3 || !tx_shown_[advance - 1U]) return false;
  if (move_window(now, advance)) ev.message_sent = true;
  return true;
}

void Link::process_data(const AdminByte& a, std::span<const std::uint8_t> data, LinkEvents& ev) {
  // With a window of two the peer shows SEQs from last - 1 to last + 2 (docs/pcp.md): only
  // last + 1 is new; last and last - 1 are old frames seen again, last + 2 the second of a window
  // whose first we missed (the peer shows the first again).
  if (a.seq != next_seq(rx_last_)) {
    if (a.seq == next_seq(next_seq(rx_last_))) {
      ++stats_.frames_ahead;
    } else {
      ++stats_.frames_repeated;
    }
    return;
  }
  if (rx_complete_) {
    ++stats_.frames_refused;  // not acknowledged: the peer repeats it until we take it
    return;
  }
  rx_last_ = a.seq;
  if (a.type == FrameType::first ||
      (a.type == FrameType::last && !rx_in_message_ && data_size_ >= kMinPduSize)) {
    // FIRST opens a message; over 4 words a LAST outside one is a message of a single frame
    // (narrower frames cannot hold the 6-byte minimum: there it is an orphan).
    rx_size_ = 0;
    rx_expected_ = 0;
    rx_in_message_ = true;
  } else if (!rx_in_message_) {
    ++stats_.fragments_orphaned;
    return;
  }
  if (rx_size_ + data.size() > kRxLimit) {
    rx_in_message_ = false;
    ++stats_.messages_dropped;
    return;
  }
  std::copy(data.begin(), data.end(), rx_.begin() + static_cast<std::ptrdiff_t>(rx_size_));
  rx_size_ += data.size();
  if (rx_expected_ == 0 && rx_size_ >= 4) {
    const std::size_t pdu = 4U + 2U * make_word(rx_[2], rx_[3]);
    if (pdu < kMinPduSize || pdu > kMaxPduSize) {
      rx_in_message_ = false;
      ++stats_.messages_dropped;
      return;
    }
    rx_expected_ = pdu;
  }
  if (a.type == FrameType::last) {
    ev.message_received = finish_message();
  } else if (rx_expected_ != 0 && rx_size_ >= rx_expected_) {
    rx_in_message_ = false;  // the message is complete but its fragment does not say LAST
    ++stats_.messages_dropped;
  }
}

bool Link::finish_message() {
  rx_in_message_ = false;
  const bool length_ok =
      rx_expected_ != 0 && rx_size_ >= rx_expected_ && rx_size_ - rx_expected_ < data_size_;
  bool ok = length_ok;
  if (ok) {
    // The LAST fragment's padding (fewer than a frame's data bytes, so < 8) must be zeros.
    const std::size_t n = rx_size_ - rx_expected_;
    if constexpr (kWholeFrames) {
      // As one 8-byte load (rx_ holds kMaxMessageSize + 8 bytes), the bytes past it masked off.
      static_assert(kMaxFrameData < 8 && kRxLimit + 1 >= kMaxMessageSize + 8);
      std::uint64_t x = 0;
      std::memcpy(&x, rx_.data() + rx_expected_, sizeof x);
      ok = (x & ((std::uint64_t{1} << (8U * n)) - 1U)) == 0;
    } else {
      unsigned padding = 0;
      for (std::size_t i = 0; i < n; ++i) padding |= rx_[rx_expected_ + i];
      ok = padding == 0;
    }
  }
  if (!ok) {
    ++stats_.messages_dropped;
    rx_size_ = 0;
    rx_expected_ = 0;
    return false;
  }
  rx_complete_ = true;
  ++stats_.messages_received;
  return true;
}

void Link::transmit(Time now, std::span<Word> out) {
  // The shortcut: a ready link shows IDLE or a fragment (docs/pcp.md, "Go-back-N"), chosen as
  // transmit_general chooses, its words made straight from the PDU (transmit_ready). ABORT,
  // ABORT-ACK and a short output go the general way.
  if (state_ == LinkState::ready) {
    const auto words = static_cast<std::size_t>(cfg_.channel_words);  // 1, 2 or 4 (validate)
    if (out.size() >= words) {
      if (words == 4) return transmit_ready<4>(now, out);
      if (words == 2) return transmit_ready<2>(now, out);
      return transmit_ready<1>(now, out);
    }
  }
  transmit_general(now, out);
}

template <std::size_t N>
void Link::transmit_ready(Time now, std::span<Word> out) {
  unsigned admin =
      (static_cast<unsigned>(cfg_.direction) << 7U) | (static_cast<unsigned>(rx_last_) << 1U);
  if (!tx_active_) {
    admin |= kParityBit[admin >> 1U];  // IDLE: TYPE and SEQ 0, ACK the last accepted
    out[0] = make_word(static_cast<std::uint8_t>(admin), 0);
    for (std::size_t i = 1; i < N; ++i) out[i] = 0;
    return;
  }
  constexpr std::size_t kData = 2 * N - 1;
  const std::size_t size = tx_size_;
  const std::size_t base = tx_offset_;
  const std::size_t next = base + std::min(kData, size - base);
  const int shown_last = tx_last_shown_;
  const int pick = (tx_shown_[0] && next < size && shown_last == 0 && !tx_back_) ? 1 : 0;
  if (pick == 0 && shown_last == 1) tx_back_ = true;
  const std::size_t offset = pick == 0 ? base : next;
  // offset < size (the base of an unfinished message, or the fragment after it): the fragment
  // is the last when the rest fits the frame.
  const FrameType type = size - offset <= kData
                             ? FrameType::last
                             : (offset == 0 ? FrameType::first : FrameType::middle);
  const std::uint8_t seq = pick == 0 ? tx_seq_ : next_seq(tx_seq_);
  if (pick == 0 && !tx_shown_[0]) tx_since_ = now;
  tx_shown_[static_cast<std::size_t>(pick)] = true;
  tx_last_shown_ = pick;
  admin |= (static_cast<unsigned>(type) << 5U) | (static_cast<unsigned>(seq) << 3U);
  admin |= kParityBit[admin >> 1U];
  // The fragment's bytes, then the zeros after the PDU in tx_ as the LAST frame's padding.
  const std::uint8_t* d = tx_.data() + offset;
  if constexpr (N == 4 && kWholeFrames) {
    // The whole frame at once: the admin byte and the 7 bytes from offset (offset < tx_size_, so
    // the 8 bytes read lie in tx_; the 8th is shifted out).
    std::uint64_t x = 0;
    std::memcpy(&x, d, sizeof x);
    x = swap_word_bytes((x << 8U) | admin);
    std::memcpy(out.data(), &x, sizeof x);
  } else {
    out[0] = make_word(static_cast<std::uint8_t>(admin), d[0]);
    for (std::size_t i = 1; i < N; ++i) out[i] = make_word(d[2 * i - 1], d[2 * i]);
  }
}

[[gnu::noinline]] void Link::transmit_general(Time now, std::span<Word> out) {
  std::array<std::uint8_t, kMaxFrameBytes> b{};
  AdminByte a;
  a.dir = cfg_.direction;
  a.ack = rx_last_;
  switch (state_) {
    case LinkState::aborting:
      a.type = FrameType::control;
      a.seq = static_cast<std::uint8_t>(ControlCode::abort);
      a.ack = abort_number_;
      break;
    case LinkState::acking:
      a.type = FrameType::control;
      a.seq = static_cast<std::uint8_t>(ControlCode::abort_ack);
      a.ack = peer_abort_number_;
      break;
    case LinkState::ready:
      if (!tx_active_) {
        a.type = FrameType::control;
        a.seq = static_cast<std::uint8_t>(ControlCode::idle);
        break;
      }
      {
        // Go-back-N, window two: the base until it has been shown, then the fragment after it
        // (if the message has one); when neither is acknowledged then, the base again, and only
        // the base until its acknowledgement comes: whatever the peer's rate, it sees it.
        const std::size_t next = tx_offset_ + fragment_size(tx_offset_);
        const int pick = (tx_shown_[0] && next < tx_size_ && tx_last_shown_ == 0 && !tx_back_) ? 1 : 0;
        if (pick == 0 && tx_last_shown_ == 1) tx_back_ = true;
        const std::size_t offset = pick == 0 ? tx_offset_ : next;
        const std::size_t n = fragment_size(offset);
        a.type = offset + n == tx_size_ ? FrameType::last
                                         : (offset == 0 ? FrameType::first : FrameType::middle);
        a.seq = pick == 0 ? tx_seq_ : next_seq(tx_seq_);
        std::copy_n(tx_.begin() + static_cast<std::ptrdiff_t>(offset), n, b.begin() + 1);
        if (pick == 0 && !tx_shown_[0]) tx_since_ = now;
        tx_shown_[static_cast<std::size_t>(pick)] = true;
        tx_last_shown_ = pick;
      }
      break;
  }
  b[0] = encode_admin(a);
  const std::size_t words = std::min(out.size(), static_cast<std::size_t>(cfg_.channel_words));
  for (std::size_t i = 0; i < words; ++i) out[i] = make_word(b[2 * i], b[2 * i + 1]);
}

}  // namespace ibs::pcp
