#include "ibs/devices/dfs1/frame_text.hpp"

#include <cstdio>
#include <string_view>
#include <vector>

#include "ibs/devices/dfs1/parameters.hpp"
#include "ibs/devices/dfs1/status.hpp"
#include "ibs/dfs1/frame.hpp"

namespace ibs::devices::dfs1 {

namespace {

namespace proto = ::ibs::dfs1;

std::string hex2(unsigned v) {
  char b[8];
  std::snprintf(b, sizeof b, "%02X", v & 0xFFU);
  return b;
}

std::string bytes_text(std::span<const std::uint8_t> bytes) {
  std::string s;
  for (const std::uint8_t b : bytes) s += (s.empty() ? "" : " ") + hex2(b);
  return s;
}

std::string flags_text(const std::vector<std::string_view>& flags) {
  if (flags.empty()) return "none";
  std::string s;
  for (const auto f : flags) s += (s.empty() ? "" : " ") + std::string(f);
  return s;
}

// "parameter 6 (maximum motor speed)".
std::string parameter_text(std::uint8_t number) {
  const ParameterInfo* p = find_parameter(number);
  return "parameter " + std::to_string(number) + (p != nullptr ? " (" + std::string(p->name) + ")" : "");
}

std::string value_text(std::uint8_t parameter, std::uint32_t v) {
  const ParameterInfo* p = find_parameter(parameter);
  return std::to_string(v) + (p != nullptr && !p->unit.empty() ? " " + std::string(p->unit) : "");
}

std::string request_text(const proto::Frame& f) {
  const proto::CommandInfo* c = proto::find_command(f.code);
  if (c == nullptr) return "command " + hex2(f.code) + "H (no DFS-1 command)" + (f.size > 0 ? ", data " + bytes_text(f.payload()) : "");
  std::string s(c->name);
  if (f.size != c->request_size) {
    return s + ", " + std::to_string(f.size) + " data byte(s) where it takes " + std::to_string(c->request_size) +
           (f.size > 0 ? ": " + bytes_text(f.payload()) : "");
  }
  switch (c->command) {
    case proto::Command::set_speed:
    case proto::Command::set_and_execute_speed:
      return s + " " + std::to_string(proto::to_signed(f.value_at(0))) + " rpm";
    case proto::Command::read_parameter:
      return "read " + parameter_text(f.data[0]);
    case proto::Command::write_parameter:
      return "write " + parameter_text(f.data[0]) + " = " + value_text(f.data[0], f.value_at(1));
    case proto::Command::read_analog_input:
    case proto::Command::read_analog_output:
    case proto::Command::read_digital_input:
    case proto::Command::read_digital_output:
      return s + " channel " + std::to_string(f.data[0]);
    case proto::Command::write_analog_output:
    case proto::Command::write_digital_output:
      return s + " channel " + std::to_string(f.data[0]) + " = " + std::to_string(f.value_at(1));
    case proto::Command::set_operational_mode:
      return s + ", inputs " + hex2(f.data[2]) + hex2(f.data[3]) + "H";
    case proto::Command::application_mode:
      return s + " " + (f.data[0] == 1 ? "slave" : f.data[0] == 0 ? "master" : std::to_string(f.data[0])) +
             ", value " + std::to_string(f.value_at(1));
    default:
      return s;
  }
}

// An ACK's data by the command it answers.
std::string ack_text(const proto::Frame& f, std::optional<std::uint8_t> command, std::optional<std::uint8_t> parameter) {
  if (!command) return f.size > 0 ? "ACK, data " + bytes_text(f.payload()) + " (its request is not in the capture)" : "ACK";
  const proto::CommandInfo* c = proto::find_command(*command);
  if (c == nullptr || f.size != c->response_size) {
    return "ACK" + (f.size > 0 ? ", data " + bytes_text(f.payload()) : std::string());
  }
  switch (c->command) {
    case proto::Command::status:
      // D3: commanded, actual, load %, 00 00 ST2 ST1.
      return "ACK status: commanded " + std::to_string(proto::to_signed(f.value_at(0))) + " rpm, actual " +
             std::to_string(proto::to_signed(f.value_at(4))) + " rpm, load " + std::to_string(f.value_at(8)) +
             " %, ST2 " + hex2(f.data[14]) + "H (" + flags_text(st2_flags(f.data[14])) + "), ST1 " + hex2(f.data[15]) +
             "H (" + flags_text(st1_flags(f.data[15])) + ")";
    case proto::Command::read_parameter:
      return "ACK " + (parameter ? parameter_text(*parameter) + " = " + value_text(*parameter, f.value_at(0))
                                 : std::to_string(f.value_at(0)));
    case proto::Command::read_operational_mode:
      return "ACK inputs " + hex2(f.data[2]) + hex2(f.data[3]) + "H";
    case proto::Command::read_analog_input:
    case proto::Command::read_analog_output:
    case proto::Command::read_digital_input:
    case proto::Command::read_digital_output:
      return "ACK " + std::string(c->name) + " = " + std::to_string(f.value_at(0));
    default:
      return "ACK " + std::string(c->name);
  }
}

}  // namespace

std::string FrameExplainer::explain(bool from_host, std::span<const std::uint8_t> bytes) {
  proto::FrameDecoder d;
  std::optional<proto::Frame> frame;
  std::optional<proto::DecodeError> error;
  for (const std::uint8_t b : bytes) {
    const proto::DecodeResult r = d.push(b);
    if (r.status == proto::DecodeStatus::frame) {
      frame = d.frame();
      break;
    }
    if (r.status == proto::DecodeStatus::error) {
      error = r.error;
      break;
    }
  }
  if (!frame) {
    const std::string why = error ? std::string(proto::to_string(*error))
                            : d.in_frame() ? "cut before its DLE ETX CSM"
                                           : "no DLE STX: noise";
    return "broken frame (" + why + "): " + bytes_text(bytes);
  }
  const proto::Frame& f = *frame;
  const std::string uid = "UID " + std::to_string(f.uid) + (f.uid == proto::kGlobalUid ? " (every controller)" : "");
  if (from_host) {
    request_[f.uid] = f.code;
    parameter_[f.uid] = f.size > 0 ? std::optional<std::uint8_t>(f.data[0]) : std::nullopt;
    return uid + " " + request_text(f);
  }
  const std::optional<std::uint8_t> command = request_[f.uid];
  const std::optional<std::uint8_t> parameter = parameter_[f.uid];
  request_[f.uid].reset();
  if (f.is_nak()) {
    const std::uint8_t e = f.size > 0 ? f.data[0] : 0;
    return uid + " NAK " + hex2(e) + "H " + std::string(proto::error_name(e));
  }
  if (f.is_ack()) return uid + " " + ack_text(f, command, parameter);
  return uid + " sent " + request_text(f) + " (a controller answers ACK or NAK)";
}

}  // namespace ibs::devices::dfs1
