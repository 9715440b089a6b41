// The test bench (docs/testbench.md): a scenario's drives served on a LUSTBUS pseudo-terminal while
// the simulator runs them on INTERBUS in real time. A host on the pty's other end (the project's
// own lustbus::Host over serial::transact, as `ibs lustbus read` uses it) and the scenario's
// INTERBUS master reach one drive core: what one bus writes the other reads, the speed the master
// commands is what 77-SPEED reads, a fault injected on the timeline shows in the status word both
// buses read, and the power-on bit is the drive's (LB-D1).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <sstream>
#include <thread>

#include "ibs/devices/dfs1/controller.hpp"
#include "ibs/dfs1/host.hpp"
#include "ibs/lustbus/host.hpp"
#include "bench.hpp"
#include "ibs/sim/realtime.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"
#include "ibs/serial/dfs1_host.hpp"
#include "ibs/serial/lustbus_host.hpp"
#include "ibs/serial/serial_port.hpp"
#include "ibs/serial/capture.hpp"

namespace ibs::sim {
namespace {

using cli::Bench;
using cli::BenchReport;

namespace lb = ::ibs::lustbus;
using Clock = std::chrono::steady_clock;

constexpr const char* kScenario = R"(
name = "bench"
duration = "4 s"

[[device]]
name = "servo"
type = "mc6000"
supi = 11
ibcnf = 2
lustbus = 1

[lustbus]
pty = true

[[timeline]]
at = "0 s"
device = "servo"
read = 85

[[timeline]]
at = "0 s"
device = "servo"
state = "enabled"

[[timeline]]
at = "0 s"
device = "servo"
speed = 1500

[[timeline]]
at = "200 ms"
device = "servo"
write = { parameter = 83, value = 1234 }

[[timeline]]
at = "2 s"
device = "servo"
fault = "device"
duration = "1 s"

[[timeline]]
at = "3 s"
device = "servo"
read = 83
)";

// 000 2.4.2: the MC6000's CODE for parameter n is 2nnnn (read/write RAM).
lb::Code servo_code(unsigned n) { return lb::make_code(20000 + n); }

struct Host {
  serial::SerialPort port;
  lb::Host host;
  explicit Host(const std::string& path)
      : port(serial::SerialPort::open(path, {9600, serial::k7E1, false})), host([] {
          lb::HostConfig c;
          c.response_timeout = std::chrono::milliseconds(500);
          return c;
        }()) {}

  std::optional<std::uint32_t> read(unsigned n) {
    const lb::Outcome o = serial::transact(port, host, lb::enquiry(1, servo_code(n)));
    if (o.kind != lb::OutcomeKind::value) return std::nullopt;
    const auto raw = lb::parse_raw(lb::Family::enhanced, o.value.view());
    return raw.ok() ? std::optional<std::uint32_t>(raw.value) : std::nullopt;
  }
  lb::OutcomeKind write(unsigned n, const char* value) {
    return serial::transact(port, host, lb::select(1, servo_code(n), lb::make_value(value))).kind;
  }
  // Reads `n` until `ok` holds or `deadline` passes; the last value read.
  template <typename F>
  std::optional<std::uint32_t> poll(unsigned n, F ok, Clock::time_point deadline) {
    std::optional<std::uint32_t> v;
    while (Clock::now() < deadline) {
      v = read(n);
      if (v && ok(*v)) return v;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return v;
  }
};

TEST(Bench, OneServoAnswersOnInterbusAndLustbusWithOneState) {
  const Scenario s = parse_scenario_toml(kScenario, "bench.toml");
  Simulator sim(s);
  Bench bench(sim, s, "bench.toml");
  const std::vector<std::string> lines = bench.ready_lines();
  ASSERT_EQ(lines.size(), 1U);
  ASSERT_EQ(lines[0].rfind("lustbus pty: /dev/", 0), 0U) << lines[0];
  const std::string path = lines[0].substr(std::string("lustbus pty: ").size());

  std::optional<std::uint32_t> speed, dummy, status_in_fault, status_after;
  lb::OutcomeKind written = lb::OutcomeKind::no_answer;
  std::thread host_thread([&] {
    Host h(path);
    const auto t0 = Clock::now();
    // The speed the INTERBUS master commanded, read as 77-SPEED (Q16 rpm) once the servo is there.
    speed = h.poll(77, [](std::uint32_t v) { return v == 1500U << 16; }, t0 + std::chrono::milliseconds(1900));
    // The PCP write of 83-SDMMY at 200 ms is what LUSTBUS reads; then LUSTBUS writes it for the
    // PCP read at 3 s. No 85 read over LUSTBUS first: the master's read at 0 s cleared the
    // drive's one power-on bit (LB-D1).
    dummy = h.poll(83, [](std::uint32_t v) { return v == 1234; }, t0 + std::chrono::milliseconds(1900));
    written = h.write(83, "10E1");  // 4321
    // 408-IBSTA, the DRIVECOM status word, while the fault injected at 2 s lasts: bit 3 (fault).
    status_in_fault = h.poll(408, [](std::uint32_t v) { return (v & 0x0008U) != 0; }, t0 + std::chrono::milliseconds(2900));
  });
  RealtimeOptions rt;
  rt.each_cycle = [&bench](Time now) { bench.turn(now); };
  run_realtime(sim, rt);
  host_thread.join();

  ASSERT_TRUE(speed.has_value());
  EXPECT_EQ(*speed, 1500U << 16) << "77-SPEED over LUSTBUS is the speed the INTERBUS master commanded";
  ASSERT_TRUE(dummy.has_value());
  EXPECT_EQ(*dummy, 1234U) << "the PCP write is what LUSTBUS reads";
  EXPECT_EQ(written, lb::OutcomeKind::acknowledged);
  ASSERT_TRUE(status_in_fault.has_value());
  EXPECT_NE(*status_in_fault & 0x0008U, 0U) << "the injected fault shows in the status word LUSTBUS reads";

  const Summary& summary = sim.summary();
  // The PCP read at 3 s returns what LUSTBUS wrote.
  const TransactionRecord* last = nullptr;
  for (const TransactionRecord& t : summary.transactions) {
    if (t.op == devices::ParamOp::read && t.number == 83) last = &t;
  }
  ASSERT_NE(last, nullptr);
  EXPECT_EQ(last->kind, devices::ParamKind::value) << last->result;
  EXPECT_EQ(last->result_value, 4321);
  // The master saw the same fault through the INTERBUS status word.
  bool fault_seen = false;
  for (const StateRecord& r : summary.devices[0].states) fault_seen = fault_seen || r.what == "FAULT";
  EXPECT_TRUE(fault_seen);
  // The real-time run's overrun counts stay in the summary; the bench counts what it served.
  ASSERT_TRUE(summary.realtime.has_value());
  const BenchReport report = bench.report();
  ASSERT_EQ(report.devices.size(), 1U);
  EXPECT_EQ(report.devices[0].name, "servo");
  EXPECT_GE(report.devices[0].telegrams, 4U);
  EXPECT_EQ(report.devices[0].errors, 0U);
}

// The inverter: its serial interface opens once the master has written 1-MODE <> 4 (INTERBUS manual,
// 6.1; VF-E16); then the communication word's write is what LUSTBUS reads, and LUSTBUS's write is
// what the communication word reads.
TEST(Bench, OneInverterAnswersOnTheCommunicationWordAndLustbusWithOneStore) {
  const Scenario s = parse_scenario_toml(R"(
name = "fan"
duration = "3 s"

[[device]]
name = "fan"
type = "vf1000"
lustbus = 2

[lustbus]
pty = true

[[timeline]]
at = "0 s"
device = "fan"
read = 85

[[timeline]]
at = "100 ms"
device = "fan"
write = { parameter = 1, value = 1 }

[[timeline]]
at = "600 ms"
device = "fan"
write = { parameter = 22, value = 900 }

[[timeline]]
at = "2500 ms"
device = "fan"
read = 22
)",
                                         "fan.toml");
  Simulator sim(s);
  Bench bench(sim, s, "fan.toml");
  const std::string path = bench.ready_lines().at(0).substr(std::string("lustbus pty: ").size());
  std::optional<std::uint32_t> locked, fmax;
  lb::OutcomeKind written = lb::OutcomeKind::no_answer;
  std::thread host_thread([&] {
    serial::SerialPort port = serial::SerialPort::open(path, {9600, serial::k7E1, false});
    lb::HostConfig c;
    c.response_timeout = std::chrono::milliseconds(100);
    c.enquiry_retries = 0;  // one ENQUIRY is one look at the drive
    lb::Host host(c);
    const auto read22 = [&]() -> std::optional<std::uint32_t> {
      const lb::Outcome o = serial::transact(port, host, lb::enquiry(2, *lb::vf_code(22)));
      if (o.kind != lb::OutcomeKind::value) return std::nullopt;
      const auto raw = lb::parse_raw(lb::Family::standard, o.value.view());
      return raw.ok() ? std::optional<std::uint32_t>(raw.value) : std::nullopt;
    };
    const auto t0 = Clock::now();
    locked = read22();  // at once: 1-MODE is still 4, the drive hears nothing
    while (Clock::now() < t0 + std::chrono::milliseconds(2200)) {
      fmax = read22();
      if (fmax == 900U) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    // 10, exception 4: the ACK of a changed EEPROM value comes after storing (~120 ms more).
    lb::Host writer{};
    written = serial::transact(port, writer, lb::select(2, *lb::vf_code(22), lb::make_value("044C"))).kind;  // 1100
  });
  RealtimeOptions rt;
  rt.each_cycle = [&bench](Time now) { bench.turn(now); };
  run_realtime(sim, rt);
  host_thread.join();

  EXPECT_FALSE(locked.has_value()) << "answered at 1-MODE = 4";
  ASSERT_TRUE(fmax.has_value());
  EXPECT_EQ(*fmax, 900U) << "the communication word's write of 22-FMAX1 is what LUSTBUS reads";
  EXPECT_EQ(written, lb::OutcomeKind::acknowledged);
  const TransactionRecord& last = sim.summary().transactions.back();
  ASSERT_EQ(last.number, 22);
  EXPECT_EQ(last.kind, devices::ParamKind::value) << last.result;
  EXPECT_EQ(last.result_value, 1100) << "LUSTBUS's write is what the communication word reads";
}

// A DFS-1 controller of the bench: not on the ring, on its own line; the timeline's fault with a
// cause of the DFS-1 manual's status list shows in the status a host reads (command 81, ST1), and a cause
// the wing does not know is refused with the entry's line.
TEST(Bench, ADfs1ControllerTakesTheTimelinesFaultOnItsOwnLine) {
  const std::string text = R"(name = "press"
duration = "2 s"

[[device]]
name = "servo"
type = "mc6000"

[dfs1]
pty = true

[[dfs1.controller]]
name = "press"
uid = 7

[[timeline]]
at = "1 s"
device = "press"
fault = "device"
cause = "IOC"
)";
  const Scenario s = parse_scenario_toml(text, "press.toml");
  Simulator sim(s);
  Bench bench(sim, s, "press.toml");
  ASSERT_EQ(bench.ready_lines().size(), 1U);
  const std::string path = bench.ready_lines()[0].substr(std::string("dfs1 pty: ").size());
  std::optional<std::uint8_t> before, after;
  std::thread host_thread([&] {
    serial::SerialPort port = serial::SerialPort::open(path, {9600, serial::k8N1, false});
    const auto st1 = [&]() -> std::optional<std::uint8_t> {
      const ::ibs::dfs1::HostResult r = serial::transact(port, ::ibs::dfs1::request::status(7), {});
      if (r.outcome != ::ibs::dfs1::Outcome::ack) return std::nullopt;
      return r.response.data[15];
    };
    const auto t0 = Clock::now();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    before = st1();
    while (Clock::now() < t0 + std::chrono::milliseconds(1900)) {
      after = st1();
      if (after && *after != 0) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  RealtimeOptions rt;
  rt.each_cycle = [&bench](Time now) { bench.turn(now); };
  run_realtime(sim, rt);
  host_thread.join();
  ASSERT_TRUE(before.has_value());
  EXPECT_EQ(*before, 0) << "no fault before 1 s";
  ASSERT_TRUE(after.has_value());
  EXPECT_EQ(*after, devices::dfs1::kSt1Ioc);
  const BenchReport report = bench.report();
  ASSERT_EQ(report.events.size(), 1U);
  EXPECT_EQ(report.events[0].rfind("1.000 s press: fault IOC", 0), 0U) << report.events[0];

  std::string bad = text;
  bad.replace(bad.find("\"IOC\""), 5, "\"E-OC\"");
  const Scenario b = parse_scenario_toml(bad, "press.toml");
  Simulator sim2(b);
  try {
    Bench refused(sim2, b, "press.toml");
    FAIL() << "a cause the DFS-1 does not know was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("press.toml:15: controller 'press': ", 0), 0U) << e.what();
    EXPECT_NE(std::string(e.what()).find("E-OC"), std::string::npos) << e.what();
  }
}

TEST(Bench, AServedLineIsRefusedForADriveThatDoesNotRunAtItsRate) {
  std::string text = kScenario;
  text.replace(text.find("pty = true"), 10, "pty = true\nbaud = 57600");
  Scenario s = parse_scenario_toml(text, "bench.toml");
  // The MC6000 runs at 57600 (LUSTBUS manual 4); a VF1000 would not.
  { Simulator sim(s); EXPECT_NO_THROW(Bench(sim, s, "bench.toml")); }
  s.devices[0] = DeviceConfig{};
  s.devices[0].name = "fan";
  s.devices[0].kind = "vf1000";
  s.devices[0].lustbus = 2;
  s.timeline.clear();
  Simulator sim(s);
  try {
    Bench b(sim, s, "bench.toml");
    FAIL() << "a VF1000 at 57600 baud was served";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "bench.toml: device 'fan': a VF1000 runs at 2400, 4800 or 9600 baud (LUSTBUS manual 4), not 57600");
  }
}

// A served line as a capture (`ibs run --lustbus-pcap`, docs/pcap.md "Serial lines"): the host's
// ENQUIRY and the drive's answer each its way, stamped with the run's clock (the epoch plus the
// simulated time of the turn that read or wrote them) like the INTERBUS capture of the same run.
TEST(Bench, AServedLineIsCapturedOnTheRunsClock) {
  const Scenario s = parse_scenario_toml(R"(
name = "bench-capture"
duration = "800 ms"

[[device]]
name = "servo"
type = "mc6000"
lustbus = 1

[lustbus]
pty = true
)", "capture.toml");
  Simulator sim(s);
  Bench bench(sim, s, "capture.toml");
  EXPECT_TRUE(bench.serves_line("lustbus"));
  EXPECT_FALSE(bench.serves_line("dfs1"));
  EXPECT_THROW(bench.capture("dfs1", std::cout, Time{0}), std::invalid_argument);
  std::ostringstream out;
  const Time epoch{1'700'000'000'000'000'000};
  bench.capture("lustbus", out, epoch);
  const std::string path = bench.ready_lines().at(0).substr(std::string("lustbus pty: ").size());
  std::optional<std::uint32_t> type;
  std::thread host_thread([&] {
    Host h(path);
    type = h.poll(91, [](std::uint32_t) { return true; }, Clock::now() + std::chrono::milliseconds(600));
  });
  RealtimeOptions rt;
  rt.each_cycle = [&bench](Time now) { bench.turn(now); };
  run_realtime(sim, rt);
  host_thread.join();
  ASSERT_TRUE(type.has_value());
  const std::uint64_t packets = bench.finish_capture("lustbus");
  const std::string file = out.str();
  const auto r = serial::read_line_capture(std::span(reinterpret_cast<const std::uint8_t*>(file.data()), file.size()));
  ASSERT_FALSE(r.error) << r.error->what;
  EXPECT_EQ(r.protocol, serial::LineProtocol::lustbus);
  ASSERT_EQ(r.packets.size(), packets);
  ASSERT_GE(r.packets.size(), 2U);
  EXPECT_EQ(r.packets[0].from, base::LineSide::host);
  EXPECT_EQ(r.packets[0].address, 1);
  EXPECT_EQ(r.packets[1].from, base::LineSide::device);
  EXPECT_EQ(r.packets[1].flags, 0);
  for (const auto& p : r.packets) {
    EXPECT_GE(p.at, epoch);
    EXPECT_LE(p.at, epoch + s.duration) << "stamped with the simulated time";
  }
}

}  // namespace
}  // namespace ibs::sim
