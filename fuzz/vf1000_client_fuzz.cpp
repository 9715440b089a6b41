// The master's side of the VF1000 communication-word channel (vf1000_channel::Client,
// docs/vf1000_channel.md "Master side") fed arbitrary inverter words, cycle by cycle, with
// requests of every kind submitted at any time, per-request timeouts and master restarts.
//
// Asserts:
// - every accepted request ends with exactly one documented Outcome, and within its timeout:
//   after any step, a request that became active at T with timeout D is done once now >= T + D;
//   at the end, with the inverter silent, every request is done;
// - a request moves queued -> active -> done, never back; outcomes are never lost (polled after
//   every step, the completed ring is at least as long as the queue);
// - each outcome fits its request and what the inverter showed: `value` only for a value
//   inquiry, `written` only for a value transfer and with its value, `description` only for a
//   description scan, each on a word with ACK; `nak` with a cause (siof / siof_unread for
//   transfers, no_parameter / control_bits for inquiries and scans) and only after a NAK word;
//   `inverter_restarted` only in a step whose word had RESET distinction 0; `aborted` only at a
//   restart; `timeout` only once the timeout has run out;
// - the master's word has no unused bits (4.1.2.1: always 0), a defined CODE, and is the starting
//   position 0000 whenever no telegram runs.
//
// Input: a header (timeout, resync hold, queue size); then per cycle an action byte (time step,
// submit or restart), for a submission its kind, number, value and timeout, and the inverter's word.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/vf1000_channel/client.hpp"
#include "ibs/vf1000_channel/comm_word.hpp"

namespace {

using namespace ibs;
using namespace ibs::vf1000_channel;
using ibs::fuzz::fail;
using ibs::fuzz::hex4;

struct Tracked {
  RequestId id = 0;
  Request request;
  Duration timeout{0};  // effective
  RequestState state = RequestState::queued;
  bool activated = false;
  Time active_since{0};
  bool saw_nak = false;  // a NAK word while it was active
};

std::string kind_name(OutcomeKind k) { return std::string(to_string(k)); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ibs::fuzz::Input in(data, size);
  ClientConfig cfg;
  cfg.timeout = std::chrono::milliseconds(1 + in.ConsumeIntegral<std::uint8_t>());
  cfg.resync_hold = std::chrono::milliseconds(in.ConsumeIntegral<std::uint8_t>());
  cfg.queue_capacity = 1 + in.ConsumeIntegral<std::uint8_t>() % 16;
  cfg.completed_capacity = cfg.queue_capacity;
  cfg.start_synchronised = in.ConsumeBool();
  Client client(cfg);

  std::vector<Tracked> requests;
  Time now{0};
  ibs::fuzz::Recent<> recent;

  // Checks every open request after a step (or a restart) with the inverter's word `in_word`.
  const auto check = [&](Word in_word, Word out, bool restarted) {
    const auto where = [&] {
      return "now " + std::to_string(now.count()) + " ns, inverter " + hex4(in_word) + " answered " + hex4(out) +
             "; cycles (inverter>master):" + recent.str();
    };
    if (!restarted) {
      if ((out & kMasterUnusedMask) != 0) fail("the master's word has unused bits set: " + where());
      if (master_code(out) > 3) fail("undefined CODE in the master's word: " + where());
      if (client.state() != ClientState::exchanging && out != kMasterIdleWord) {
        fail("no telegram runs (" + std::string(to_string(client.state())) + ") but the word is not 0000: " + where());
      }
      if (client.state() == ClientState::exchanging && master_code(out) == 0) fail("a telegram with CODE 0: " + where());
    }
    for (Tracked& t : requests) {
      if (t.state == RequestState::done) continue;
      const Poll p = client.poll(t.id);
      const auto who = [&] {
        return "request " + std::to_string(t.id) + " (" + std::string(to_string(t.request.kind)) + " " +
               std::to_string(t.request.number) + ")";
      };
      if (p.state == RequestState::unknown) fail(who() + " is unknown before it ended: " + where());
      if (p.state == RequestState::queued && t.state != RequestState::queued) fail(who() + " went back to the queue: " + where());
      if (p.state == RequestState::active) {
        if (!t.activated) {
          t.activated = true;
          t.active_since = now;
        }
        if (!restarted && inverter_ready(in_word) && inverter_nak(in_word)) t.saw_nak = true;
        if (now >= t.active_since + t.timeout) {
          fail(who() + " is still active " + std::to_string((now - t.active_since).count()) + " ns after it became active; its timeout is " +
               std::to_string(t.timeout.count()) + " ns: " + where());
        }
      }
      t.state = p.state;
      if (p.state != RequestState::done) continue;
      const Outcome& o = p.outcome;
      const auto what = [&] { return who() + " ended " + kind_name(o.kind) + " (" + describe(o) + "): "; };
      const bool ack_word = !restarted && inverter_ready(in_word) && inverter_ack(in_word);
      const bool nak_word = !restarted && inverter_ready(in_word) && inverter_nak(in_word);
      if (nak_word && t.activated) t.saw_nak = true;
      const RequestKind k = t.request.kind;
      switch (o.kind) {
        case OutcomeKind::value:
          if (k != RequestKind::value_inquiry || !ack_word) fail(what() + "not a value inquiry answered with ACK: " + where());
          break;
        case OutcomeKind::written:
          if (k != RequestKind::value_transfer || !ack_word) fail(what() + "not a value transfer answered with ACK: " + where());
          if (o.value != t.request.value) fail(what() + "written value " + hex4(o.value) + " is not the request's: " + where());
          break;
        case OutcomeKind::description:
          if (k != RequestKind::description_scan || !ack_word) fail(what() + "not a description scan answered with ACK: " + where());
          break;
        case OutcomeKind::nak: {
          const bool transfer = k == RequestKind::value_transfer;
          const bool ok_cause = transfer ? (o.nak_cause == NakCause::siof || o.nak_cause == NakCause::siof_unread)
                                         : (o.nak_cause == NakCause::no_parameter || o.nak_cause == NakCause::control_bits);
          if (!ok_cause) fail(what() + "a NAK cause that does not fit the request: " + where());
          if (!t.saw_nak) fail(what() + "no NAK word was seen while it was active: " + where());
          break;
        }
        case OutcomeKind::timeout:
          if (!t.activated || now < t.active_since + t.timeout) fail(what() + "a timeout before the timeout ran out: " + where());
          break;
        case OutcomeKind::inverter_restarted:
          if (restarted || inverter_ready(in_word)) fail(what() + "the inverter did not show RESET distinction 0: " + where());
          break;
        case OutcomeKind::aborted:
          if (!restarted) fail(what() + "aborted without a restart: " + where());
          break;
        case OutcomeKind::protocol_error:
          if (restarted) fail(what() + "a protocol error at a restart: " + where());
          break;
        default:
          fail(what() + "an undocumented outcome kind " + std::to_string(static_cast<int>(o.kind)) + ": " + where());
      }
      if (o.kind != OutcomeKind::nak && o.nak_cause != NakCause::none) fail(what() + "a NAK cause without NAK: " + where());
    }
  };

  Word last_out = Client::initial_word();
  while (in.remaining_bytes() > 0) {
    const std::uint8_t op = in.ConsumeIntegral<std::uint8_t>();
    switch (op & 3U) {
      case 0: now += 1ms; break;
      case 1: now += 8200us; break;
      case 2: now += 40ms; break;
      default: break;
    }
    switch ((op >> 2U) & 7U) {
      case 4:
      case 5: {
        Request r;
        r.kind = static_cast<RequestKind>(in.ConsumeIntegral<std::uint8_t>() % 3);
        r.number = in.ConsumeIntegral<std::uint16_t>() & 0x7FFU;  // beyond 3FFH sometimes
        r.value = in.ConsumeIntegral<std::uint16_t>();
        const std::uint8_t t = in.ConsumeIntegral<std::uint8_t>();
        r.timeout = t < 128 ? Duration{0} : std::chrono::milliseconds(t - 127);
        const Submitted s = client.submit(r);
        if (r.number > kMaxParameterNumber) {
          if (s.error != SubmitError::invalid_number) fail("parameter number " + std::to_string(r.number) + " accepted");
          break;
        }
        if (!s) {
          // Refused only when the queue (the active request included) is full.
          std::size_t open = 0;
          for (const Tracked& q : requests) open += q.state != RequestState::done ? 1U : 0U;
          if (s.error != SubmitError::queue_full || open != cfg.queue_capacity) {
            fail("a request refused (" + std::string(to_string(s.error)) + ") with " + std::to_string(open) + " of " +
                 std::to_string(cfg.queue_capacity) + " places taken");
          }
          break;
        }
        requests.push_back({s.id, r, r.timeout > Duration{0} ? r.timeout : cfg.timeout});
        recent.note("submit");
        break;
      }
      case 6:
        client.restart(now);
        recent.note("restart");
        check(0, 0, true);
        break;
      default: break;
    }
    const Word w = in.ConsumeIntegral<std::uint16_t>();
    last_out = client.step(w, now);
    recent.words(w, last_out);
    check(w, last_out, false);
  }
  // The inverter goes silent (wait mode): every request must end within its timeout.
  for (int i = 0; i < 20000; ++i) {
    now += 10ms;
    last_out = client.step(kInverterWaitWord, now);
    check(kInverterWaitWord, last_out, false);
    bool open = false;
    for (const Tracked& t : requests) open = open || t.state != RequestState::done;
    if (!open) break;
  }
  for (const Tracked& t : requests) {
    if (t.state != RequestState::done) fail("request " + std::to_string(t.id) + " never ended");
  }
  return 0;
}
