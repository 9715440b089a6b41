// DRIVECOM Profile 20 control word (INTERBUS manual 5.1.2). The device-specific bits belong to the
// drives (devices/vf1000/descriptor.hpp: 5.2.1, devices/mc6000/descriptor.hpp: 5.3.1).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "ibs/base/words.hpp"

namespace ibs::drivecom {

// The device control commands of 5.1.2 as decoded from bits 0-3. POWER-ON (X X 1 1 1) is carried
// by both `disable` (bit 3 = 0) and `enable` (bit 3 = 1): those words perform transition 3 in
// READY before DISABLE (5) or ENABLE (4) applies.
enum class Command : std::uint8_t {
  block_power,     // X X X 0 X   transitions 7, 9, 10, 12
  emergency_stop,  // X X 0 1 X   transitions 7, 10, 11
  shutdown,        // X X 1 1 0   transitions 2, 6, 8
  disable,         // X 0 1 1 1   POWER-ON (3) and DISABLE (5)
  enable,          // X 1 1 1 1   POWER-ON (3) and ENABLE (4)
};

// Bits of the control word (5.1.2).
namespace cw {
inline constexpr unsigned kPowerOn = 0;
inline constexpr unsigned kBlockPower = 1;  // 0 = block power requested
inline constexpr unsigned kEmergencyStop = 2;  // 0 = emergency stop requested
inline constexpr unsigned kEnableOperation = 3;
inline constexpr unsigned kResetFault = 7;  // acts on its 0 -> 1 edge
inline constexpr Word kReservedMask = 0x0700;  // bits 8-10, must be 0
// Bits the state machine owns; all others are mode-dependent or manufacturer-specific.
inline constexpr Word kDrivecomMask = 0x008F;
}  // namespace cw

// One row of the command table of 5.1.2: a command is `(word & mask) == value`, rows in priority
// order. The rows are disjoint and cover all of bits 0-3, so every word is exactly one command.
struct CommandRow {
  Command command;
  Word mask;
  Word value;
  std::array<std::uint8_t, 4> transitions;  // 0 = unused slot
  std::string_view name;
};

inline constexpr std::array<CommandRow, 5> kCommandTable{{
    {Command::block_power, 0x0002, 0x0000, {7, 9, 10, 12}, "BLOCK POWER"},
    {Command::emergency_stop, 0x0006, 0x0002, {7, 10, 11, 0}, "EMERGENCY STOP"},
    {Command::shutdown, 0x0007, 0x0006, {2, 6, 8, 0}, "SHUTDOWN"},
    {Command::disable, 0x000F, 0x0007, {3, 5, 0, 0}, "POWER-ON/DISABLE"},
    {Command::enable, 0x000F, 0x000F, {3, 4, 0, 0}, "POWER-ON/ENABLE"},
}};

namespace detail {
// Bits 0-3 -> command, derived once from kCommandTable (the table stays the only source).
constexpr std::array<Command, 16> make_command_lut() {
  std::array<Command, 16> lut{};
  for (unsigned bits = 0; bits < 16; ++bits) {
    for (const auto& row : kCommandTable) {
      if ((bits & row.mask) == row.value) {
        lut[bits] = row.command;
        break;
      }
    }
  }
  return lut;
}
inline constexpr std::array<Command, 16> kCommandLut = make_command_lut();
}  // namespace detail

constexpr Command decode_command(Word control) { return detail::kCommandLut[control & 0x000FU]; }

constexpr const CommandRow& command_row(Command c) {
  return kCommandTable[static_cast<std::size_t>(c)];
}

constexpr std::string_view to_string(Command c) { return command_row(c).name; }

// The canonical control word of a command (bits 0-3 only), as the master sends it.
constexpr Word command_word(Command c) {
  switch (c) {
    case Command::block_power: return 0x0000;
    case Command::emergency_stop: return 0x0002;
    case Command::shutdown: return 0x0006;
    case Command::disable: return 0x0007;
    case Command::enable: return 0x000F;
  }
  return 0x0000;
}

constexpr bool reset_fault_edge(Word previous, Word current) {
  return !bit(previous, cw::kResetFault) && bit(current, cw::kResetFault);
}

// A control word in words as far as the profile defines it: the command, the reset-fault bit and
// reserved bits, e.g. "000F POWER-ON/ENABLE" or "0080 BLOCK POWER, RESET FAULT edge". `previous`
// tells the edge. The device bits (4-6, 11-15) are the drive's: its descriptor appends them.
std::string explain_control_word(Word control, Word previous);

}  // namespace ibs::drivecom
