// The master's PCP client through a board's mailbox (pcp::MailboxClient, docs/pcp.md "Through a
// board's mailbox") fed whatever a board could hand it: arbitrary messages, confirmations built
// from the request it sent (of any result, length and invoke ID), Abort indications of any
// reason, Information Reports; submissions of every service at any time with their own timeouts,
// user aborts, time steps, messages sent or held back.
//
// Asserts:
// - a submission is refused only as documented: `busy` exactly while a request is outstanding,
//   `not_initiated` exactly for Read, Write or Get-OV without an association;
// - every message the client hands the board is whole: its count is the rest, the CR its own,
//   the code a request's or Abort's, the invoke ID the request's;
// - every accepted request gets exactly one result, for its service, its invoke ID and its
//   submission time; none comes without a request;
// - after a step at T + D or later, a request submitted at T with timeout D has ended; a
//   `timeout` result comes no earlier;
// - the association is there only after a positive Initiate and goes with every timeout,
//   protocol error and abort().
//
// Input: a header (CR, default timeout); then per step an action byte and its data.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/pcp/mailbox_client.hpp"

namespace {

using namespace ibs;
using namespace ibs::pcp;
using ibs::fuzz::fail;
using ibs::fuzz::hex4;

struct Outstanding {
  ServiceCode service = ServiceCode::read;
  Time submitted{0};
  Duration timeout{0};
  std::uint8_t invoke_id = 0;
  bool known = false;  // the invoke ID as the client sent it
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ibs::fuzz::Input in(data, size);
  MailboxConfig cfg;
  cfg.communication_reference = in.ConsumeIntegralInRange<std::uint8_t>(2, 255);
  cfg.request_timeout = std::chrono::milliseconds(in.ConsumeIntegralInRange<int>(1, 2000));
  MailboxClient c(cfg);
  Time now{0};
  std::optional<Outstanding> out;
  std::uint8_t last_sent_id = 0;
  bool board_ended = false;  // the result taken now comes from the board's Abort indication
  const auto check_outgoing = [&] {
    const std::span<const Word> m = c.outgoing();
    if (m.empty()) return;
    if (m.size() < 3 || m[1] != m.size() - 2) fail("outgoing message with a wrong count");
    if ((m[2] & 0xFFU) != cfg.communication_reference) fail("outgoing message for CR " + hex4(m[2]));
    const bool abort = m[0] == static_cast<Word>(ServiceCode::abort);
    if (!abort) {
      if (!out || m[0] != static_cast<Word>(out->service)) fail("a request nobody submitted: " + hex4(m[0]));
      out->invoke_id = static_cast<std::uint8_t>(m[2] >> 8U);
      out->known = true;
      last_sent_id = out->invoke_id;
    }
  };
  const auto take = [&] {
    const Result* r = c.take_result_view();
    if (r == nullptr) return;
    if (!out) fail("a result without a request");
    if (r->service != out->service) fail("a result for another service");
    if (r->submitted_at != out->submitted) fail("a result with another submission time");
    if (out->known && r->invoke_id != out->invoke_id) fail("a result with another invoke ID");
    // The board's timeout (an Abort indication) may come at any time; the client's own not early.
    if (r->kind == ResultKind::timeout && !board_ended && r->completed_at < out->submitted + out->timeout) {
      fail("a timeout before the request's time");
    }
    if (r->kind == ResultKind::ok && r->service == ServiceCode::initiate && !c.associated()) {
      fail("a positive Initiate without an association");
    }
    if ((r->kind == ResultKind::timeout || r->kind == ResultKind::protocol_error || r->kind == ResultKind::aborted) &&
        c.associated()) {
      fail("an association after a " + std::string(to_string(r->kind)));
    }
    out.reset();
  };
  while (in.remaining_bytes() > 0) {
    const std::uint8_t action = in.ConsumeIntegral<std::uint8_t>();
    switch (action % 8U) {
      case 0: {  // time passes, a step
        now += std::chrono::milliseconds(in.ConsumeIntegralInRange<int>(0, 300));
        c.step(now, {}, {});
        take();
        if (out && now >= out->submitted + out->timeout) fail("a request outlived its timeout");
        break;
      }
      case 1: {  // a submission
        const std::uint8_t what = in.ConsumeIntegral<std::uint8_t>();
        const Duration timeout = std::chrono::milliseconds(in.ConsumeIntegralInRange<int>(0, 1500));
        const ParameterRef ref = ParameterRef::object(in.ConsumeIntegral<std::uint16_t>());
        const bool busy = c.busy();
        const bool associated = c.associated();
        SubmitStatus s = SubmitStatus::invalid_argument;
        ServiceCode service = ServiceCode::initiate;
        switch (what % 5U) {
          case 0: s = c.initiate(now, timeout); break;
          case 1: service = ServiceCode::read; s = c.read(now, ref, timeout); break;
          case 2: service = ServiceCode::read; s = c.read(now, ref, DataType::usign16, timeout); break;
          case 3: service = ServiceCode::write; s = c.write(now, ref, Value{DataType::usign16, what}, timeout); break;
          default: service = ServiceCode::get_ov; s = c.get_ov(now, ref, timeout); break;
        }
        if (busy != (s == SubmitStatus::busy)) fail("busy is not exactly a request outstanding");
        const bool needs = service != ServiceCode::initiate;
        if (!busy && (needs && !associated) != (s == SubmitStatus::not_initiated)) fail("not_initiated misplaced");
        if (s == SubmitStatus::accepted) {
          out = Outstanding{service, now, timeout > Duration::zero() ? timeout : cfg.request_timeout, 0, false};
        }
        break;
      }
      case 2:  // the carrier sends what waits (or holds it back)
        check_outgoing();
        if (in.ConsumeBool()) c.sent();
        break;
      case 3: {  // a confirmation for the request, as the board could build it
        const std::uint16_t code = static_cast<std::uint16_t>((out ? static_cast<Word>(out->service) : 0x0081U) | 0x8000U);
        const std::uint8_t id = in.ConsumeBool() ? last_sent_id : in.ConsumeIntegral<std::uint8_t>();
        std::vector<Word> m{code, 0, static_cast<Word>((id << 8U) | cfg.communication_reference),
                            in.ConsumeBool() ? Word{0} : in.ConsumeIntegral<Word>()};
        const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(0, 16);
        for (std::size_t k = 0; k < n; ++k) m.push_back(in.ConsumeIntegral<Word>());
        m[1] = static_cast<Word>(m.size() - 2);
        c.receive(now, m);
        take();
        break;
      }
      case 4: {  // an Abort indication of any reason
        const std::vector<Word> m{mailbox::kAbortIndication, 2, cfg.communication_reference,
                                  in.ConsumeIntegralInRange<Word>(0, 7)};
        c.receive(now, m);
        board_ended = true;
        take();
        board_ended = false;
        if (c.associated()) fail("an association after the board's Abort indication");
        break;
      }
      case 5: {  // any words at all
        std::vector<Word> m(in.ConsumeIntegralInRange<std::size_t>(0, 40));
        for (Word& w : m) w = in.ConsumeIntegral<Word>();
        c.receive(now, m);
        take();
        break;
      }
      case 6:  // the user aborts
        c.abort(now);
        if (out) {
          const Result* r = c.take_result_view();
          if (r == nullptr || r->kind != ResultKind::aborted) fail("abort() did not end the request at once");
          out.reset();
        }
        if (c.associated()) fail("an association after abort()");
        break;
      default: {  // an Information Report
        std::vector<Word> m{mailbox::kInformationReportIndication, 0, cfg.communication_reference,
                            in.ConsumeIntegral<Word>(), in.ConsumeIntegralInRange<Word>(0, 8)};
        for (Word k = 0; k < (m[4] + 1U) / 2U; ++k) m.push_back(in.ConsumeIntegral<Word>());
        m[1] = static_cast<Word>(m.size() - 2);
        c.receive(now, m);
        take();
        static_cast<void>(c.take_information_report());
        break;
      }
    }
  }
  // At the end, with the board silent, every request ends by its timeout.
  now += std::chrono::seconds(3);
  c.step(now, {}, {});
  take();
  if (out) fail("a request that never ended");
  return 0;
}
