// Plant and fault events of the emulated DFS-1 (events.hpp; docs/dfs1.md, "Faults on demand",
// decisions D15-D20): each one as a host reads it through the real protocol path (the master
// driver asking status 81, 8A and the others on the simulated RS-485 line), the served
// controller's queue that applies them at the serve loop's time, and the control lines' parser
// with every refusal it gives.
#include "ibs/devices/dfs1/events.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ibs/devices/dfs1/line.hpp"
#include "ibs/devices/dfs1/served_controller.hpp"
#include "ibs/devices/dfs1/status.hpp"
#include "ibs/dfs1/host.hpp"

namespace ibs::devices::dfs1 {
namespace {

namespace proto = ::ibs::dfs1;
namespace request = proto::request;

// What a host reads with status 81 (D3).
struct Status {
  std::int32_t commanded = 0;
  std::int32_t actual = 0;
  std::uint32_t load = 0;
  std::uint8_t st2 = 0;
  std::uint8_t st1 = 0;
};

// One controller (UID 7) and the project's master on the simulated line at 9600 Bd.
struct Bench {
  Bench() : controller({7}), master({100ms, 10ms}), line(master, {&controller}, 9600) {}

  proto::HostResult transact(const proto::Frame& f) {
    EXPECT_TRUE(master.submit(f));
    line.run_until_idle(line.now() + 10s);
    auto c = master.take_completion();
    EXPECT_TRUE(c);
    return c ? c->result : proto::HostResult{};
  }
  void ack(const proto::Frame& f) {
    const auto r = transact(f);
    EXPECT_EQ(r.outcome, proto::Outcome::ack) << proto::to_string(static_cast<proto::Command>(f.code));
  }
  std::uint32_t value(const proto::Frame& f) {
    const auto r = transact(f);
    EXPECT_EQ(r.outcome, proto::Outcome::ack);
    return r.value();
  }
  Status status() {
    const auto r = transact(request::status(7));
    EXPECT_EQ(r.outcome, proto::Outcome::ack);
    Status s;
    s.commanded = proto::to_signed(r.response.value_at(0));
    s.actual = proto::to_signed(r.response.value_at(4));
    s.load = r.response.value_at(8);
    s.st2 = r.response.data[14];
    s.st1 = r.response.data[15];
    return s;
  }
  EventReport apply(const Event& e) { return controller.apply(e, line.now()); }
  void run_for(Duration d) { line.run_until(line.now() + d); }
  // Remote (parameter 3 = 15) and running at `rpm`, settled.
  void running(std::int32_t rpm) {
    ack(request::write_parameter(7, kRemoteFunctions, kRemoteAll));
    ack(request::set_and_execute_speed(7, rpm));
    run_for(6s);
    ASSERT_EQ(status().actual, rpm);
  }

  Controller controller;
  Master master;
  SimulatedLine line;
};

// DFS-1 manual's status list (public notes, "Status (81)"): each cause by its name shows as its bit of
// ST1 (or ST2's uP fault) and as ST2's fault bit, in the status the host reads, and by the name
// `ibs dfs1 status` prints.
struct CauseRow {
  const char* seed_name;
  std::uint8_t st1;
  std::uint8_t st2;
  const char* printed;
};
constexpr CauseRow kCauseTable[] = {
    {"Bus not charged", kSt1BusNotCharged, 0, "bus-not-charged"},
    {"IOC", kSt1Ioc, 0, "IOC"},
    {"Stall", kSt1Stall, 0, "stall"},
    {"I2t", kSt1I2t, 0, "I2t"},
    {"Heatsink OT", kSt1HeatsinkOvertemp, 0, "heatsink-overtemp"},
    {"Commutation", kSt1Commutation, 0, "commutation"},
    {"Overvolt", kSt1Overvolt, 0, "overvolt"},
    {"Undervolt", kSt1Undervolt, 0, "undervolt"},
    {"uP fault", 0, kSt2MicroFault, "uP-fault"},
};

TEST(Dfs1Events, EveryFaultCauseShowsInTheStatusTheHostReads) {
  for (const CauseRow& row : kCauseTable) {
    SCOPED_TRACE(row.seed_name);
    Bench b;
    b.running(1000);
    const auto cause = find_fault_cause(row.seed_name);
    ASSERT_TRUE(cause);
    EXPECT_EQ(find_fault_cause(row.printed), cause);
    const EventReport r = b.apply(Event::fault(*cause));
    EXPECT_TRUE(r.latched);
    const Status s = b.status();
    EXPECT_EQ(s.st1, row.st1);
    EXPECT_EQ(s.st2 & kSt2Fault, kSt2Fault);
    EXPECT_EQ(s.st2 & kSt2MicroFault, row.st2);
    EXPECT_EQ(s.st2 & kSt2Enabled, 0);
    if (row.st1 != 0) {
      EXPECT_EQ(st1_flags(s.st1), std::vector<std::string_view>{row.printed});
    } else {
      EXPECT_EQ(st2_flags(s.st2 & kSt2MicroFault), std::vector<std::string_view>{row.printed});
    }
    // The motor coasts (D15): nothing drives it any more, it takes no current (D18).
    EXPECT_EQ(s.load, 0U);
    EXPECT_GT(s.actual, 0);
    b.run_for(10s);
    EXPECT_EQ(b.status().actual, 0);
  }
}

TEST(Dfs1Events, DecisionD16AFaultStaysLatchedUntilTheEstopOpensWithTheCauseGone) {
  Bench b;
  b.running(1000);
  b.apply(Event::fault(FaultCause::overvolt, 500ms));
  b.run_for(2s);  // the cause is gone, the fault is not
  EXPECT_FALSE(b.controller.cause_present(FaultCause::overvolt));
  EXPECT_EQ(b.status().st1, kSt1Overvolt);
  // A start while latched is taken, and runs nothing.
  b.ack(request::set_and_execute_speed(7, 800));
  b.run_for(2s);
  EXPECT_EQ(b.status().actual, 0);
  // The E-stop opened resets it; closed again, the motor waits for a new start.
  EventReport r = b.apply(Event::input_level(kEstopInput, false));
  EXPECT_FALSE(r.latched);
  EXPECT_EQ(r.st1, 0);
  r = b.apply(Event::input_level(kEstopInput, true));
  Status s = b.status();
  EXPECT_EQ(s.st1, 0);
  EXPECT_EQ(s.st2 & kSt2Fault, 0);
  b.run_for(2s);
  EXPECT_EQ(b.status().actual, 0);
  b.ack(request::set_and_execute_speed(7, 800));
  b.run_for(6s);
  s = b.status();
  EXPECT_EQ(s.actual, 800);
  EXPECT_EQ(s.st2 & kSt2Enabled, kSt2Enabled);
}

TEST(Dfs1Events, DecisionD16AnOpenEstopResetsTheFaultOnlyOnceItsCauseHasGone) {
  Bench b;
  b.apply(Event::input_level(kEstopInput, false));
  b.apply(Event::fault(FaultCause::heatsink_overtemp, 1s));
  EXPECT_EQ(b.status().st1, kSt1HeatsinkOvertemp);  // the cause is still there
  b.run_for(500ms);
  EXPECT_EQ(b.status().st1, kSt1HeatsinkOvertemp);
  b.run_for(1s);
  EXPECT_EQ(b.status().st1, 0);  // gone with its cause: the E-stop was open all along
  // Without a duration the cause is gone at once: an open E-stop never lets the fault latch.
  const EventReport r = b.apply(Event::fault(FaultCause::ioc));
  EXPECT_FALSE(r.latched);
  EXPECT_EQ(r.st1, 0);
}

TEST(Dfs1Events, DecisionD17MainsLossShowsBusNotChargedAndNeedsANewStart) {
  Bench b;
  b.running(1200);
  EventReport r = b.apply(Event::mains(false));
  EXPECT_EQ(r.st1, kSt1BusNotCharged);
  EXPECT_FALSE(r.latched);  // a state of the supply, not a fault memory
  Status s = b.status();  // the control electronics still answer
  EXPECT_EQ(s.st1, kSt1BusNotCharged);
  EXPECT_EQ(s.st2 & kSt2Fault, kSt2Fault);
  EXPECT_EQ(s.st2 & kSt2Enabled, 0);
  b.ack(request::set_and_execute_speed(7, 1200));  // taken, runs nothing
  b.run_for(10s);
  EXPECT_EQ(b.status().actual, 0);
  r = b.apply(Event::mains(true));
  EXPECT_EQ(r.st1, 0);
  s = b.status();
  EXPECT_EQ(s.st2 & kSt2Fault, 0);
  b.run_for(2s);
  EXPECT_EQ(b.status().actual, 0);
  b.ack(request::set_and_execute_speed(7, 1200));
  b.run_for(6s);
  EXPECT_EQ(b.status().actual, 1200);
}

TEST(Dfs1Events, DecisionD19InputsReadWithCommand8AAndTheEstopStopsTheMotor) {
  Bench b;
  b.running(900);
  for (std::uint8_t channel = 2; channel <= kDigitalInputs; ++channel) {
    SCOPED_TRACE(static_cast<int>(channel));
    EXPECT_EQ(b.value(request::read_digital_input(7, channel)), 0U);
    b.apply(Event::input_level(channel, true));
    EXPECT_EQ(b.value(request::read_digital_input(7, channel)), 1U);
    EXPECT_EQ(b.status().actual, 900);  // no function of theirs is modelled
    b.apply(Event::input_level(channel, false));
    EXPECT_EQ(b.value(request::read_digital_input(7, channel)), 0U);
  }
  EXPECT_EQ(b.value(request::read_digital_input(7, kEstopInput)), 1U);  // closed at power-on
  b.apply(Event::input_level(kEstopInput, false));
  EXPECT_EQ(b.value(request::read_digital_input(7, kEstopInput)), 0U);
  b.run_for(10s);
  Status s = b.status();
  EXPECT_EQ(s.actual, 0);
  EXPECT_EQ(s.st2 & kSt2Enabled, 0);
  EXPECT_EQ(s.st1, 0);  // an E-stop is no fault
  b.apply(Event::input_level(kEstopInput, true));
  b.run_for(5s);
  EXPECT_EQ(b.status().actual, 0);  // no restart by itself
}

TEST(Dfs1Events, DecisionD18LoadShowsAsLoadPercentWhileTheMotorIsDriven) {
  Bench b;
  b.running(1000);
  EXPECT_EQ(b.status().load, 0U);
  const EventReport r = b.apply(Event::load(40));
  EXPECT_EQ(r.load_percent, 40U);
  b.run_for(1s);
  Status s = b.status();
  EXPECT_EQ(s.load, 40U);
  EXPECT_EQ(s.actual, 1000);  // the speed loop holds the speed
  b.apply(Event::load(kMaxLoadPercent));
  EXPECT_EQ(b.status().load, kMaxLoadPercent);
  b.ack(request::set_and_execute_speed(7, 0));
  b.run_for(10s);
  s = b.status();
  EXPECT_EQ(s.actual, 0);
  EXPECT_EQ(s.load, 0U);  // not driven: no current
}

TEST(Dfs1Events, DecisionD20APowerCycleRestartsAsAtPowerOnAndKeepsTheParameters) {
  Bench b;
  b.running(1000);
  b.ack(request::set_operational_mode(7, 0x0006));
  b.ack(request::write_digital_output(7, 2, 1));
  b.ack(request::write_analog_output(7, 1, 700));
  b.ack(request::application_mode(7, 1, 5));
  b.ack(request::write_parameter(7, kTurnaroundDelay, 9));
  b.apply(Event::fault(FaultCause::stall));
  b.apply(Event::load(30));
  b.apply(Event::input_level(3, true));

  const EventReport r = b.apply(Event::power_cycle());
  EXPECT_FALSE(r.latched);
  Status s = b.status();
  EXPECT_EQ(s.commanded, 0);
  EXPECT_EQ(s.st1, 0);
  EXPECT_EQ(s.st2 & (kSt2Fault | kSt2Slave), 0);
  EXPECT_EQ(b.value(request::read_operational_mode(7)), 0U);
  EXPECT_EQ(b.value(request::read_digital_output(7, 2)), 0U);
  EXPECT_EQ(b.value(request::read_analog_output(7, 1)), 0U);
  EXPECT_EQ(b.value(request::read_parameter(7, kRemoteFunctions)), kRemoteAll);  // kept
  EXPECT_EQ(b.value(request::read_parameter(7, kTurnaroundDelay)), 9U);
  EXPECT_EQ(b.value(request::read_digital_input(7, 3)), 1U);  // the terminal strip is wired
  EXPECT_EQ(b.controller.load(), 30U);
  b.ack(request::set_and_execute_speed(7, 500));
  b.run_for(6s);
  EXPECT_EQ(b.status().actual, 500);
}

TEST(Dfs1Events, DecisionD20ACauseStillPresentTripsAgainAtPowerOn) {
  Bench b;
  b.apply(Event::fault(FaultCause::heatsink_overtemp, 5s));
  b.run_for(1s);
  EXPECT_TRUE(b.apply(Event::power_cycle()).latched);
  EXPECT_EQ(b.status().st1, kSt1HeatsinkOvertemp);
  b.run_for(5s);
  EXPECT_TRUE(b.apply(Event::power_cycle()).latched == false);
  EXPECT_EQ(b.status().st1, 0);
  // Mains stay off through a power cycle: the supply is outside the controller.
  b.apply(Event::mains(false));
  b.apply(Event::power_cycle());
  EXPECT_EQ(b.status().st1, kSt1BusNotCharged);
}

TEST(Dfs1Events, DecisionD20APowerCycleLosesAReplyNotYetSent) {
  Controller c({1});
  c.receive(proto::encode(request::status(1)).span(), Time{0ms});
  ASSERT_TRUE(c.next_deadline());
  c.apply(Event::power_cycle(), Time{1ms});  // before the 2 ms turnaround
  EXPECT_FALSE(c.next_deadline());
  EXPECT_TRUE(c.pending(Time{10ms}).empty());
  // Half a frame is lost too: the rest of it alone is no request.
  const auto frame = proto::encode(request::status(1));
  c.receive(frame.span().first(3), Time{20ms});
  c.apply(Event::power_cycle(), Time{21ms});
  c.receive(frame.span().subspan(3), Time{22ms});
  EXPECT_FALSE(c.next_deadline());
  EXPECT_EQ(c.counters().requests, 1U);  // the counters are the emulator's: kept
}

TEST(Dfs1Events, TheServedControllerAppliesPostedEventsAtTheLoopsTime) {
  Controller c({3});
  ServedController d{c};
  ASSERT_TRUE(d.post(Event::fault(FaultCause::ioc, 250ms)));
  EXPECT_EQ(c.st1(), 0);  // nothing before the loop's turn
  EXPECT_FALSE(d.take_report());
  d.advance(Time{1500ms});
  EXPECT_EQ(c.st1(), kSt1Ioc);
  const auto r = d.take_report();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->at, Time(1500ms));
  EXPECT_EQ(r->event.cause, FaultCause::ioc);
  EXPECT_EQ(r->st1, kSt1Ioc);
  EXPECT_FALSE(d.take_report());
  d.receive({}, Time{1700ms});
  EXPECT_TRUE(c.cause_present(FaultCause::ioc));
  d.receive({}, Time{1751ms});
  EXPECT_FALSE(c.cause_present(FaultCause::ioc));  // 250 ms after the turn that applied it

  for (std::size_t i = 0; i < ServedController::kEventCapacity; ++i) EXPECT_TRUE(d.post(Event::load(1)));
  EXPECT_FALSE(d.post(Event::load(2)));  // full: the caller keeps it
  EXPECT_EQ(d.events_waiting(), ServedController::kEventCapacity);
  d.advance(Time{2s});
  EXPECT_EQ(d.events_waiting(), 0U);
  std::size_t reports = 0;
  while (d.take_report()) ++reports;
  EXPECT_EQ(reports, ServedController::kEventCapacity);
}

TEST(Dfs1Events, AReportSaysWhatHappenedAndWhatTheHostReads) {
  Controller c({1});
  EXPECT_EQ(to_string(c.apply(Event::fault(FaultCause::ioc, 500ms), Time{0ms})),
            "fault IOC, its cause lasting 500 ms; the motor coasts, the fault is latched until the E-stop "
            "input opens with the cause gone, or a power cycle; status ST2 39H at-speed forward fault "
            "zero-speed, ST1 40H IOC, load 0 %");
  EXPECT_EQ(to_string(Event::mains(false)), "mains off");
  EXPECT_EQ(to_string(Event::input_level(1, false)), "input 1 (E-stop) low");
  EXPECT_EQ(to_string(Event::input_level(4, true)), "input 4 high");
  EXPECT_EQ(to_string(Event::load(40)), "load 40 %");
  EXPECT_EQ(to_string(Event::power_cycle()), "power cycle");
  EXPECT_EQ(to_string(Event::fault(FaultCause::micro_fault)), "fault uP fault, its cause gone at once");
}

// --- the control lines' parser ---

ControlFields fields(std::initializer_list<std::pair<const char*, ControlValue>> kv) {
  ControlFields f;
  for (const auto& [k, v] : kv) f.emplace_back(k, v);
  return f;
}
ControlValue s(const char* t) { return ControlValue::string(t); }
ControlValue n(double v) { return ControlValue::of_number(v); }

ControlEvent parsed(const ControlFields& f) {
  const ParsedControl p = parse_event(f);
  EXPECT_TRUE(p.event) << p.error;
  EXPECT_TRUE(p.error.empty());
  return p.event.value_or(ControlEvent{});
}

std::string refusal(const ControlFields& f) {
  const ParsedControl p = parse_event(f);
  EXPECT_FALSE(p.event);
  return p.error;
}

TEST(Dfs1ControlParser, EveryEventAndDeviceForm) {
  ControlEvent e = parsed(fields({{"fault", s("device")}, {"cause", s("Heatsink OT")}, {"duration", s("0.5 s")}}));
  EXPECT_FALSE(e.uid);
  EXPECT_EQ(e.event.kind, Event::Kind::fault);
  EXPECT_EQ(e.event.cause, FaultCause::heatsink_overtemp);
  EXPECT_EQ(e.event.duration, 500ms);
  e = parsed(fields({{"device", s("dfs1@7")}, {"fault", s("device")}, {"cause", s("heatsink-overtemp")}}));
  EXPECT_EQ(e.uid, 7);
  EXPECT_EQ(e.event.duration, Duration::zero());
  e = parsed(fields({{"device", n(255)}, {"fault", s("power-cycle")}}));
  EXPECT_EQ(e.uid, 255);
  EXPECT_EQ(e.event.kind, Event::Kind::power_cycle);
  e = parsed(fields({{"mains", s("off")}}));
  EXPECT_EQ(e.event.kind, Event::Kind::mains);
  EXPECT_FALSE(e.event.on);
  EXPECT_TRUE(parsed(fields({{"mains", s("on")}})).event.on);
  for (const ControlValue& v : {n(1), s("1"), s("DI1"), s("di1"), s("E-stop"), s("estop")}) {
    e = parsed(fields({{"input", v}, {"level", s("low")}}));
    EXPECT_EQ(e.event.kind, Event::Kind::input);
    EXPECT_EQ(e.event.input, kEstopInput);
    EXPECT_FALSE(e.event.on);
  }
  e = parsed(fields({{"input", s("DI7")}, {"level", s("high")}}));
  EXPECT_EQ(e.event.input, 7);
  EXPECT_TRUE(e.event.on);
  e = parsed(fields({{"load", n(150)}}));
  EXPECT_EQ(e.event.kind, Event::Kind::load);
  EXPECT_EQ(e.event.load_percent, 150U);
  for (const CauseRow& row : kCauseTable) {
    EXPECT_EQ(parsed(fields({{"fault", s("device")}, {"cause", s(row.seed_name)}})).event.cause,
              *find_fault_cause(row.printed));
  }
}

TEST(Dfs1ControlParser, EveryRefusalNamesTheKeyTheValueAndWhatIsAllowed) {
  EXPECT_EQ(refusal(fields({{"fault", s("device")}, {"cause", s("IOC")}, {"colour", s("red")}})),
            "unknown key \"colour\"; a DFS-1 control line takes device, fault, cause, duration, mains, input, "
            "level, load");
  EXPECT_EQ(refusal(fields({{"device", n(7)}})), "no event: give one of \"fault\", \"mains\", \"input\", \"load\"");
  EXPECT_EQ(refusal(fields({{"mains", s("off")}, {"load", n(3)}})),
            "\"mains\" and \"load\" in one line: give one event per line");
  EXPECT_EQ(refusal(fields({{"mains", s("off")}, {"mains", s("on")}})), "key \"mains\" given twice");
  // device
  EXPECT_EQ(refusal(fields({{"device", n(0)}, {"mains", s("off")}})),
            "\"device\": 0 is no unit ID; give a unit ID 1..255 or \"dfs1@UID\"");
  EXPECT_EQ(refusal(fields({{"device", n(7.5)}, {"mains", s("off")}})),
            "\"device\": 7.5 is no unit ID; give a unit ID 1..255 or \"dfs1@UID\"");
  EXPECT_EQ(refusal(fields({{"device", s("vf1000@7")}, {"mains", s("off")}})),
            "\"device\": \"vf1000@7\" names no DFS-1 controller; give a unit ID 1..255 or \"dfs1@UID\"");
  EXPECT_EQ(refusal(fields({{"device", s("dfs1@256")}, {"mains", s("off")}})),
            "\"device\": \"dfs1@256\" names no DFS-1 controller; give a unit ID 1..255 or \"dfs1@UID\"");
  EXPECT_EQ(refusal(fields({{"device", ControlValue::other("a boolean")}, {"mains", s("off")}})),
            "\"device\": expected a unit ID 1..255 or \"dfs1@UID\", got a boolean");
  // fault
  EXPECT_EQ(refusal(fields({{"fault", s("trip")}})),
            "\"fault\": \"trip\" is no DFS-1 fault event; allowed: \"device\", \"power-cycle\"");
  EXPECT_EQ(refusal(fields({{"fault", n(1)}})),
            "\"fault\": expected a string (\"device\" or \"power-cycle\"), got the number 1");
  EXPECT_EQ(refusal(fields({{"fault", s("device")}})),
            "\"fault\": \"device\" needs \"cause\", one of \"Bus not charged\", \"IOC\", \"Stall\", \"I2t\", "
            "\"Heatsink OT\", \"Commutation\", \"Overvolt\", \"Undervolt\", \"uP fault\"");
  EXPECT_EQ(refusal(fields({{"fault", s("device")}, {"cause", s("E42")}})),
            "\"cause\": \"E42\" is no DFS-1 fault; allowed: \"Bus not charged\", \"IOC\", \"Stall\", \"I2t\", "
            "\"Heatsink OT\", \"Commutation\", \"Overvolt\", \"Undervolt\", \"uP fault\" (or the names `ibs dfs1 "
            "status` prints)");
  EXPECT_EQ(refusal(fields({{"fault", s("device")}, {"cause", ControlValue::other("an array")}})),
            "\"cause\": expected a string (a DFS-1 fault), got an array");
  EXPECT_EQ(refusal(fields({{"fault", s("device")}, {"cause", s("IOC")}, {"duration", n(0.5)}})),
            "\"duration\": expected a string (a time with its unit, e.g. \"0.5 s\"), got the number 0.5");
  EXPECT_EQ(refusal(fields({{"fault", s("device")}, {"cause", s("IOC")}, {"duration", s("half")}})).rfind(
                "\"duration\": \"half\": ", 0),
            0U);
  EXPECT_EQ(refusal(fields({{"fault", s("power-cycle")}, {"cause", s("IOC")}})),
            "\"cause\" belongs to \"fault\": \"device\"; a power cycle takes none");
  EXPECT_EQ(refusal(fields({{"fault", s("power-cycle")}, {"duration", s("1 s")}})),
            "\"duration\" belongs to \"fault\": \"device\"; a power cycle takes none");
  EXPECT_EQ(refusal(fields({{"mains", s("off")}, {"cause", s("IOC")}})),
            "\"cause\" belongs to \"fault\": \"device\" only");
  EXPECT_EQ(refusal(fields({{"load", n(5)}, {"duration", s("1 s")}})),
            "\"duration\" belongs to \"fault\": \"device\" only");
  // mains
  EXPECT_EQ(refusal(fields({{"mains", s("down")}})), "\"mains\": \"down\"; allowed: \"off\", \"on\"");
  EXPECT_EQ(refusal(fields({{"mains", n(0)}})), "\"mains\": expected a string (\"off\" or \"on\"), got the number 0");
  EXPECT_EQ(refusal(fields({{"mains", s("off")}, {"level", s("low")}})), "\"level\" belongs to an input event only");
  // input
  const std::string forms =
      "1..7 (digital inputs #1-#7, as a number or a string), \"DI1\"..\"DI7\" or \"E-stop\" (input 1)";
  EXPECT_EQ(refusal(fields({{"input", n(8)}, {"level", s("high")}})),
            "\"input\": 8 is no DFS-1 digital input; allowed: " + forms);
  EXPECT_EQ(refusal(fields({{"input", s("DI0")}, {"level", s("high")}})),
            "\"input\": \"DI0\" is no DFS-1 digital input; allowed: " + forms);
  EXPECT_EQ(refusal(fields({{"input", ControlValue::other("null")}, {"level", s("high")}})),
            "\"input\": expected " + forms + ", got null");
  EXPECT_EQ(refusal(fields({{"input", n(3)}})), "\"input\" needs \"level\": \"high\" or \"low\"");
  EXPECT_EQ(refusal(fields({{"input", n(3)}, {"level", s("1")}})), "\"level\": \"1\"; allowed: \"high\", \"low\"");
  EXPECT_EQ(refusal(fields({{"input", n(3)}, {"level", ControlValue::other("a boolean")}})),
            "\"level\": expected a string (\"high\" or \"low\"), got a boolean");
  // load
  EXPECT_EQ(refusal(fields({{"load", n(201)}})),
            "\"load\": 201; allowed: a whole number of percent of the drive's rating, 0..200");
  EXPECT_EQ(refusal(fields({{"load", n(12.5)}})),
            "\"load\": 12.5; allowed: a whole number of percent of the drive's rating, 0..200");
  EXPECT_EQ(refusal(fields({{"load", n(-1)}})),
            "\"load\": -1; allowed: a whole number of percent of the drive's rating, 0..200");
  EXPECT_EQ(refusal(fields({{"load", s("40 %")}})),
            "\"load\": expected a whole number of percent of the drive's rating, 0..200, got the string \"40 %\"");
  EXPECT_EQ(refusal(fields({{"load", n(5)}, {"level", s("low")}})), "\"level\" belongs to an input event only");
}

}  // namespace
}  // namespace ibs::devices::dfs1
