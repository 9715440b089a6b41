// The master's DRIVECOM sequencer (drivecom::Sequencer, docs/drivecom.md "Master side") fed
// arbitrary status words, requests of every kind, restarts, application bits and time steps,
// with arbitrary transition timeouts and reset pulses.
//
// Asserts, for every control word it sends, what the sequencer monitor
// (tests/support/sequencer_monitor.hpp, written from the documented promises) checks: BLOCK
// POWER with bit 7 low after any failure (and a failure is reported whenever the drive faulted
// outside a covered reset or left the reached target), SHUTDOWN never skipped, no POWER-ON or
// ENABLE that was not asked for, no reset edge the request did not cover, stop requests obeyed
// at once, reserved bits 8-10 clear. Besides: the application's bits are in every word and
// nothing else of them; the report names the word sent; a timeout failure comes only after the
// awaited transition's timeout has run out, and none is overdue while the sequencer still waits.
//
// Input: a header of timeouts, reset pulse and application bits; then per cycle an event byte
// (request, stop requests, restart, new application bits, or none), a status word and a time step.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "ibs/drivecom/sequencer.hpp"
#include "ibs/drivecom/status_word.hpp"
#include "sequencer_monitor.hpp"

namespace {

using namespace ibs;
using namespace ibs::drivecom;
using ibs::fuzz::fail;
using ibs::fuzz::hex4;

constexpr Word kOwned = static_cast<Word>(cw::kDrivecomMask | cw::kReservedMask);

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ibs::fuzz::Input in(data, size);
  SequencerConfig cfg = SequencerConfig::defaults();
  const std::uint8_t mode = in.ConsumeIntegral<std::uint8_t>();
  if ((mode & 1U) != 0) {
    // Short, arbitrary timeouts (1..255 ms), so that timeouts happen inside short inputs.
    for (auto& t : cfg.transition_timeout) t = std::chrono::milliseconds(1 + in.ConsumeIntegral<std::uint8_t>());
  }
  if ((mode & 2U) != 0) cfg.reset_pulse = std::chrono::milliseconds(1 + in.ConsumeIntegral<std::uint8_t>() % 100);
  cfg.application_bits = in.ConsumeIntegral<std::uint16_t>();
  Word app = static_cast<Word>(cfg.application_bits & ~kOwned);

  Sequencer seq(cfg);
  test_support::Monitor mon;
  Time now{0};
  ibs::fuzz::Recent<> recent;  // the last cycles, for the message
  while (in.remaining_bytes() > 0) {
    const std::uint8_t event = in.ConsumeIntegral<std::uint8_t>();
    switch (event >> 4U) {
      case 0: case 1: case 2: {
        const auto t = static_cast<Target>(event & 3U);
        seq.request(t, now);
        mon.on_request(t);
        recent.note(t == Target::enabled ? "request(enabled)" : t == Target::on ? "request(on)" : t == Target::ready ? "request(ready)" : "request(start-up-inhibit)");
        break;
      }
      case 3:
        seq.request_emergency_stop(now);
        mon.on_emergency_stop();
        recent.note("estop");
        break;
      case 4:
        seq.request_block_power(now);
        mon.on_block_power();
        recent.note("block-power");
        break;
      case 5:
        seq.restart();
        mon.on_restart();
        recent.note("restart");
        break;
      case 6:
        app = static_cast<Word>(in.ConsumeIntegral<std::uint16_t>() & ~kOwned);
        seq.set_application_bits(app);
        break;
      default: break;  // most cycles: no event
    }
    const Word status = in.ConsumeIntegral<std::uint16_t>();
    const Word w = seq.step(status, now);
    const Report& r = seq.report();
    recent.words(status, w);
    const auto where = [&] {
      return "at " + std::to_string(now.count()) + " ns, status " + hex4(status) + " answered " + hex4(w) + " (" +
             describe(r) + "); cycles (status>control):" + recent.str();
    };

    const std::string why = mon.check(status, w, r);
    if (!why.empty()) fail(why + " " + where());
    if ((w & ~kOwned) != app) fail("application bits " + hex4(app) + " not in the word, " + where());
    if (r.command_sent != w) fail("the report says " + hex4(r.command_sent) + " was sent, " + where());
    if (r.phase == Phase::failed && r.failure == Failure::timeout && r.waited < r.timeout) {
      fail("a timeout after " + std::to_string(r.waited.count()) + " ns of " + std::to_string(r.timeout.count()) +
           " ns, " + where());
    }
    if (r.phase == Phase::moving && r.transition != 0 && r.timeout > Duration{0} && r.waited > r.timeout) {
      fail("still waiting for transition " + std::to_string(r.transition) + " past its timeout, " + where());
    }
    if (r.phase == Phase::failed && r.failure == Failure::none) fail("failed without a reason, " + where());

    // 0 .. 65.5 ms between cycles, in 1 us steps.
    now += std::chrono::microseconds(in.ConsumeIntegral<std::uint16_t>());
  }
  return 0;
}
