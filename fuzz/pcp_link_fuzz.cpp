// The PCP channel's segmentation and reassembly (pcp::Link, docs/pcp.md "Segmentation"), two ways:
//
// Mode 0, one link fed arbitrary channel words cycle by cycle (with sends, aborts, late message
// releases and time steps). Asserts:
// - a delivered message is 6..134 bytes, its count word says its size, and it is one that the
//   loose model of docs/pcp.md (fuzz/support/pcp_model.hpp) could have assembled from the frames
//   seen -- a complete message of the length its count word gives, completed by this very frame;
// - the link's own frame always has odd parity and its own direction, shows ABORT while aborting
//   and ABORT-ACK while acking, and a control frame carries only zero data bytes;
// - send() takes exactly the PDUs it documents (6..134 bytes, count word matching, link ready
//   and idle), and the statistics never go down.
//
// In both modes every link has a shadow of the same configuration that gets the same calls but
// through receive_general and transmit_general: events, counters, state, messages and the words
// shown must be the same (the shortcut of receive/transmit, LinkShortcuts.* in the tests).
//
// Mode 1, a master link and a servo link joined by a faulty bus that delivers, each way and each
// cycle, the sender's current frame or an older one, never a newer one and never one older than
// what it delivered before (lost and repeated cycles, docs/pcp.md "Why the faults cannot make a
// wrong or duplicated message"), with arbitrary PDUs sent both ways, restarts and late releases.
// Asserts: every delivered message is, byte for byte, a message its peer sent (each carries its
// number), delivered at most once and in the order sent; a sender learns its message was sent
// only after the receiver delivered it.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/pcp/link.hpp"
#include "ibs/pcp/pdu.hpp"
#include "pcp_model.hpp"

namespace {

using namespace ibs;
using namespace ibs::pcp;
using ibs::fuzz::Bytes;
using ibs::fuzz::fail;
using ibs::fuzz::hex4;

using Frame = std::array<Word, kMaxChannelWords>;

int width(std::uint8_t b) {
  static constexpr int kWidths[] = {1, 2, 4};
  return kWidths[(b & 3U) % 3U];  // bits 0-1; the other bits are flags
}

std::string hex(const Bytes& b) {
  std::string s;
  for (const std::uint8_t x : b) {
    char t[4];
    std::snprintf(t, sizeof t, "%02X", x);
    s += t;
  }
  return s;
}

// An arbitrary PDU whose count word fits its size (so that the link takes it).
Bytes make_pdu(ibs::fuzz::Input& in) {
  const std::size_t count = 1 + in.ConsumeIntegralInRange<std::size_t>(0, 64);
  Bytes b = in.ConsumeBytes<std::uint8_t>(4 + 2 * count);
  b.resize(4 + 2 * count, 0);
  b[2] = static_cast<std::uint8_t>(count >> 8U);
  b[3] = static_cast<std::uint8_t>(count & 0xFFU);
  return b;
}

// The message with its number in bytes 4-5 (InvokeID, CR), so that every message sent is unique
// and a delivery names exactly one of them.
Bytes unique(Bytes b, std::size_t number) {
  b[4] = static_cast<std::uint8_t>(number >> 8U);
  b[5] = static_cast<std::uint8_t>(number & 0xFFU);
  return b;
}

template <typename Where>
void check_own_frame(const Link& l, const Frame& f, const Where& where) {
  const auto admin = static_cast<std::uint8_t>(f[0] >> 8U);
  const auto a = decode_admin(admin);
  if (!a) fail("the link's own frame has a bad administrative byte " + hex4(f[0]) + ": " + where());
  if (a->dir != l.config().direction) fail("the link's frame has the wrong direction: " + where());
  if (l.state() == LinkState::aborting &&
      (a->type != FrameType::control || a->seq != static_cast<std::uint8_t>(ControlCode::abort))) {
    fail("aborting but not showing ABORT: " + where());
  }
  if (l.state() == LinkState::acking &&
      (a->type != FrameType::control || a->seq != static_cast<std::uint8_t>(ControlCode::abort_ack))) {
    fail("acking but not showing ABORT-ACK: " + where());
  }
  if (a->type == FrameType::control) {
    if ((f[0] & 0xFFU) != 0) fail("a control frame with data: " + where());
    for (int i = 1; i < l.config().channel_words; ++i) {
      if (f[static_cast<std::size_t>(i)] != 0) fail("a control frame with data: " + where());
    }
  }
}

// The link and its shadow (receive_general, transmit_general) agree in everything visible.
template <typename Where>
void check_shadow(const Link& l, const Link& shadow, const Where& where) {
  if (l.state() != shadow.state()) fail("the general path's state differs: " + where());
  if (!(l.stats() == shadow.stats())) fail("the general path's counters differ: " + where());
  if (l.sending() != shadow.sending() || l.can_send() != shadow.can_send()) {
    fail("the general path's sending differs: " + where());
  }
  const auto a = l.message();
  const auto b = shadow.message();
  if (l.has_message() != shadow.has_message() || !std::equal(a.begin(), a.end(), b.begin(), b.end())) {
    fail("the general path's message differs: " + where());
  }
}

bool stats_monotonic(const LinkStats& a, const LinkStats& b) {
  return b.frames_invalid >= a.frames_invalid && b.frames_repeated >= a.frames_repeated &&
         b.frames_ahead >= a.frames_ahead &&
         b.frames_refused >= a.frames_refused && b.fragments_orphaned >= a.fragments_orphaned &&
         b.messages_sent >= a.messages_sent && b.messages_received >= a.messages_received &&
         b.messages_dropped >= a.messages_dropped && b.sequence_errors >= a.sequence_errors &&
         b.ack_timeouts >= a.ack_timeouts && b.aborts_local >= a.aborts_local && b.aborts_peer >= a.aborts_peer;
}

void run_single(ibs::fuzz::Input& in) {
  LinkConfig cfg;
  const std::uint8_t h = in.ConsumeIntegral<std::uint8_t>();
  cfg.channel_words = width(h);
  cfg.direction = (h & 0x10U) != 0 ? Direction::to_client : Direction::to_server;
  cfg.start_ready = (h & 0x20U) != 0;
  cfg.ack_timeout = std::chrono::milliseconds(1 + in.ConsumeIntegral<std::uint8_t>());
  Link link(cfg);
  Link shadow(cfg);
  const auto words = static_cast<std::size_t>(cfg.channel_words);
  fuzz::PlausibleMessages model(cfg.channel_words, cfg.direction == Direction::to_client);
  Time now{0};
  ibs::fuzz::Recent<> recent;
  while (in.remaining_bytes() > 0) {
    const std::uint8_t op = in.ConsumeIntegral<std::uint8_t>();
    now += std::chrono::microseconds(500 * (op & 7U));
    if ((op & 0x08U) != 0) {
      const bool could = link.can_send();
      Bytes pdu = (op & 0x40U) != 0 ? make_pdu(in) : in.ConsumeBytes<std::uint8_t>(in.ConsumeIntegral<std::uint8_t>());
      const bool fits = pdu.size() >= kMinPduSize && pdu.size() <= kMaxPduSize &&
                        pdu.size() == 4U + 2U * ((static_cast<std::size_t>(pdu[2]) << 8U) | pdu[3]);
      const bool sent = link.send(pdu);
      if (shadow.send(pdu) != sent) fail("send() differs on the general path");
      if (sent != (could && fits)) {
        fail("send() of " + std::to_string(pdu.size()) + " bytes " + hex(pdu) + " returned " + std::to_string(sent) +
             " (ready and idle " + std::to_string(could) + ", fits " + std::to_string(fits) + ")");
      }
    }
    if ((op & 0x80U) != 0 && (op & 0x30U) == 0x30U) {
      link.abort();
      shadow.abort();
    }
    Frame f{};
    for (std::size_t i = 0; i < words; ++i) f[i] = in.ConsumeIntegral<std::uint16_t>();
    const LinkStats before = link.stats();
    const bool had_message = link.has_message();
    const std::vector<Bytes> plausible = model.feed(std::span<const Word>(f.data(), words));
    const LinkEvents ev = link.receive(now, std::span<const Word>(f.data(), words));
    const auto where = [&] { return "frames (first word in>out):" + recent.str(); };
    if (!(shadow.receive_general(now, std::span<const Word>(f.data(), words)) == ev)) {
      fail("receive_general's events differ: " + where());
    }
    check_shadow(link, shadow, where);
    if (!stats_monotonic(before, link.stats())) fail("a statistic went down: " + where());
    if (ev.message_received) {
      if (!link.has_message()) fail("message_received without a message: " + where());
      if (had_message) fail("a new message while the last one was not released: " + where());
      const auto msg = link.message();
      const Bytes m(msg.begin(), msg.end());
      if (m.size() < kMinPduSize || m.size() > kMaxPduSize) fail("a message of " + std::to_string(m.size()) + " bytes: " + where());
      if (m.size() != 4U + 2U * ((static_cast<std::size_t>(m[2]) << 8U) | m[3])) {
        fail("a message whose count word does not give its size: " + hex(m) + ": " + where());
      }
      if (!model.overflowed() && std::find(plausible.begin(), plausible.end(), m) == plausible.end()) {
        fail("delivered " + hex(m) + ", which no complete, checked message of the frames seen could give: " + where());
      }
    }
    // The user takes the message now, or later (flow control).
    if (link.has_message() && (op & 0x30U) != 0x10U) {
      link.release_message();
      shadow.release_message();
    }
    Frame out{};
    link.transmit(now, std::span<Word>(out.data(), words));
    Frame shadow_out{};
    shadow.transmit_general(now, std::span<Word>(shadow_out.data(), words));
    recent.words(f[0], out[0]);
    if (out != shadow_out) fail("transmit_general shows other words: " + where());
    check_shadow(link, shadow, where);
    check_own_frame(link, out, where);
  }
}

// One direction of the faulty bus: the sender's frames and which one the receiver saw last.
struct Wire {
  std::vector<Frame> frames;
  std::size_t seen = 0;
  // Picks the frame delivered this cycle: 0 the newest, 1 the one delivered before, else between.
  const Frame& deliver(std::uint8_t how, std::uint8_t where) {
    const std::size_t newest = frames.size() - 1;
    if (how == 0) seen = newest;
    else if (how >= 2) seen += where % (newest - seen + 1);
    return frames[seen];
  }
};

// What one side sent, and what of it the peer delivered.
struct Sent {
  std::vector<Bytes> messages;    // in the order send() took them
  std::size_t delivered = 0;      // messages[0 .. delivered) may no longer be delivered
  std::vector<bool> was_delivered;
};

void run_pair(ibs::fuzz::Input& in) {
  const std::uint8_t h = in.ConsumeIntegral<std::uint8_t>();
  const int words = width(h);
  const auto ack_timeout = std::chrono::milliseconds(20 + in.ConsumeIntegral<std::uint8_t>());
  Link master(LinkConfig{words, Direction::to_server, ack_timeout, (h & 0x10U) != 0});
  Link servo(LinkConfig{words, Direction::to_client, ack_timeout, (h & 0x10U) != 0});
  Link master_shadow(master.config());
  Link servo_shadow(servo.config());
  const auto n = static_cast<std::size_t>(words);
  // The shadow shows the same words as its link (transmit_general against transmit).
  const auto show = [&](Link& l, Link& shadow, Time t, Frame& out) {
    l.transmit(t, std::span<Word>(out.data(), n));
    Frame g{};
    shadow.transmit_general(t, std::span<Word>(g.data(), n));
    if (g != out) fail("transmit_general shows other words than transmit");
    check_shadow(l, shadow, [] { return std::string("after transmit"); });
  };
  const auto take = [&](Link& l, Link& shadow, Time t, const Frame& frame) {
    const LinkEvents ev = l.receive(t, std::span<const Word>(frame.data(), n));
    if (!(shadow.receive_general(t, std::span<const Word>(frame.data(), n)) == ev)) {
      fail("receive_general's events differ from receive's");
    }
    check_shadow(l, shadow, [] { return std::string("after receive"); });
    return ev;
  };
  Wire to_servo;
  Wire to_master;
  Sent from_master;
  Sent from_servo;
  Time now{0};
  Frame f{};
  show(master, master_shadow, now, f);
  to_servo.frames.push_back(f);
  show(servo, servo_shadow, now, f);
  to_master.frames.push_back(f);

  const auto on_delivery = [&](Link& receiver, Sent& sent, const std::string& who) {
    const auto msg = receiver.message();
    const Bytes m(msg.begin(), msg.end());
    for (std::size_t i = sent.delivered; i < sent.messages.size(); ++i) {
      if (sent.messages[i] == m) {
        sent.delivered = i + 1;
        sent.was_delivered[i] = true;
        return;
      }
    }
    fail(who + " delivered " + hex(m) + ", which is not a message its peer sent after the last one delivered (" +
         std::to_string(sent.delivered) + " of " + std::to_string(sent.messages.size()) + " delivered)");
  };
  const auto on_sent = [&](const Sent& sent, const std::string& who) {
    if (sent.messages.empty() || !sent.was_delivered.back()) {
      fail(who + " was told its message was sent, but its peer has not delivered it");
    }
  };

  std::size_t cycles = 0;
  while (in.remaining_bytes() > 0 && ++cycles < 20000) {
    const std::uint8_t op = in.ConsumeIntegral<std::uint8_t>();
    const std::uint8_t where = in.ConsumeIntegral<std::uint8_t>();
    now += std::chrono::microseconds(250 + 250 * ((op >> 6U) & 3U));
    // Receive what the bus delivers, then send this cycle's frames.
    const LinkEvents es = take(servo, servo_shadow, now, to_servo.deliver(op & 3U, where));
    if (es.message_received) on_delivery(servo, from_master, "the servo");
    if (es.message_sent) on_sent(from_servo, "the servo");
    const LinkEvents em = take(master, master_shadow, now, to_master.deliver((op >> 2U) & 3U, where));
    if (em.message_received) on_delivery(master, from_servo, "the master");
    if (em.message_sent) on_sent(from_master, "the master");

    const std::uint8_t act = in.ConsumeIntegral<std::uint8_t>();
    if ((act & 0x01U) != 0 && master.can_send()) {
      const Bytes p = unique(make_pdu(in), from_master.messages.size());
      const bool sent = master.send(p);
      if (master_shadow.send(p) != sent) fail("send() differs on the general path");
      if (sent) {
        from_master.messages.push_back(p);
        from_master.was_delivered.push_back(false);
      }
    }
    if ((act & 0x02U) != 0 && servo.can_send()) {
      const Bytes p = unique(make_pdu(in), from_servo.messages.size());
      const bool sent = servo.send(p);
      if (servo_shadow.send(p) != sent) fail("send() differs on the general path");
      if (sent) {
        from_servo.messages.push_back(p);
        from_servo.was_delivered.push_back(false);
      }
    }
    if ((act & 0x0CU) == 0x0CU) {
      master.abort();
      master_shadow.abort();
    }
    if ((act & 0x30U) == 0x30U) {
      servo.abort();
      servo_shadow.abort();
    }
    // Messages are taken at once, or a few cycles late (flow control).
    if (servo.has_message() && (act & 0x40U) == 0) {
      servo.release_message();
      servo_shadow.release_message();
    }
    if (master.has_message() && (act & 0x80U) == 0) {
      master.release_message();
      master_shadow.release_message();
    }

    show(master, master_shadow, now, f);
    to_servo.frames.push_back(f);
    show(servo, servo_shadow, now, f);
    to_master.frames.push_back(f);
    if (std::getenv("IBS_FUZZ_TRACE") != nullptr) {
      std::fprintf(stderr, "t=%lld servo saw #%zu %s, master saw #%zu %s | master shows %s (%s) servo shows %s (%s) | es r%d s%d rx%d em r%d s%d rx%d | sent m%zu s%zu\n",
                   static_cast<long long>(now.count()), to_servo.seen, hex4(to_servo.frames[to_servo.seen][0]).c_str(),
                   to_master.seen, hex4(to_master.frames[to_master.seen][0]).c_str(), hex4(to_servo.frames.back()[0]).c_str(),
                   std::string(to_string(master.state())).c_str(), hex4(to_master.frames.back()[0]).c_str(),
                   std::string(to_string(servo.state())).c_str(), es.reset, es.message_sent, es.message_received, em.reset,
                   em.message_sent, em.message_received, from_master.messages.size(), from_servo.messages.size());
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ibs::fuzz::Input in(data, size);
  if (in.ConsumeBool()) {
    run_pair(in);
  } else {
    run_single(in);
  }
  return 0;
}
