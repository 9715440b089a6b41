// The inverter side of the parameter channel: the cycle tables of the INTERBUS manual 4.1.3 fed word by
// word, every NAK path of 4.1.4 with its 85-SIOF bit and the clearing read, power-on (6.1), the
// EEPROM rule (4.1.3.2), parameter numbers above FFH, and values never half-written.
#include "ibs/vf1000_channel/server.hpp"

#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "ibs/devices/vf1000/channel.hpp"
#include "ibs/devices/vf1000/parameters.hpp"

namespace {

using namespace ibs::vf1000_channel;
using namespace ibs::drive;
using namespace ibs::devices::vf1000;
using ibs::Error;
using ibs::ErrorCode;
using ibs::Time;
using ibs::Word;
using namespace std::chrono_literals;

// What a step returned and reported.
struct Answer {
  Word to_master = 0;
  ServerEvent event;
};

// The inverter with a clock; each step is one processing step.
struct Inverter {
  explicit Inverter(ServerStart start = ServerStart::operational)
      : s(server_config(), start, Time{0}, parameters()) {}
  Server s;
  Time now{0};
  bool power_stage_enabled = false;
  Answer last;

  Word step(Word m) {
    now += 16400us;
    last.to_master = s.step(m, now, power_stage_enabled);
    last.event = s.last_event();
    return last.to_master;
  }
  // Feeds the m2s column of a cycle table (rows 0..n-1) and returns the s2m column of rows
  // 1..n, which by the timing convention answers the row before.
  std::vector<Word> answers(const std::vector<Word>& m2s) {
    std::vector<Word> out;
    for (Word m : m2s) out.push_back(step(m));
    return out;
  }
};

// A conforming master's value inquiry, word by word; nullopt on NAK.
std::optional<Word> inquire(Inverter& inv, std::uint16_t number) {
  const Word first = inv.step(master_start_word(true, Code::value_inquiry, number));
  if (inverter_nak(first)) {
    EXPECT_EQ(inv.step(kMasterIdleWord), kInverterWaitWord);
    return std::nullopt;
  }
  EXPECT_EQ(first & 0xFF00, 0xA000) << std::hex << first;
  const Word second = inv.step(master_word(false, Code::value_inquiry, 0, 0));
  EXPECT_EQ(second & 0xFF00, 0x8800) << std::hex << second;
  EXPECT_EQ(inv.step(kMasterIdleWord), kInverterWaitWord);
  return ibs::make_word(ibs::low_byte(first), ibs::low_byte(second));
}

// A conforming master's value transfer; returns the inverter's last word (ACK or NAK) and the
// event that came with it.
Answer transfer(Inverter& inv, std::uint16_t number, Word value) {
  Word w = inv.step(master_start_word(true, Code::value_transfer, number));
  Answer last = inv.last;
  if (!inverter_nak(w)) {
    EXPECT_EQ(w, 0xA000);
    w = inv.step(master_word(false, Code::value_transfer, 0, ibs::high_byte(value)));
    last = inv.last;
    if (!inverter_nak(w)) {
      EXPECT_EQ(w, 0x8000);
      inv.step(master_word(true, Code::value_transfer, 0, ibs::low_byte(value)));
      last = inv.last;
    }
  }
  EXPECT_EQ(inv.step(kMasterIdleWord), kInverterWaitWord);
  return last;
}

TEST(ServerCycleTables, ValueInquiryAnswersTheRowsOf41311) {
  Inverter inv;
  EXPECT_EQ(inv.s.output(), 0x8000);  // row 0
  EXPECT_EQ(inv.answers({0x0000, 0x2416, 0x2416, 0x0400, 0x0400, 0x0000}),
            (std::vector<Word>{0x8000, 0xA003, 0xA003, 0x88E8, 0x88E8, 0x8000}));
  EXPECT_EQ(inv.s.state(), ServerState::wait);
}

TEST(ServerCycleTables, ValueInquiryNakOnMissingParameterLeavesNoSiofEntry) {
  Inverter inv;
  EXPECT_EQ(inv.answers({0x0000, 0x2428, 0x2428, 0x0000}),
            (std::vector<Word>{0x8000, 0xB000, 0xB000, 0x8000}));
  EXPECT_EQ(inv.s.siof(), 0);  // "Faulty value inquiries bring about no entry" (4.1.4)
}

TEST(ServerCycleTables, ValueTransferTakesEffectOnlyAfterItsLastByte) {
  Inverter inv;
  const std::vector<Word> m2s = {0x0000, 0x2816, 0x2816, 0x0801, 0x0801, 0x28F4, 0x28F4, 0x0000};
  const std::vector<Word> s2m = {0x8000, 0xA000, 0xA000, 0x8000, 0x8000, 0xA800, 0xA800, 0x8000};
  for (std::size_t k = 0; k < m2s.size(); ++k) {
    EXPECT_EQ(inv.step(m2s[k]), s2m[k]) << "row " << k + 1;
    const Word expected = k < 5 ? 0x03E8 : 0x01F4;
    EXPECT_EQ(inv.s.value(pnr::kFmax1), expected) << "after row " << k + 1;
    if (k == 5) {
      EXPECT_EQ(inv.last.event.kind, ServerEvent::Kind::value_written);
      EXPECT_EQ(inv.last.event.number, pnr::kFmax1);
      EXPECT_EQ(inv.last.event.value, 0x01F4);
    }
  }
}

TEST(ServerCycleTables, DescriptionScanSendsTheCorrectedRowsOf41331) {
  Inverter inv;
  // Rows 0..37 of the master column: 0000, 2C2D twice, then pairs 0C00 0C00 / 2C00 2C00 ..., 0000.
  std::vector<Word> m2s = {0x0000, 0x2C2D, 0x2C2D};
  bool toggle = false;
  for (int byte = 1; byte < 18; ++byte) {
    const Word w = toggle ? 0x2C00 : 0x0C00;
    m2s.push_back(w);
    m2s.push_back(w);
    toggle = !toggle;
  }
  m2s.push_back(0x0000);
  const std::vector<std::uint8_t> bytes = {'V', 'B', '2', ' ',  ' ',  '%',  ' ',  ' ',  ' ',
                                           ' ', '2', '2', 0x00, 0x00, 0x01, 0xF4, 0x00, 0xA0};
  std::vector<Word> s2m = {0x8000};
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const Word flags = i == 17 ? 0x8800 : (i % 2 == 0 ? 0xA000 : 0x8000);
    s2m.push_back(static_cast<Word>(flags | bytes[i]));
    s2m.push_back(static_cast<Word>(flags | bytes[i]));
  }
  s2m.push_back(0x8000);
  ASSERT_EQ(m2s.size(), 38U);  // rows 0..37 drive the answers of rows 1..38
  EXPECT_EQ(inv.answers(m2s), s2m);
  EXPECT_EQ(inv.s.siof(), 0);
}

TEST(ServerRepeats, WithoutAToggleChangeTheAnswerStaysAndNothingAdvances) {
  Inverter inv;
  EXPECT_EQ(inv.step(0x2416), 0xA003);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(inv.step(0x2416), 0xA003);
  EXPECT_EQ(inv.step(0x0400), 0x88E8);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(inv.step(0x0400), 0x88E8);
}

TEST(ServerNak, TransferToMissingParameterSetsSiofBit5AndReadingClearsIt) {
  Inverter inv;
  const Answer r = transfer(inv, 40, 1);
  EXPECT_EQ(r.to_master, 0xB000);  // refused on receipt of the PNR
  EXPECT_EQ(r.event.reason, NakReason::no_parameter);
  EXPECT_EQ(r.event.siof_set, 0x20);
  EXPECT_EQ(inv.s.siof(), 0x20);
  EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0020);
  EXPECT_EQ(inv.s.siof(), 0);
  EXPECT_EQ(transfer(inv, pnr::kFmax1, 0x01F4).to_master, 0xA800);
}

TEST(ServerNak, TransferToReadOnlyParameterSetsSiofBit6) {
  Inverter inv;
  const Answer r = transfer(inv, pnr::kIbsta, 0x0437);
  EXPECT_EQ(r.to_master, 0xB000);
  EXPECT_EQ(r.event.reason, NakReason::no_change);
  EXPECT_EQ(inv.s.siof(), 0x40);
  EXPECT_EQ(inv.s.value(pnr::kIbsta), 0);
  EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0040);
  EXPECT_EQ(inv.s.siof(), 0);
}

TEST(ServerNak, EepromTransferWithPowerStageEnabledSetsSiofBit6) {
  Inverter inv;
  inv.power_stage_enabled = true;
  const Answer r = transfer(inv, pnr::kIbWd, 500);
  EXPECT_EQ(r.to_master, 0xB000);
  EXPECT_EQ(r.event.reason, NakReason::no_change);
  EXPECT_EQ(inv.s.siof(), 0x40);
  EXPECT_EQ(inv.s.value(pnr::kIbWd), 200);
  EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0040);
  inv.power_stage_enabled = false;
  EXPECT_EQ(transfer(inv, pnr::kIbWd, 500).to_master, 0xA800);
  EXPECT_EQ(inv.s.value(pnr::kIbWd), 500);
}

TEST(ServerNak, PowerStageEnabledDuringAnEepromTransferRefusesItsLastByte) {
  Inverter inv;
  EXPECT_EQ(inv.step(master_start_word(true, Code::value_transfer, pnr::kIbWd)), 0xA000);
  EXPECT_EQ(inv.step(master_word(false, Code::value_transfer, 0, 0x01)), 0x8000);
  inv.power_stage_enabled = true;
  EXPECT_EQ(inv.step(master_word(true, Code::value_transfer, 0, 0xF4)), 0xB000);
  EXPECT_EQ(inv.last.event.reason, NakReason::no_change);
  EXPECT_EQ(inv.s.siof(), 0x40);
  EXPECT_EQ(inv.s.value(pnr::kIbWd), 200);
}

TEST(ServerNak, EepromRamVariableIsWritableWithPowerStageEnabled) {
  Inverter inv;
  inv.power_stage_enabled = true;
  EXPECT_EQ(transfer(inv, pnr::kFssio, 463).to_master, 0xA800);  // 23.15 Hz
  EXPECT_EQ(inv.s.value(pnr::kFssio), 463);
  inv.s.power_on(inv.now);  // only RAM had it (4.1.3.3, category '3')
  EXPECT_EQ(inv.s.value(pnr::kFssio), 0);
}

TEST(ServerNak, ValueOutOfRangeSetsSiofBit7AndLeavesTheValue) {
  Inverter inv;
  for (const Word v : {Word{0x5000}, Word{0xFFFF}, Word{20000}}) {
    const Answer r = transfer(inv, pnr::kFmax1, v);
    EXPECT_EQ(r.to_master, 0xB000) << v;  // refused with its last byte, toggle 1
    EXPECT_EQ(r.event.reason, NakReason::invalid_value);
    EXPECT_EQ(r.event.siof_set, 0x80);
    EXPECT_EQ(inv.s.value(pnr::kFmax1), 0x03E8);
    EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0080);
  }
  EXPECT_EQ(transfer(inv, pnr::kIbWd, 7).event.reason, NakReason::invalid_value);  // below min 8
  EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0080);
  EXPECT_EQ(transfer(inv, pnr::kCntl, 0x0100).event.reason, NakReason::invalid_value);
  EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0080);
  EXPECT_EQ(transfer(inv, pnr::kFmax1, 19999).to_master, 0xA800);  // the maximum itself
}

TEST(ServerNak, UnintendedControlBitsInATransferSetSiofBit3) {
  Inverter inv;
  EXPECT_EQ(inv.step(0x2816), 0xA000);
  EXPECT_EQ(inv.step(0x4801), 0x9000);  // bit 6 set in the DAT1 word: NAK, toggle 0
  EXPECT_EQ(inv.last.event.reason, NakReason::unintended_control_bits);
  EXPECT_EQ(inv.s.siof(), 0x08);
  EXPECT_EQ(inv.step(0x0000), 0x8000);
  EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0008);
  // CODE changed inside the transfer (2 -> 1).
  EXPECT_EQ(inv.step(0x2816), 0xA000);
  EXPECT_EQ(inv.step(0x0801), 0x8000);
  EXPECT_EQ(inv.step(0x24F4), 0xB000);
  EXPECT_EQ(inv.s.siof(), 0x08);
  EXPECT_EQ(inv.step(0x0000), 0x8000);
  EXPECT_EQ(inv.s.value(pnr::kFmax1), 0x03E8);
  // Bit 7 in the start word of a transfer.
  EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0008);
  EXPECT_EQ(inv.step(0xA816), 0xB000);
  EXPECT_EQ(inv.s.siof(), 0x08);
}

TEST(ServerNak, UnintendedControlBitsInAnInquiryLeaveNoSiofEntry) {
  Inverter inv;
  EXPECT_EQ(inv.step(0x2416), 0xA003);
  EXPECT_EQ(inv.step(0x0800), 0x9000);  // CODE 1 -> 2 inside the inquiry
  EXPECT_EQ(inv.last.event.reason, NakReason::unintended_control_bits);
  EXPECT_EQ(inv.step(0x0000), 0x8000);
  EXPECT_EQ(inv.step(0x6416), 0xB000);  // bit 6 in the start word
  EXPECT_EQ(inv.step(0x0000), 0x8000);
  EXPECT_EQ(inv.s.siof(), 0);
}

TEST(ServerNak, UndefinedCodesAreRefusedWithoutSiofEntry) {
  Inverter inv;
  for (unsigned code = 4; code <= 7; ++code) {
    const auto w = static_cast<Word>(0x2000U | (code << 10U) | 0x16U);
    EXPECT_EQ(inv.step(w), 0xB000) << code;
    EXPECT_EQ(inv.last.event.reason, NakReason::undefined_code);
    EXPECT_EQ(inv.step(0x0000), 0x8000);
  }
  EXPECT_EQ(inv.s.siof(), 0);
}

TEST(ServerNak, ToggleAfterTheLastByteIsRefusedUntilCode0) {
  Inverter inv;
  EXPECT_EQ(inv.step(0x2416), 0xA003);
  EXPECT_EQ(inv.step(0x0400), 0x88E8);
  EXPECT_EQ(inv.step(0x2400), 0xB000);  // a third byte asked for
  EXPECT_EQ(inv.last.event.reason, NakReason::after_end);
  EXPECT_EQ(inv.step(0x0000), 0x8000);
  EXPECT_EQ(inv.s.siof(), 0);
}

TEST(ServerNak, WhileSiofIsNonZeroTransfersAreRefusedAndInquiriesAnswered) {
  Inverter inv;
  inv.s.raise_siof(siof_mask(SiofBit::watchdog));
  const Answer r = transfer(inv, pnr::kFmax1, 0x01F4);
  EXPECT_EQ(r.to_master, 0xB000);
  EXPECT_EQ(r.event.reason, NakReason::siof_pending);
  EXPECT_EQ(r.event.siof_set, 0);  // no new bit
  EXPECT_EQ(inv.s.siof(), 0x02);
  EXPECT_EQ(inquire(inv, pnr::kFmax1), 0x03E8);
  EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0002);
  EXPECT_EQ(transfer(inv, pnr::kFmax1, 0x01F4).to_master, 0xA800);
}

TEST(ServerSiof, ReadingClearsOnlyTheBitsItReturned) {
  Inverter inv;
  inv.s.raise_siof(0x80);
  EXPECT_EQ(inv.step(master_start_word(true, Code::value_inquiry, pnr::kSiof)), 0xA000);
  inv.s.raise_siof(0x02);  // set while the inquiry runs
  EXPECT_EQ(inv.step(master_word(false, Code::value_inquiry, 0, 0)), 0x8880);
  EXPECT_EQ(inv.s.siof(), 0x02);
  EXPECT_EQ(inv.step(0x0000), 0x8000);
  EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0002);
  EXPECT_EQ(inv.s.siof(), 0);
}

TEST(ServerSiof, AnInquiryOf85AbortedBeforeItsLastByteClearsNothing) {
  Inverter inv;
  inv.s.raise_siof(0x80);
  EXPECT_EQ(inv.step(master_start_word(true, Code::value_inquiry, pnr::kSiof)), 0xA000);
  EXPECT_EQ(inv.step(0x0000), 0x8000);
  EXPECT_EQ(inv.last.event.kind, ServerEvent::Kind::aborted);
  EXPECT_EQ(inv.s.siof(), 0x80);
}

TEST(ServerPowerOn, InitialisesFourSecondsWithResetDistinction0) {
  Inverter inv(ServerStart::power_on);
  EXPECT_EQ(inv.s.output(), 0x0000);
  EXPECT_TRUE(inv.s.initialising(Time{0}));
  EXPECT_EQ(inv.s.ready_at(), Time{4s});
  while (inv.now + 16400us < Time{4s}) {
    EXPECT_EQ(inv.step(0x2416), 0x0000);  // requests are ignored meanwhile
    EXPECT_TRUE(inv.s.initialising(inv.now));
  }
  EXPECT_EQ(inv.step(0x0000), 0x8000);
  EXPECT_EQ(inv.last.event.kind, ServerEvent::Kind::initialised);
  EXPECT_FALSE(inv.s.initialising(inv.now));
  EXPECT_EQ(inv.s.siof(), 0x01);
}

TEST(ServerPowerOn, RefusesTransfersUntil85IsRead) {
  Inverter inv(ServerStart::initialised);
  EXPECT_EQ(inv.s.siof(), 0x01);
  const Answer r = transfer(inv, pnr::kFmax1, 0x01F4);
  EXPECT_EQ(r.to_master, 0xB000);
  EXPECT_EQ(r.event.reason, NakReason::siof_pending);
  EXPECT_EQ(inv.s.siof(), 0x01);
  EXPECT_EQ(inquire(inv, pnr::kFmax1), 0x03E8);  // inquiries are not restricted
  EXPECT_EQ(inv.step(master_start_word(true, Code::description_scan, pnr::kVb2)), 0xA056);
  EXPECT_EQ(inv.step(kMasterIdleWord), kInverterWaitWord);  // nor are description scans (D8)
  EXPECT_EQ(inquire(inv, pnr::kSiof), 0x0001);
  EXPECT_EQ(inv.s.siof(), 0);
  EXPECT_EQ(transfer(inv, pnr::kFmax1, 0x01F4).to_master, 0xA800);
}

TEST(ServerPowerOn, RestartKeepsEepromValuesAndResetsRamValues) {
  Inverter inv;
  EXPECT_EQ(transfer(inv, pnr::kFmax1, 0x01F4).to_master, 0xA800);
  EXPECT_EQ(transfer(inv, pnr::kIcntl, 0x000F).to_master, 0xA800);
  inv.s.power_on(inv.now);
  EXPECT_EQ(inv.step(0x0000), 0x0000);
  EXPECT_EQ(inv.s.value(pnr::kFmax1), 0x01F4);
  EXPECT_EQ(inv.s.value(pnr::kIcntl), 0);
  EXPECT_EQ(inv.s.siof(), 0x01);
}

TEST(ServerHalfWrite, Code0AfterTheHighByteDropsTheTransfer) {
  Inverter inv;
  EXPECT_EQ(inv.step(0x2816), 0xA000);
  EXPECT_EQ(inv.step(0x0801), 0x8000);
  EXPECT_EQ(inv.step(0x0000), 0x8000);
  EXPECT_EQ(inv.last.event.kind, ServerEvent::Kind::aborted);
  EXPECT_EQ(inv.last.event.code, Code::value_transfer);
  EXPECT_EQ(inv.s.value(pnr::kFmax1), 0x03E8);
  // A new telegram starts from its PNR; the dropped high byte is not reused.
  EXPECT_EQ(inv.step(0x2816), 0xA000);
  EXPECT_EQ(inv.step(0x0800), 0x8000);
  EXPECT_EQ(inv.step(0x2864), 0xA800);
  EXPECT_EQ(inv.s.value(pnr::kFmax1), 0x0064);
}

// Issue 9, defect 5: 85-SIOF is checked where the value is taken, not only at the PNR.
TEST(ServerNak, SiofSetBetweenThePnrAndTheValueRefusesTheTransfer) {
  for (const int after_row : {1, 2}) {  // after the PNR, after the high byte
    Inverter inv;
    EXPECT_EQ(inv.step(0x2816), 0xA000);  // PNR 22, accepted: 85-SIOF is 0
    if (after_row == 1) inv.s.raise_siof(siof_mask(SiofBit::watchdog));
    EXPECT_EQ(inv.step(0x0801), 0x8000);  // high byte
    if (after_row == 2) inv.s.raise_siof(siof_mask(SiofBit::watchdog));
    const Word answer = inv.step(0x28F4);  // low byte: here the value would take effect
    EXPECT_TRUE(inverter_nak(answer)) << std::hex << answer;
    EXPECT_EQ(inv.last.event.kind, ServerEvent::Kind::nak);
    EXPECT_EQ(inv.last.event.reason, NakReason::siof_pending);
    EXPECT_EQ(inv.s.value(pnr::kFmax1), 0x03E8) << "the value must not change";
    EXPECT_EQ(inv.s.siof(), siof_mask(SiofBit::watchdog)) << "the refusal adds no cause of its own";
  }
}

TEST(ServerHalfWrite, RestartAfterTheHighByteDropsTheTransfer) {
  Inverter inv;
  EXPECT_EQ(inv.step(0x2816), 0xA000);
  EXPECT_EQ(inv.step(0x0801), 0x8000);
  inv.s.power_on(inv.now);
  EXPECT_EQ(inv.step(0x28F4), 0x0000);
  EXPECT_EQ(inv.s.value(pnr::kFmax1), 0x03E8);
  inv.now += 4s;
  // Back from initialisation, the held word (toggle 1, CODE 2) reads as a new telegram for
  // parameter F4H, and 85-SIOF's power-on bit refuses it: nothing of the old transfer survives.
  EXPECT_EQ(inv.step(0x28F4), 0xB000);
  EXPECT_EQ(inv.last.event.reason, NakReason::siof_pending);
  EXPECT_EQ(inv.step(0x0000), 0x8000);
  EXPECT_EQ(inv.s.value(pnr::kFmax1), 0x03E8);
}

TEST(ServerInquiry, TheValueIsTakenWholeWhenThePnrArrives) {
  Inverter inv;
  inv.s.set_value(pnr::kIbsta, 0x0237);
  EXPECT_EQ(inv.step(master_start_word(true, Code::value_inquiry, pnr::kIbsta)), 0xA002);
  inv.s.set_value(pnr::kIbsta, 0x0437);  // the device updates it between the two bytes
  EXPECT_EQ(inv.step(master_word(false, Code::value_inquiry, 0, 0)), 0x8837);
  EXPECT_EQ(inv.last.event.value, 0x0237);
}

TEST(ServerHighNumbers, ParametersAbove0FFHTravelInControlBits0And1) {
  Inverter inv;
  EXPECT_EQ(inquire(inv, pnr::kIbWd), 200);
  EXPECT_EQ(transfer(inv, pnr::kIbcod, 2).to_master, 0xA800);
  EXPECT_EQ(inv.s.value(pnr::kIbcod), 2);
  inv.s.set_value(pnr::kFist, 0xFFEC);
  EXPECT_EQ(inquire(inv, pnr::kFist), 0xFFEC);
  EXPECT_EQ(transfer(inv, pnr::kFdriv, 0x8000).to_master, 0xA800);  // -32768 is in range
  EXPECT_EQ(inquire(inv, 0x3FF), std::nullopt);
  EXPECT_EQ(inquire(inv, 0x116), std::nullopt);  // 16H with bit 8: not FMAX1
  // Description of 912-FIST: starts with 'F'.
  EXPECT_EQ(inv.step(master_start_word(true, Code::description_scan, pnr::kFist)), 0xA046);
}

TEST(ServerHighNumbers, NumberBitsInDataWordsAreIgnored) {
  Inverter inv;
  EXPECT_EQ(inv.step(master_start_word(true, Code::value_transfer, pnr::kIbWd)), 0xA000);
  EXPECT_EQ(inv.step(0x0B01), 0x8000);  // DAT1 01H with the number bits 11 still set
  EXPECT_EQ(inv.step(0x2B2C), 0xA800);  // DAT2 2CH
  EXPECT_EQ(inv.s.value(pnr::kIbWd), 0x012C);
}

TEST(ServerProg, WritingOneTo71LoadsTheFactorySettings) {
  Inverter inv;
  EXPECT_EQ(transfer(inv, pnr::kFmax1, 0x01F4).to_master, 0xA800);
  EXPECT_EQ(transfer(inv, pnr::kMode, 0).to_master, 0xA800);
  EXPECT_EQ(transfer(inv, pnr::kProg, kLoadDefaults).to_master, 0xA800);
  EXPECT_EQ(inv.s.value(pnr::kFmax1), 0x03E8);
  EXPECT_EQ(inv.s.value(pnr::kMode), 4);
  EXPECT_EQ(inv.s.value(pnr::kProg), 0);
  EXPECT_EQ(transfer(inv, pnr::kProg, 2).event.reason, NakReason::invalid_value);
}

TEST(ServerDeviceAccess, SetValueAndValueForTheDeviceModel) {
  Inverter inv;
  EXPECT_TRUE(inv.s.set_value(pnr::kIbsta, 0x0437));
  EXPECT_EQ(inv.s.value(pnr::kIbsta), 0x0437);
  EXPECT_FALSE(inv.s.set_value(40, 1));
  EXPECT_EQ(inv.s.value(40), std::nullopt);
  EXPECT_EQ(inv.s.value(pnr::kSiof), 0);
  inv.s.raise_siof(0x02);
  EXPECT_EQ(inv.s.value(pnr::kSiof), 0x02);
}

// Server::validate, the check the constructor throws by (docs/embedding.md, "An embedded build").
TEST(ServerConstruction, ValidateGivesTheCodeAndTheConstructorsMessage) {
  const auto thrown = [](std::span<const ParameterInfo> params) -> std::string {
    try {
      const Server s(ServerConfig{}, ServerStart::operational, Time{0}, params);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_FALSE(Server::validate(ibs::devices::vf1000::parameters()));
  EXPECT_EQ(thrown(ibs::devices::vf1000::parameters()), "");

  const ParameterInfo only{1, "MODE", "", Category::eeprom, DataType::usign8, 0, 4, 4, 1.0, ""};
  Error e = Server::validate({&only, 1});
  EXPECT_EQ(e.code, ErrorCode::table_lacks_siof);
  EXPECT_EQ(e.message,
            "vf1000_channel::Server: the parameter table has no 85-SIOF, which every value "
            "transfer depends "
            "on (INTERBUS manual 4.1.4)");
  EXPECT_EQ(e.message, thrown({&only, 1}));

  // A malformed table is refused as the table refuses it, before the 85-SIOF question.
  const std::array<ParameterInfo, 2> twice{only, only};
  e = Server::validate(twice);
  EXPECT_EQ(e.code, ErrorCode::table_number_repeated);
  EXPECT_EQ(e, ibs::drive::ParameterTable::validate(twice));
  EXPECT_EQ(e.message, thrown(twice));
}

TEST(ServerConstruction, RequiresSiofInTheTable) {
  const ParameterInfo only{1, "MODE", "", Category::eeprom, DataType::usign8, 0, 4, 4, 1.0, ""};
  try {
    const Server s(ServerConfig{}, ServerStart::operational, Time{0}, {&only, 1});
    ADD_FAILURE() << "a table without 85-SIOF was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("85-SIOF"), std::string::npos) << e.what();
  }
}

}  // namespace
