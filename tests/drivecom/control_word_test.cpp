// Seed 001, 5.1.2: the device control commands from bits 0-3 and 7 of the control word.
#include <gtest/gtest.h>

#include "ibs/drivecom/control_word.hpp"

namespace ibs::drivecom {
namespace {

// The command table of 5.1.2 written out bit by bit, independent of kCommandTable.
//   SHUTDOWN       X X 1 1 0
//   POWER-ON       X X 1 1 1
//   BLOCK POWER    X X X 0 X
//   EMERGENCY STOP X X 0 1 X
//   DISABLE        X 0 1 1 1
//   ENABLE         X 1 1 1 1
Command manual_command(unsigned w) {
  const bool b0 = (w & 1U) != 0, b1 = (w & 2U) != 0, b2 = (w & 4U) != 0, b3 = (w & 8U) != 0;
  if (!b1) return Command::block_power;
  if (!b2) return Command::emergency_stop;
  if (!b0) return Command::shutdown;
  return b3 ? Command::enable : Command::disable;
}

TEST(ControlWord, EveryWordDecodesToExactlyOneCommandOfTheManualTable) {
  for (unsigned w = 0; w <= 0xFFFF; ++w) {
    int matching_rows = 0;
    for (const auto& row : kCommandTable) matching_rows += (w & row.mask) == row.value ? 1 : 0;
    ASSERT_EQ(matching_rows, 1) << std::hex << w;
    ASSERT_EQ(decode_command(static_cast<Word>(w)), manual_command(w)) << std::hex << w;
  }
}

TEST(ControlWord, StartUpSequenceWordsOf534) {
  EXPECT_EQ(decode_command(0x0000), Command::block_power);
  EXPECT_EQ(decode_command(0x0006), Command::shutdown);
  EXPECT_EQ(decode_command(0x000F), Command::enable);
  EXPECT_EQ(command_word(Command::shutdown), 0x0006);
  EXPECT_EQ(command_word(Command::enable), 0x000F);
  for (const auto& row : kCommandTable) EXPECT_EQ(decode_command(command_word(row.command)), row.command);
}

TEST(ControlWord, CommandTransitionsAreThoseOf512) {
  using T = std::array<std::uint8_t, 4>;
  EXPECT_EQ(command_row(Command::shutdown).transitions, (T{2, 6, 8, 0}));
  EXPECT_EQ(command_row(Command::block_power).transitions, (T{7, 9, 10, 12}));
  EXPECT_EQ(command_row(Command::emergency_stop).transitions, (T{7, 10, 11, 0}));
  EXPECT_EQ(command_row(Command::disable).transitions, (T{3, 5, 0, 0}));
  EXPECT_EQ(command_row(Command::enable).transitions, (T{3, 4, 0, 0}));
}

TEST(ControlWord, ResetFaultIsTheRisingEdgeOfBit7NotItsLevel) {
  EXPECT_TRUE(reset_fault_edge(0x0000, 0x0080));
  EXPECT_TRUE(reset_fault_edge(0x0006, 0x0086));
  EXPECT_FALSE(reset_fault_edge(0x0080, 0x0080));
  EXPECT_FALSE(reset_fault_edge(0x0080, 0x0000));
  EXPECT_FALSE(reset_fault_edge(0x0000, 0x0000));
}

TEST(ControlWord, Vf1000BitsOf521) {
  const auto b = decode_vf1000_bits(0x8070);
  EXPECT_TRUE(b.ramp_enable);
  EXPECT_TRUE(b.ramp_run);
  EXPECT_TRUE(b.ramp_follow);
  EXPECT_TRUE(b.str);
  EXPECT_FALSE(b.stl);
  EXPECT_FALSE(b.s1ind);
  EXPECT_FALSE(b.s2ind);
  EXPECT_TRUE(decode_vf1000_bits(0x4000).stl);
  EXPECT_TRUE(decode_vf1000_bits(0x2000).s1ind);
  EXPECT_TRUE(decode_vf1000_bits(0x1000).s2ind);
  for (unsigned w = 0; w <= 0xFFFF; w += 0x10) {
    const auto masked = static_cast<Word>(w & 0xF070U);
    EXPECT_EQ(encode_vf1000_bits(decode_vf1000_bits(masked)), masked);
  }
}

TEST(ControlWord, Mc6000BitsOf531) {
  EXPECT_TRUE(decode_mc6000_bits(0x4000).os00);
  EXPECT_FALSE(decode_mc6000_bits(0x4000).os01);
  EXPECT_TRUE(decode_mc6000_bits(0x8000).os01);
}

TEST(ControlWord, ExplanationNamesCommandEdgeAndDeviceBits) {
  EXPECT_EQ(explain_control_word(DeviceType::mc6000, 0x000F, 0x0006), "000F POWER-ON/ENABLE");
  EXPECT_EQ(explain_control_word(DeviceType::mc6000, 0x0080, 0x0000), "0080 BLOCK POWER, RESET FAULT edge");
  EXPECT_EQ(explain_control_word(DeviceType::vf1000, 0x807F, 0x807F), "807F POWER-ON/ENABLE, STR");
  EXPECT_NE(explain_control_word(DeviceType::vf1000, 0x0106, 0).find("reserved bits 8-10"), std::string::npos);
}

}  // namespace
}  // namespace ibs::drivecom
