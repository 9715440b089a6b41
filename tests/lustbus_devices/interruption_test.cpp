// No parameter of the emulated drives is ever half-written (LUSTBUS manual 3): every telegram kind
// against the real VF1000 and MC6000 wings, each character on the line lost, replaced by EOT,
// garbage, a garbled character or a NUL, or a bit flipped (a wrong BCC at the BCC). The value
// is old or new, exactly; an ACK means new; an answer's value is the true one; afterwards (85
// read first) the clean telegram works. tests/lustbus/interruption_test.cpp does the same
// against the fake drive with every protocol path.
#include <gtest/gtest.h>

#include <functional>

#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "../lustbus/line_faults.hpp"
#include "servo_procedures.hpp"
#include "support.hpp"

namespace {

using namespace ibs::lustbus;
using namespace ibs::lustbus::devtest;
using ibs::lustbus::test::apply;
using ibs::lustbus::test::Fault;
using ibs::lustbus::test::kFaults;
namespace mc = ibs::devices::mc6000;
namespace vf = ibs::devices::vf1000;

struct Drives {
  vf::LustbusDevice vf1000{vf_timing()};
  mc::LustbusDevice mc6000{mc_timing()};
  static vf::LustbusTiming vf_timing() { return {}; }
  static mc::LustbusTiming mc_timing() {
    mc::LustbusTiming t;
    t.eeprom_per_byte = 0ms;  // the clean repetition must not meet 04H
    return t;
  }
};

struct Kind {
  const char* name;
  Request request;
  std::function<std::uint32_t(const Drives&)> value;  // the parameter written (null: none)
  std::uint32_t new_value;
  const char* text;  // what an ENQUIRY answers ("" for a SELECT)
};

std::vector<Kind> kinds() {
  const auto vfv = [](unsigned n) {
    return [n](const Drives& d) -> std::uint32_t { return d.vf1000.value(static_cast<std::uint16_t>(n)); };
  };
  const auto mcv = [](unsigned n) {
    return [n](const Drives& d) { return d.mc6000.value(static_cast<std::uint16_t>(n)); };
  };
  return {
      {"VF SELECT RAM", select(1, make_code(105), make_value("03E8")), vfv(5), 0x3E8, ""},
      {"VF SELECT EEPROM (delayed ACK)", select(1, make_code(122), make_value("0190")), vfv(22), 0x190, ""},
      {"VF ENQUIRY", enquiry(1, make_code(191)), nullptr, 0, "03E8"},
      {"VF description", enquiry(1, make_code(10122)), nullptr, 0, " FMAX1    Hz2200004E1F03E8"},
      {"MC SELECT 32 bit", select(3, make_code(20428), make_value("84FA4000")), mcv(428), 0x84FA4000, ""},
      {"MC SELECT EEPROM", select(3, make_code(20417), make_value("3")), mcv(417), 3, ""},
      {"MC ENQUIRY", enquiry(3, make_code(20091)), nullptr, 0, "1770"},
      {"MC substitution text", substitution_text_request(3, 300, 2), mcv(108), 2, "SCON"},
  };
}

bool good(const Outcome& o) {
  return o.kind == OutcomeKind::value || o.kind == OutcomeKind::acknowledged;
}

// A bus with both drives whose power-on bits have been read.
struct TwoDrives {
  Drives d;
  Bus bus;
  explicit TwoDrives(HostConfig cfg) : bus(cfg) {
    bus.add(d.vf1000, 1);
    bus.add(d.mc6000, 3);
    bus.read(1, 85);
    bus.read(3, 85);
  }
};

TEST(WingInterruptions, EveryCharacterOfEveryTelegramKind) {
  int runs = 0;
  for (const Kind& k : kinds()) {
    std::size_t length = 0;
    {
      TwoDrives s{HostConfig{}};
      s.bus.line.set_tap([&length](const LineChar&) { ++length; });
      const Outcome o = s.bus.run(k.request);
      ASSERT_TRUE(good(o)) << k.name << ": " << describe(o);
      if (o.kind == OutcomeKind::value) {
        ASSERT_EQ(o.value.view(), k.text) << k.name;
      }
    }
    for (std::size_t at = 0; at < length; ++at) {
      for (const Fault fault : kFaults) {
        ++runs;
        HostConfig cfg;
        cfg.enquiry_retries = 0;
        cfg.select_retries = 0;
        TwoDrives s(cfg);
        const std::uint32_t old = k.value ? k.value(s.d) : 0;
        std::size_t n = 0;
        s.bus.line.set_filter([&n, at, fault](const LineChar& c) -> std::optional<std::uint8_t> {
          return n++ == at ? apply(fault, c.byte) : std::optional<std::uint8_t>(c.byte);
        });
        const Outcome o = s.bus.run(k.request);
        const std::string where = std::string(k.name) + " at " + std::to_string(at) + " fault " +
                                  std::to_string(static_cast<int>(fault)) + ": " + describe(o);
        if (k.value) {
          const std::uint32_t now = k.value(s.d);
          EXPECT_TRUE(now == old || now == k.new_value) << where << " value " << now;
          if (o.kind == OutcomeKind::acknowledged) {
            EXPECT_EQ(now, k.new_value) << where;
          }
        }
        if (o.kind == OutcomeKind::value) {
          EXPECT_EQ(o.value.view(), k.text) << where;
        }
        s.bus.line.set_filter(nullptr);
        s.bus.read(k.request.address, 85);  // whatever the fault left in the latch
        const Outcome again = s.bus.run(k.request);
        EXPECT_TRUE(good(again)) << where << " then " << describe(again);
        if (k.value) {
          EXPECT_EQ(k.value(s.d), k.new_value) << where;
        }
      }
    }
  }
  EXPECT_GT(runs, 500);
}

}  // namespace
