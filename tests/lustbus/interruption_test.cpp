// No parameter is ever half-written: every telegram kind, interrupted at every character (EOT,
// garbage, a parity error, a NUL, a flipped bit — which is a wrong BCC at the BCC — or the
// character lost), on the line between the host and a fake drive; and, on the receiver alone,
// EOT or garbage inserted before every character. The value is old or new, exactly; an ACK or
// a value outcome is always true; the next clean telegram works.
#include <gtest/gtest.h>

#include "line_faults.hpp"
#include "test_support.hpp"

namespace ibs::lustbus {
namespace {

using test::apply;
using test::Bus;
using test::Fault;
using test::kFaults;
using test::FakeDrive;
using test::make_mc6000;
using test::make_vf1000;

struct Kind {
  const char* name;
  Family family;
  Request request;
  unsigned parameter;      // the parameter written (0: none)
  std::uint32_t new_value; // what a SELECT writes
  const char* text;        // what an ENQUIRY answers ("" for a SELECT)
};

// 11.3 as the fake servo offers it (a static: the requests point at it).
const IndexedTextProcedure kTexts{Family::enhanced, 108};

std::vector<Kind> kinds() {
  return {
      {"VF SELECT RAM", Family::standard, select(1, make_code(105), make_value("03E8")), 5, 0x3E8, ""},
      {"VF SELECT EEPROM (delayed ACK)", Family::standard, select(1, make_code(122), make_value("0190")),
       22, 0x190, ""},
      {"VF ENQUIRY", Family::standard, enquiry(1, make_code(112)), 0, 0, "03E8"},
      {"VF description", Family::standard, enquiry(1, make_code(10122)), 0, 0,
       " FMAX1    Hz2200004E1F03E8"},
      {"VF broadcast", Family::standard, broadcast(shared_code(83), make_value("0042")), 83, 0x42, ""},
      {"VF SIOF read", Family::standard, enquiry(1, kSiofCode), 0, 0, "0000"},
      {"MC SELECT 32 bit", Family::enhanced, select(1, make_code(20428), make_value("84FA4000")), 428,
       0x84FA4000, ""},
      {"MC SELECT short", Family::enhanced, select(1, make_code(20416), make_value("1")), 416, 1, ""},
      {"MC ENQUIRY", Family::enhanced, enquiry(1, make_code(20077)), 0, 0, "4FA4000"},
      {"MC PosMOD1", Family::enhanced, select(1, kPosmodCode, make_value("8GOA0V1000")), 0, 0, ""},
      {"MC substitution text", Family::enhanced, indexed_text_request(kTexts, 1, 300, 2), 108, 2,
       "SCON"},
  };
}

FakeDrive make(Family f) {
  auto d = f == Family::standard ? make_vf1000() : make_mc6000();
  d.siof = 0;
  d.mc_eeprom_per_byte = 0ms;
  return d;
}

TEST(Interruptions, EveryCharacterOfEveryTelegramKindOnTheLine) {
  int runs = 0;
  for (const Kind& k : kinds()) {
    // How many characters a clean run puts on the line.
    std::size_t length = 0;
    {
      auto d = make(k.family);
      Bus bus;
      bus.add(d, 1);
      bus.line.set_tap([&length](const LineChar&) { ++length; });
      const Outcome o = bus.run(k.request);
      ASSERT_TRUE(o.kind == OutcomeKind::value || o.kind == OutcomeKind::acknowledged ||
                  o.kind == OutcomeKind::sent)
          << k.name << ": " << describe(o);
    }
    for (std::size_t at = 0; at < length; ++at) {
      for (const Fault fault : kFaults) {
        ++runs;
        auto d = make(k.family);
        const std::uint32_t old = k.parameter != 0 ? d.value_of(k.parameter) : 0;
        HostConfig cfg;
        cfg.enquiry_retries = 0;
        cfg.select_retries = 0;
        Bus bus(cfg);
        bus.add(d, 1);
        std::size_t n = 0;
        bus.line.set_filter([&n, at, fault](const LineChar& c) -> std::optional<std::uint8_t> {
          return n++ == at ? apply(fault, c.byte) : std::optional<std::uint8_t>(c.byte);
        });
        const Outcome o = bus.run(k.request);
        const std::string where = std::string(k.name) + " at " + std::to_string(at) + " fault " +
                                  std::to_string(static_cast<int>(fault)) + ": " + describe(o);
        if (k.parameter != 0) {
          const std::uint32_t now = d.value_of(k.parameter);
          EXPECT_TRUE(now == old || now == k.new_value) << where << " value " << now;
          for (const auto& w : d.history) {
            if (w.number == k.parameter) {
              EXPECT_EQ(w.value, k.new_value) << where;
            }
          }
          if (o.kind == OutcomeKind::acknowledged) {
            EXPECT_EQ(now, k.new_value) << where;
          }
        }
        if (k.family == Family::enhanced && k.request.code == kPosmodCode) {
          EXPECT_TRUE(d.posmod_last.empty() || d.posmod_last == k.request.value) << where;
        }
        if (o.kind == OutcomeKind::value) {
          EXPECT_EQ(o.value.view(), k.text) << where;
        }
        // Nothing else changed.
        for (const auto& w : d.history) {
          EXPECT_TRUE(w.number == k.parameter) << where << " wrote " << w.number;
        }
        // The next clean telegram works (after a refusal the latch is read first).
        bus.line.set_filter(nullptr);
        d.siof = 0;
        const Outcome again = bus.run(k.request);
        EXPECT_TRUE(again.kind == OutcomeKind::value || again.kind == OutcomeKind::acknowledged ||
                    again.kind == OutcomeKind::sent)
            << where << " then " << describe(again);
      }
    }
  }
  EXPECT_GT(runs, 1000);
}

TEST(Interruptions, InsertedEotOrGarbageBeforeEveryCharacterOnTheReceiver) {
  struct Sel {
    Family family;
    unsigned code;
    const char* value;
    unsigned parameter;
    std::uint32_t new_value;
  };
  const Sel sels[] = {{Family::standard, 105, "03E8", 5, 0x3E8},
                      {Family::standard, 103, "0080", 3, 0x80},  // BCC 05H (ENQ)
                      {Family::enhanced, 20428, "84FA4000", 428, 0x84FA4000},
                      {Family::enhanced, 20416, "1", 416, 1}};
  const std::uint8_t inserts[] = {kEot, kStx, kEtx, kEnq, kAck, kNak, kGarbled, 0x00, 'X', '0',
                                  '=',  0x41};
  for (const Sel& s : sels) {
    const Frame f = encode_select(1, make_code(s.code), make_value(s.value));
    for (std::size_t at = 0; at <= f.size; ++at) {
      for (const std::uint8_t ins : inserts) {
        auto d = make(s.family);
        const std::uint32_t old = d.value_of(s.parameter);
        Receiver rx(d, 1);
        for (std::size_t i = 0; i < f.size; ++i) {
          if (i == at) rx.receive(ins, Time{0});
          rx.receive(f.bytes[i], Time{0});
        }
        if (at == f.size) rx.receive(ins, Time{0});
        const auto answer = test::to_vector(rx.take_answer(Time{1s}));
        rx.receive(kEot, Time{1s});
        const std::uint32_t now = d.value_of(s.parameter);
        const std::string where = std::to_string(s.code) + " insert " + std::to_string(ins) +
                                  " before " + std::to_string(at);
        EXPECT_TRUE(now == old || now == s.new_value) << where;
        EXPECT_LE(d.history.size(), 1U) << where;
        if (!answer.empty() && answer[1] == kAck) {
          EXPECT_EQ(now, s.new_value) << where;
        }
        // Recovery.
        d.siof = 0;
        for (std::size_t i = 0; i < f.size; ++i) rx.receive(f.bytes[i], Time{2s});
        const auto again = test::to_vector(rx.take_answer(Time{3s}));
        ASSERT_EQ(again.size(), 2U) << where;
        EXPECT_EQ(again[1], kAck) << where;
        EXPECT_EQ(d.value_of(s.parameter), s.new_value) << where;
      }
    }
  }
}

}  // namespace
}  // namespace ibs::lustbus
