// The wings' LUSTBUS devices allocate nothing on the byte path: whole transactions with the host
// in memory after construction -- values, refusals and 85, descriptions, EEPROM timing, PROG, the
// MC6000's download with its dataset copy, the watchdog.
#include <gtest/gtest.h>

#include "../support/counting_new.hpp"
#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/mc6000/lustbus_face.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/receiver.hpp"

namespace ibs::lustbus {
namespace {

using namespace std::chrono_literals;

OutcomeKind exchange(Host& host, Receiver& rx, const Request& r, Time& now) {
  const auto id = host.submit(r).id;
  for (int guard = 0; guard < 100000; ++guard) {
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

Request slow(Request r) {
  r.response_timeout = 10s;
  return r;
}

TEST(LustbusWingsBytePath, NoAllocation) {
  devices::vf1000::LustbusDevice vf;
  devices::mc6000::LustbusDevice mc;
  Receiver rx_vf(vf, 1);
  Receiver rx_mc(mc, 3);
  Host host;
  Time now{0};
  const Request vf_reqs[] = {
      enquiry(1, kSiofCode),  select(1, make_code(105), make_value("03E8")),
      select(1, make_code(104), make_value("00FF")),  enquiry(1, make_code(10145)),
      select(1, make_code(101), make_value("0000")),  select(1, make_code(101), make_value("0004")),
      slow(select(1, make_code(171), make_value("0001"))), enquiry(1, make_code(112)),
      select(1, make_code(111), make_value("000F"))};
  const Assignment records[] = {{make_code(20417), make_value("3")},
                                {make_code(20419), make_value("9")}};
  const Request mc_reqs[] = {enquiry(3, kSiofCode),
                             select(3, make_code(20428), make_value("842666")),
                             select(3, make_code(20081), make_value("4B00")),
                             select(3, make_code(20084), make_value("0")),
                             enquiry(3, make_code(30428)),
                             enquiry(3, make_code(20077)),
                             slow(select(3, make_code(20004), make_value("1"))),
                             download(*devices::mc6000::lustbus_procedures().download, 3, records)};
  exchange(host, rx_vf, vf_reqs[0], now);  // warm-up
  exchange(host, rx_mc, mc_reqs[0], now);
  ibs::test::AllocationCounter counter;
  for (int round = 0; round < 3; ++round) {
    for (const Request& r : vf_reqs) EXPECT_NE(exchange(host, rx_vf, r, now), OutcomeKind::aborted);
    for (const Request& r : mc_reqs) EXPECT_NE(exchange(host, rx_mc, r, now), OutcomeKind::aborted);
    vf.advance(now + 1s);
    mc.advance(now + 1s);
  }
  EXPECT_EQ(counter.count(), 0);
}

}  // namespace
}  // namespace ibs::lustbus
