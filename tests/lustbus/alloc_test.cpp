// The byte path allocates nothing: receiver, answer decoder, host (submit, step, output,
// receive) and the fake responder, through whole transactions after construction.
#include <gtest/gtest.h>

#include "../support/counting_new.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/receiver.hpp"
#include "test_support.hpp"

namespace ibs::lustbus {
namespace {

// Runs one request host <-> receiver in memory, time passed in.
OutcomeKind exchange(Host& host, Receiver& rx, const Request& r, Time& now) {
  const auto id = host.submit(r).id;
  for (int guard = 0; guard < 10000; ++guard) {
    host.step(now);
    const auto out = host.take_output();
    for (const auto b : out) rx.receive(b, now);
    if (!out.empty()) host.output_done(now);
    for (const auto b : rx.take_answer(now)) host.receive(b, now);
    const Poll p = host.poll(id);
    if (p.state == RequestState::done) return p.outcome->kind;
    now += 1ms;
  }
  return OutcomeKind::aborted;
}

TEST(LustbusCyclePath, NoAllocationOnTheBytePath) {
  auto vf = test::make_vf1000(0ms);
  Receiver rx(vf, 1);
  Host host;
  Time now{0};
  const Request reqs[] = {enquiry(1, make_code(112)), select(1, make_code(105), make_value("03E8")),
                          select(1, make_code(105), make_value("FFFF")), enquiry(1, make_code(10122)),
                          enquiry(1, kSiofCode), broadcast(shared_code(83), make_value("0001"))};
  exchange(host, rx, reqs[0], now);  // warm-up
  ibs::test::AllocationCounter counter;
  for (int round = 0; round < 10; ++round) {
    for (const Request& r : reqs) {
      const auto k = exchange(host, rx, r, now);
      EXPECT_NE(k, OutcomeKind::aborted);
    }
  }
  EXPECT_EQ(counter.count(), 0);
}

}  // namespace
}  // namespace ibs::lustbus
