// The host against the wings' LUSTBUS devices over a pseudo-terminal in process: serve_lustbus on
// the master side, transact_lustbus on the slave, real time.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/serial/pty.hpp"
#include "lustbus_cmd.hpp"

namespace ibs::cli {
namespace {

namespace lb = ::ibs::lustbus;

struct PtyBus {
  devices::vf1000::LustbusDevice vf;
  devices::mc6000::LustbusDevice mc;
  lb::Receiver rx_vf{vf, 1};
  lb::Receiver rx_mc{mc, 3};
  serial::PtyPair pair = serial::PtyPair::open({9600, serial::k7E1, false});
  std::vector<LustbusServed> served{{&rx_vf, [this](Time t) { vf.advance(t); }},
                                    {&rx_mc, [this](Time t) { mc.advance(t); }}};
  std::atomic<bool> stop{false};
  std::thread server{[this] { serve_lustbus(pair.master(), served, [this] { return stop.load(); }); }};
  serial::SerialPort host_port =
      serial::SerialPort::open(pair.slave_path(), {9600, serial::k7E1, false});
  ~PtyBus() {
    stop = true;
    server.join();
  }
};

TEST(LustbusPty, ReadWriteAndNakThroughTheHost) {
  PtyBus bus;
  lb::HostConfig cfg;
  cfg.response_timeout = std::chrono::milliseconds(1000);
  lb::Host host(cfg);
  // 6.2.2 over the pty: the power-on bit makes the first SELECT a NAK, the host reads 85 and
  // repeats it (9.2).
  auto o = transact_lustbus(bus.host_port, host,
                            lb::select(1, lb::make_code(105), lb::make_value("03E8")));
  EXPECT_EQ(o.kind, lb::OutcomeKind::acknowledged) << lb::describe(o);
  EXPECT_EQ(bus.vf.value(5), 0x03E8);
  o = transact_lustbus(bus.host_port, host, lb::enquiry(3, lb::make_code(20091)));
  ASSERT_EQ(o.kind, lb::OutcomeKind::value);
  EXPECT_EQ(o.value.view(), "1770");
  transact_lustbus(bus.host_port, host, lb::enquiry(3, lb::make_code(85)));
  o = transact_lustbus(bus.host_port, host,
                       lb::select(3, lb::make_code(20417), lb::make_value("9")));
  EXPECT_EQ(o.kind, lb::OutcomeKind::nak);
  EXPECT_EQ(o.siof, 0x80);
  o = transact_lustbus(bus.host_port, host, lb::network_scan());
  ASSERT_EQ(o.kind, lb::OutcomeKind::scan);
  EXPECT_EQ(o.scan.count, 2);
}

}  // namespace
}  // namespace ibs::cli
