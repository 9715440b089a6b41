// Identifiers, telegram coding and data types against CANLust manual's examples, byte for byte.
#include <gtest/gtest.h>

#include <vector>

#include "ibs/canlust/data_types.hpp"
#include "ibs/canlust/errors.hpp"
#include "ibs/canlust/identifiers.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/canlust/telegrams.hpp"

namespace ibs::canlust {
namespace {

std::vector<std::uint8_t> bytes(const CanFrame& f) { return {f.data.begin(), f.data.begin() + f.dlc}; }
std::vector<std::uint8_t> wire(std::uint32_t v) {
  std::array<std::uint8_t, 4> b{};
  put_le32(b, v);
  return {b.begin(), b.end()};
}

// CAN-E1 / D1: the examples' identifiers for CDA 1 (7.1.2: control 663, status 883; 7.1.3:
// parameters 1103 / 1323; public-facts: logon 1545) come from step 2.
TEST(Identifiers, StepTwoGivesTheExamplesIdentifiersForCda1) {
  const IdentifierMap ids;  // the default
  EXPECT_EQ(ids.step, 2);
  EXPECT_EQ(ids.id(TelegramKind::control, 1), 663);
  EXPECT_EQ(ids.id(TelegramKind::status, 1), 883);
  EXPECT_EQ(ids.id(TelegramKind::parameter_request, 1), 1103);
  EXPECT_EQ(ids.id(TelegramKind::parameter_reply, 1), 1323);
  EXPECT_EQ(ids.id(TelegramKind::logon, 1), 1545);
  EXPECT_EQ(ids.id(TelegramKind::error, 1), 443);
  EXPECT_EQ(ids.id(TelegramKind::system, 7), 221);
}

TEST(Identifiers, StationZeroUsesTheBases) {
  const IdentifierMap ids;
  EXPECT_EQ(ids.id(TelegramKind::error, 0), 0x1B9);
  EXPECT_EQ(ids.id(TelegramKind::logon, 0), 0x607);
  EXPECT_EQ(ids.id(TelegramKind::control, 0), 0x295);
  EXPECT_EQ(ids.id(TelegramKind::status, 0), 0x371);
  EXPECT_EQ(ids.id(TelegramKind::parameter_request, 0), 0x44D);
  EXPECT_EQ(ids.id(TelegramKind::parameter_reply, 0), 0x529);
  EXPECT_EQ(kIdSystem, 0xDD);
}

TEST(Identifiers, StepOneOfTheTextIsOneSettingAway) {
  IdentifierMap ids;
  ids.step = 1;
  EXPECT_EQ(ids.id(TelegramKind::control, 1), 662);
  EXPECT_EQ(ids.id(TelegramKind::parameter_reply, 1), 1322);
  EXPECT_EQ(ids.classify(1322), (Classified{TelegramKind::parameter_reply, 1}));
  EXPECT_TRUE(ids.unambiguous());
}

TEST(Identifiers, BlocksTwoHundredTwentyApartHoldAddresses0To99AtStepTwo) {
  IdentifierMap ids;
  EXPECT_TRUE(ids.unambiguous());
  EXPECT_EQ(ids.id(TelegramKind::logon, 99), 1543 + 198);
  EXPECT_FALSE(ids.id(TelegramKind::logon, 100).has_value());
  ids.max_address = 110;  // 441 + 2 x 110 = 661: the error block runs into the control block
  EXPECT_FALSE(ids.unambiguous());
}

TEST(Identifiers, ClassifyInvertsIdForEveryKindAndAddress) {
  const IdentifierMap ids;
  for (const auto k : {TelegramKind::error, TelegramKind::logon, TelegramKind::control,
                       TelegramKind::status, TelegramKind::parameter_request,
                       TelegramKind::parameter_reply}) {
    for (unsigned a = 0; a <= 99; ++a) {
      const auto id = ids.id(k, static_cast<Address>(a));
      ASSERT_TRUE(id);
      EXPECT_EQ(ids.classify(*id), (Classified{k, static_cast<Address>(a)}));
    }
  }
  EXPECT_FALSE(ids.classify(664));  // odd offset at step 2
  EXPECT_FALSE(ids.classify(0x7FF));
  EXPECT_FALSE(ids.classify(100));
}

// 5.5.4: System Start is the broadcast 221 with data 01H; Stop 00H (decision D3).
TEST(SystemTelegram, StartIs221With01) {
  const auto f = encode_system(SystemCommand::start);
  EXPECT_EQ(f.id, 221);
  EXPECT_EQ(bytes(f), (std::vector<std::uint8_t>{0x01}));
  EXPECT_FALSE(f.rtr);
  EXPECT_EQ(decode_system(f).value, SystemCommand::start);
  EXPECT_EQ(bytes(encode_system(SystemCommand::stop)), (std::vector<std::uint8_t>{0x00}));
  EXPECT_EQ(decode_system(CanFrame::make(221, {0x02})).error, DecodeError::bad_value);
  auto r = f;
  r.rtr = true;
  EXPECT_EQ(decode_system(r).error, DecodeError::remote);
}

TEST(LogonTelegram, HasNoData) {
  const auto f = encode_logon(IdentifierMap{}, 1);
  EXPECT_EQ(f.id, 1545);
  EXPECT_EQ(f.dlc, 0);
}

// 7.1.2: "CDA 1 is to dwell in the ready for start state, reference value 10 rpm clockwise":
// 663: 00 00 00 00 0A 00 00 - printed with 7 bytes where 5.5.5 gives a DLC of 6 (CAN-E2).
TEST(ControlTelegram, ExampleOf712With7BytesDecodes) {
  const auto f = CanFrame::make(663, {0x00, 0x00, 0x00, 0x00, 0x0A, 0x00, 0x00});
  const ProcessLayout drivecom_q16 = *process_layout_for_cacnf(2);
  const auto d = decode_control(f, drivecom_q16);
  ASSERT_TRUE(d);
  EXPECT_EQ(d.value.word, 0x0000);
  EXPECT_EQ(d.value.reference, 10 * 65536);
  // Re-encoded with the nominal length of 5.5.5: the same six bytes.
  const auto e = encode_control(IdentifierMap{}, 1, drivecom_q16, d.value);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->dlc, 6);
  EXPECT_EQ(bytes(*e), (std::vector<std::uint8_t>{0x00, 0x00, 0x00, 0x00, 0x0A, 0x00}));
}

// public-facts: 20.5 Hz = 00 80 14 00 (Q16, Intel order).
TEST(ControlTelegram, Reference20p5HzIs00801400) {
  const auto f = encode_control(IdentifierMap{}, 1, *process_layout_for_cacnf(2),
                                {0x000F, q16_from_double(20.5)});
  ASSERT_TRUE(f);
  EXPECT_EQ(f->id, 663);
  EXPECT_EQ(bytes(*f), (std::vector<std::uint8_t>{0x0F, 0x00, 0x00, 0x80, 0x14, 0x00}));
}

TEST(ControlTelegram, Cacnf1Carries16BitReference) {
  const auto l = *process_layout_for_cacnf(1);
  const auto f = encode_control(IdentifierMap{}, 0, l, {0x0006, -100});
  ASSERT_TRUE(f);
  EXPECT_EQ(bytes(*f), (std::vector<std::uint8_t>{0x06, 0x00, 0x9C, 0xFF}));
  EXPECT_EQ(decode_control(*f, l).value.reference, -100);
  EXPECT_EQ(decode_control(CanFrame::make(661, {0x06, 0x00, 0x9C}), l).error, DecodeError::too_short);
}

TEST(StatusTelegram, DrivecomStartSequenceWordsOf712) {
  const auto l = *process_layout_for_cacnf(2);
  const IdentifierMap ids;
  const std::pair<std::uint16_t, std::vector<std::uint8_t>> rows[] = {
      {0x0240, {0x40, 0x02, 0x00, 0x00, 0x00, 0x00}},
      {0x0231, {0x31, 0x02, 0x00, 0x00, 0x00, 0x00}},
      {0x0237, {0x37, 0x02, 0x00, 0x00, 0x00, 0x00}}};
  for (const auto& [word, expect] : rows) {
    const auto f = encode_status(ids, 1, l, {word, 0});
    ASSERT_TRUE(f);
    EXPECT_EQ(f->id, 883);
    EXPECT_EQ(bytes(*f), expect);
  }
}

TEST(ProcessLayout, CacnfMapIsDecisionD5) {
  EXPECT_EQ(process_layout_for_cacnf(4)->mode, WordMode::easydrive);
  EXPECT_EQ(process_layout_for_cacnf(2)->mode, WordMode::drivecom);
  EXPECT_EQ(process_layout_for_cacnf(3)->actual, ValueWidth::int16q0);
  EXPECT_FALSE(process_layout_for_cacnf(0));
  EXPECT_FALSE(process_layout_for_cacnf(5));
}

// 6.2 / D6: error number, location, the reaction taken.
TEST(ErrorTelegram, Op2At170) {
  const auto f = encode_error(IdentifierMap{}, 1, {kErrorOp2, kLocationOp2Module, 1});
  ASSERT_TRUE(f);
  EXPECT_EQ(f->id, 443);
  EXPECT_EQ(bytes(*f), (std::vector<std::uint8_t>{0x10, 0xAA, 0x01}));
  EXPECT_EQ(decode_error(*f).value, (ErrorTelegram{16, 170, 1}));
  EXPECT_EQ(find_error(16)->name, "E-OP2");
  EXPECT_EQ(find_error(8)->name, "E-OTI");
  EXPECT_FALSE(find_error(200));
}

// 7.1.3: "Reply from CDA 1323: 68 01 00 96 01 00 00 00 - parameter 360-DISP = 406 (REFF)".
TEST(ParameterTelegram, ReplyExampleOf713) {
  const auto f = CanFrame::make(1323, {0x68, 0x01, 0x00, 0x96, 0x01, 0x00, 0x00, 0x00});
  EXPECT_EQ(IdentifierMap{}.classify(f.id), (Classified{TelegramKind::parameter_reply, 1}));
  const auto d = decode_parameter(f);
  ASSERT_TRUE(d);
  EXPECT_EQ(d.value, (ParameterTelegram{360, kStatusOk, 406, 0}));
}

// 7.1.3: "Send parameter 1103: 68 01 02 0E 00 00 00 ..." (the print stops there; byte 7, the
// block counter, is 0 for a single value).
TEST(ParameterTelegram, WriteRequestExampleOf713) {
  const auto f = encode_parameter_request(IdentifierMap{}, 1, {360, kModeWrite, 14, 0});
  ASSERT_TRUE(f);
  EXPECT_EQ(f->id, 1103);
  EXPECT_EQ(bytes(*f), (std::vector<std::uint8_t>{0x68, 0x01, 0x02, 0x0E, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(decode_parameter(CanFrame::make(1103, {0x68, 0x01, 0x02})).error, DecodeError::too_short);
}

TEST(ParameterChannel, ModesAreDecimal) {
  EXPECT_EQ(kModeRead, 5);
  EXPECT_EQ(kModeWrite, 2);
  EXPECT_EQ(kModeDescribe, 4);
  EXPECT_EQ(kModeStringWrite, 8);
  EXPECT_EQ(kModeStringRead, 0x0B);
  EXPECT_EQ(kModeListEnd, 0x10);
  EXPECT_EQ(describe_status(0xA0), "unknown parameter, impermissible value");
}

// 4.1.1 table 4.1 and p. 32.
TEST(DataTypes, Int32Q16TenPointFiveIs00800A00) {
  EXPECT_EQ(wire(wire_from_signed(q16_from_double(10.5))),
            (std::vector<std::uint8_t>{0x00, 0x80, 0x0A, 0x00}));
  EXPECT_DOUBLE_EQ(double_from_q16(q16_from_double(-3.25)), -3.25);
}

TEST(DataTypes, Fixpoint16TenPointZeroFiveIsC9000000) {
  EXPECT_EQ(wire(*fixpoint16_from_double(10.05)), (std::vector<std::uint8_t>{0xC9, 0x00, 0x00, 0x00}));
  EXPECT_FALSE(fixpoint16_from_double(3276.80));
  EXPECT_TRUE(fixpoint16_from_double(3276.75));
}

TEST(DataTypes, ErrStrucOp2At172After85HoursIs10AC5500) {
  const ErrStruc e{kErrorOp2, 172, 85};
  EXPECT_EQ(wire(wire_from_err_struc(e)), (std::vector<std::uint8_t>{0x10, 0xAC, 0x55, 0x00}));
  EXPECT_EQ(err_struc_from_wire(wire_from_err_struc(e)), e);
}

TEST(DataTypes, SmallTypesAreZeroOrSignFilled) {
  EXPECT_EQ(wire(wire_from_signed(-1)), (std::vector<std::uint8_t>{0xFF, 0xFF, 0xFF, 0xFF}));
  EXPECT_TRUE(wire_fits(DataType::int8, wire_from_signed(-128)));
  EXPECT_FALSE(wire_fits(DataType::int8, 0x80));  // 128 is not an INT8; -128 is FFFFFF80
  EXPECT_TRUE(wire_fits(DataType::usign8, 0xFF));
  EXPECT_FALSE(wire_fits(DataType::usign8, 0x100));
  EXPECT_FALSE(wire_fits(DataType::int16, 0x8000));
  EXPECT_TRUE(wire_fits(DataType::int16, 0xFFFF8000));
}

}  // namespace
}  // namespace ibs::canlust
