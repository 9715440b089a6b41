// INTERBUS manual 5.1.2: the device control commands from bits 0-3 and 7 of the control word.
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

}  // namespace
}  // namespace ibs::drivecom
