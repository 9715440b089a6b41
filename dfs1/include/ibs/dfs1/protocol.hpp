// The PowerTec DFS-1 binary protocol: control characters, commands, error codes, 4-byte values
// and the data length of every request and response (DFS-1 manual, manual section 6.0; the command
// list and error codes from ../shared/notes/public-facts.md, "PowerTec DFS-1"). The lengths the
// public pages leave open are decisions of docs/dfs1.md, "Decisions".
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace ibs::dfs1 {

// DFS-1 manual, "GENERAL DEFINITIONS".
inline constexpr std::uint8_t kStx = 0x02;
inline constexpr std::uint8_t kEtx = 0x03;
inline constexpr std::uint8_t kAck = 0x06;
inline constexpr std::uint8_t kNak = 0x15;
inline constexpr std::uint8_t kDle = 0x10;

// UID 01..FF address one controller; UID 00 is only for command 83, which no one answers (notes).
inline constexpr std::uint8_t kGlobalUid = 0x00;

enum class Command : std::uint8_t {
  status = 0x81,
  set_speed = 0x82,
  execute_speed = 0x83,
  set_and_execute_speed = 0x84,
  read_parameter = 0x85,
  write_parameter = 0x86,
  read_analog_input = 0x87,
  read_analog_output = 0x88,
  write_analog_output = 0x89,
  read_digital_input = 0x8A,
  read_digital_output = 0x8B,
  write_digital_output = 0x8C,
  set_operational_mode = 0x8D,
  read_operational_mode = 0x8E,
  application_mode = 0x8F,
};

// The NAK error codes (notes, "Error codes").
enum class ErrorCode : std::uint8_t {
  not_in_remote = 0x80,
  illegal_speed = 0x81,
  illegal_parameter_number = 0x82,
  illegal_parameter_value = 0x83,
  illegal_channel = 0x84,
  illegal_channel_value = 0x85,
  illegal_command = 0x86,
};

inline constexpr std::array<Command, 15> kAllCommands = {
    Command::status,
    Command::set_speed,
    Command::execute_speed,
    Command::set_and_execute_speed,
    Command::read_parameter,
    Command::write_parameter,
    Command::read_analog_input,
    Command::read_analog_output,
    Command::write_analog_output,
    Command::read_digital_input,
    Command::read_digital_output,
    Command::write_digital_output,
    Command::set_operational_mode,
    Command::read_operational_mode,
    Command::application_mode,
};

inline constexpr std::array<ErrorCode, 7> kAllErrorCodes = {
    ErrorCode::not_in_remote,
    ErrorCode::illegal_speed,
    ErrorCode::illegal_parameter_number,
    ErrorCode::illegal_parameter_value,
    ErrorCode::illegal_channel,
    ErrorCode::illegal_channel_value,
    ErrorCode::illegal_command,
};

// One row of the command table: the request's data bytes after CMD and the ACK's data bytes.
// Every value is 4 bytes (DFS-1 manual, note 3); a parameter or channel number is one byte before it
// (the command list's PRM, DTA, DIG, AMD fields). Status answers four 4-byte values (decision D3).
struct CommandInfo {
  Command command;
  std::string_view name;
  std::uint8_t request_size;
  std::uint8_t response_size;
};

inline constexpr std::array<CommandInfo, 15> kCommandTable = {{
    {Command::status, "status", 0, 16},
    {Command::set_speed, "set speed", 4, 0},
    {Command::execute_speed, "execute speed", 0, 0},
    {Command::set_and_execute_speed, "set and execute speed", 4, 0},
    {Command::read_parameter, "read parameter", 1, 4},
    {Command::write_parameter, "write parameter", 5, 0},
    {Command::read_analog_input, "read analog input", 1, 4},
    {Command::read_analog_output, "read analog output", 1, 4},
    {Command::write_analog_output, "write analog output", 5, 0},
    {Command::read_digital_input, "read digital input", 1, 4},
    {Command::read_digital_output, "read digital output", 1, 4},
    {Command::write_digital_output, "write digital output", 5, 0},
    {Command::set_operational_mode, "set operational mode", 4, 0},
    {Command::read_operational_mode, "read operational mode", 0, 4},
    {Command::application_mode, "application mode", 5, 0},
}};

// The row of a command byte, nullptr for a byte that is no DFS-1 command.
constexpr const CommandInfo* find_command(std::uint8_t code) {
  for (const auto& row : kCommandTable) {
    if (static_cast<std::uint8_t>(row.command) == code) return &row;
  }
  return nullptr;
}
constexpr const CommandInfo& command_info(Command c) {
  return *find_command(static_cast<std::uint8_t>(c));
}

std::string_view to_string(Command c);
// "not in remote", ...; "unknown error" for a code outside 80..86.
std::string_view error_name(std::uint8_t code);
constexpr std::optional<ErrorCode> to_error_code(std::uint8_t code) {
  if (code < 0x80 || code > 0x86) return std::nullopt;
  return static_cast<ErrorCode>(code);
}

// 4-byte values, most significant byte first (DFS-1 manual, note 3).
constexpr void put_u32(std::span<std::uint8_t, 4> out, std::uint32_t v) {
  out[0] = static_cast<std::uint8_t>(v >> 24);
  out[1] = static_cast<std::uint8_t>(v >> 16);
  out[2] = static_cast<std::uint8_t>(v >> 8);
  out[3] = static_cast<std::uint8_t>(v);
}
constexpr std::uint32_t get_u32(std::span<const std::uint8_t, 4> in) {
  return (std::uint32_t{in[0]} << 24) | (std::uint32_t{in[1]} << 16) | (std::uint32_t{in[2]} << 8) |
         std::uint32_t{in[3]};
}
// Speeds are signed (two's complement, reverse negative: decision D4).
constexpr std::int32_t to_signed(std::uint32_t v) {
  return static_cast<std::int32_t>(v);
}
constexpr std::uint32_t to_unsigned(std::int32_t v) {
  return static_cast<std::uint32_t>(v);
}

}  // namespace ibs::dfs1
