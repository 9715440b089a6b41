// The host against the wings' LUSTBUS devices over a pseudo-terminal in process: serial::serve on
// the master side, the host's loop serial::transact (transports/serial/lustbus_host.hpp) on the
// slave, real time.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/lustbus/served_receiver.hpp"
#include "ibs/serial/lustbus_host.hpp"
#include "ibs/serial/pty.hpp"
#include "ibs/serial/serve.hpp"

namespace ibs::cli {
namespace {

namespace lb = ::ibs::lustbus;

struct PtyBus {
  devices::vf1000::LustbusDevice vf;
  devices::mc6000::LustbusDevice mc;
  lb::Receiver rx_vf{vf, 1};
  lb::Receiver rx_mc{mc, 3};
  serial::PtyPair pair = serial::PtyPair::open({9600, serial::k7E1, false});
  lb::ServedReceiver served_vf{&rx_vf, [this](Time t) { vf.advance(t); }, [this] { return vf.line_baud(); }};
  lb::ServedReceiver served_mc{&rx_mc, [this](Time t) { mc.advance(t); }, [this] { return mc.line_baud(); }};
  std::vector<base::LineDevice*> served{&served_vf, &served_mc};
  std::atomic<bool> stop{false};
  std::thread server{[this] { serial::serve(pair.master(), served, [this] { return stop.load(); }); }};
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
  auto o = serial::transact(bus.host_port, host,
                            lb::select(1, lb::make_code(105), lb::make_value("03E8")));
  EXPECT_EQ(o.kind, lb::OutcomeKind::acknowledged) << lb::describe(o);
  EXPECT_EQ(bus.vf.value(5), 0x03E8);
  o = serial::transact(bus.host_port, host, lb::enquiry(3, lb::make_code(20091)));
  ASSERT_EQ(o.kind, lb::OutcomeKind::value);
  EXPECT_EQ(o.value.view(), "1770");
  serial::transact(bus.host_port, host, lb::enquiry(3, lb::make_code(85)));
  o = serial::transact(bus.host_port, host,
                       lb::select(3, lb::make_code(20417), lb::make_value("9")));
  EXPECT_EQ(o.kind, lb::OutcomeKind::nak);
  EXPECT_EQ(o.siof, 0x80);
  o = serial::transact(bus.host_port, host, lb::network_scan());
  ASSERT_EQ(o.kind, lb::OutcomeKind::scan);
  EXPECT_EQ(o.scan.count, 2);
}

// 11.5: 81-SBAUD takes effect at the next start — or at once with 4-PROG = 111. On a bus of two
// the servo then runs at another rate than the line: it hears nothing the host sends at 9600,
// the inverter still does.
TEST(LustbusPty, BaudRateChangeOnlineOf115) {
  PtyBus bus;
  lb::HostConfig cfg;
  cfg.response_timeout = std::chrono::milliseconds(1000);
  lb::Host host(cfg);
  serial::transact(bus.host_port, host, lb::enquiry(3, lb::make_code(85)));
  auto o = serial::transact(bus.host_port, host, lb::select(3, lb::make_code(20081), lb::make_value("4B00")));
  ASSERT_EQ(o.kind, lb::OutcomeKind::acknowledged) << lb::describe(o);  // 19200, not yet active
  EXPECT_EQ(bus.mc.line_baud(), 9600U);
  o = serial::transact(bus.host_port, host, lb::enquiry(3, lb::make_code(20091)));
  EXPECT_EQ(o.kind, lb::OutcomeKind::value);
  o = serial::transact(bus.host_port, host, lb::select(3, lb::make_code(20004), lb::make_value("6F")));
  ASSERT_EQ(o.kind, lb::OutcomeKind::acknowledged) << lb::describe(o);  // 111: the ACK at 9600
  EXPECT_EQ(bus.mc.line_baud(), 19200U);
  cfg.response_timeout = std::chrono::milliseconds(150);
  lb::Host quick(cfg);
  o = serial::transact(bus.host_port, quick, lb::enquiry(3, lb::make_code(20091)));
  EXPECT_EQ(o.kind, lb::OutcomeKind::no_answer);
  o = serial::transact(bus.host_port, quick, lb::enquiry(1, lb::make_code(91)));
  EXPECT_EQ(o.kind, lb::OutcomeKind::value);
}

// 11.5 with a lone servo: the emulator's port follows the servo's new rate once the ACK is out.
TEST(LustbusPty, LoneServoTakesThePortAlong) {
  devices::mc6000::LustbusDevice mc;
  lb::Receiver rx{mc, 3};
  serial::PtyPair pair = serial::PtyPair::open({9600, serial::k7E1, false});
  lb::ServedReceiver served_mc{&rx, [&mc](Time t) { mc.advance(t); }, [&mc] { return mc.line_baud(); }};
  std::vector<base::LineDevice*> served{&served_mc};
  std::atomic<bool> stop{false};
  std::thread server{[&] { serial::serve(pair.master(), served, [&] { return stop.load(); }); }};
  serial::SerialPort port = serial::SerialPort::open(pair.slave_path(), {9600, serial::k7E1, false});
  lb::HostConfig cfg;
  cfg.response_timeout = std::chrono::milliseconds(1000);
  lb::Host host(cfg);
  serial::transact(port, host, lb::enquiry(3, lb::make_code(85)));
  serial::transact(port, host, lb::select(3, lb::make_code(20081), lb::make_value("9600")));  // 38400
  const auto o = serial::transact(port, host, lb::select(3, lb::make_code(20004), lb::make_value("6F")));
  EXPECT_EQ(o.kind, lb::OutcomeKind::acknowledged) << lb::describe(o);
  port.set_baud(38400);  // the host follows (a pty carries the bytes whatever the rate)
  EXPECT_EQ(serial::transact(port, host, lb::enquiry(3, lb::make_code(20081))).value.view(), "9600");
  stop = true;
  server.join();
  EXPECT_EQ(pair.master().baud(), 38400U);
}

}  // namespace
}  // namespace ibs::cli
