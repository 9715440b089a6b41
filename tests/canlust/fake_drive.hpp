// A small fake drive for the CANLust tests: it is not a CDA3000 (that is a wing's job) but just
// enough of one to run the protocol core against: a DRIVECOM-ish status that answers the
// manual's start sequence (7.1.2: control 0000 / 0006 / 000F -> status 0240 / 0231 / 0237), a
// few parameters of each data type, two string parameters, and a record of what the node asked.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "ibs/canlust/node.hpp"
#include "ibs/canlust/parameter_channel.hpp"

namespace ibs::canlust::test {

inline constexpr std::uint16_t kParamDisp = 360;      // 7.1.3: 360-DISP, value 406 (REFF)
inline constexpr std::uint16_t kParamText = 7;        // a writable string (fake)
inline constexpr std::uint16_t kParamName = 8;        // a read-only string (fake)
inline constexpr std::uint16_t kParamFixed = 9;       // read-only value
inline constexpr std::uint16_t kParamSlow = 150;      // 150-SAVE-like: reply after 300 ms
inline constexpr std::uint16_t kParamQ16 = 20;        // an INT32Q16 value
inline constexpr std::uint16_t kParamSigned = 21;     // an INT16 value

class FakeDrive final : public DriveProcess, public ParameterAccess {
 public:
  struct Executed {
    ControlTelegram t;
    Time at;
  };
  std::vector<Executed> executed;
  std::vector<WatchdogEvent> watchdog_events;
  std::vector<SystemState> states;
  std::uint16_t status_word = 0x0240;  // START INHIBIT, remote bit 9 (7.1.2)
  std::int32_t actual = 0;
  std::uint32_t disp = 406;
  std::int32_t q16 = 0;
  std::int32_t int16 = -5;
  std::array<char, kMaxStringBytes> text{};
  std::size_t text_len = 0;
  std::string_view name = "fake drive 1.0";

  FakeDrive() {
    executed.reserve(1024);
    watchdog_events.reserve(64);
    states.reserve(64);
    set_text("hello");
  }
  void set_text(std::string_view s) {
    text_len = std::min(s.size(), kMaxStringChars);
    std::copy_n(s.data(), text_len, text.data());
  }
  [[nodiscard]] std::string_view text_view() const { return {text.data(), text_len}; }

  // DriveProcess
  void execute(const ControlTelegram& t, Time now) override {
    executed.push_back({t, now});
    // The manual's DRIVECOM start (7.1.2): shutdown -> READY 31H, enable -> 37H (transitions 3
    // and 4 in one step); 0000 (disable voltage) -> START INHIBIT 40H. Bit 9: remote.
    switch (t.word) {
      case 0x0000: status_word = 0x0240; break;
      case 0x0006: status_word = 0x0231; break;
      case 0x0007: status_word = 0x0233; break;
      case 0x000F: status_word = 0x0237; break;
      default: break;
    }
    actual = t.reference;
  }
  StatusTelegram status(Time) override { return {status_word, actual}; }
  std::optional<ErrorTelegram> watchdog_expired(const WatchdogEvent& e) override {
    watchdog_events.push_back(e);
    status_word = 0x0208;  // FAULT
    return e.error;
  }
  void system_state_changed(SystemState s, Time) override { states.push_back(s); }

  // ParameterAccess
  ValueResult read(std::uint16_t number, std::uint8_t, Time) override {
    switch (number) {
      case kParamDisp: return {kStatusOk, DataType::usign16, disp, {}};
      case kParamFixed: return {kStatusOk, DataType::usign8, 42, {}};
      case kParamQ16: return {kStatusOk, DataType::int32q16, static_cast<std::uint32_t>(q16), {}};
      case kParamSigned: return {kStatusOk, DataType::int16, wire_from_signed(int16), {}};
      case kParamText:
      case kParamName: return {kStatusReadNotPermitted, DataType::string, 0, {}};
      default: return {kStatusUnknownParameter, DataType::usign32, 0, {}};
    }
  }
  AccessResult write(std::uint16_t number, std::uint8_t, std::uint32_t value, Time) override {
    switch (number) {
      case kParamDisp:
        if (!wire_fits(DataType::usign16, value) || value > 999) return {kStatusImpermissibleValue, {}};
        disp = value;
        return {};
      case kParamSlow: return {kStatusOk, 300ms};
      case kParamQ16: q16 = signed_from_wire(value); return {};
      case kParamSigned:
        if (!wire_fits(DataType::int16, value)) return {kStatusImpermissibleValue, {}};
        int16 = signed_from_wire(value);
        return {};
      case kParamFixed: return {kStatusChangeNotPermitted, {}};
      default: return {kStatusUnknownParameter, {}};
    }
  }
  ValueResult describe(std::uint16_t number, std::uint8_t item, Time) override {
    if (number != kParamDisp) return {kStatusUnknownParameter, DataType::usign32, 0, {}};
    // Items of the fake's description: type code, minimum, maximum, default.
    static constexpr std::array<std::uint32_t, 4> kItems = {2, 0, 999, 406};
    if (item >= kItems.size()) return {kStatusListEnd, DataType::usign32, 0, {}};
    return {kStatusOk, DataType::usign32, kItems[item], {}};
  }
  StringResult read_string(std::uint16_t number, std::span<char> out, Time) override {
    std::string_view s;
    if (number == kParamText) {
      s = text_view();
    } else if (number == kParamName) {
      s = name;
    } else {
      return {kStatusUnknownParameter, 0, {}};
    }
    const std::size_t n = std::min(s.size(), out.size());
    std::copy_n(s.data(), n, out.data());
    return {kStatusOk, static_cast<std::uint8_t>(n), {}};
  }
  AccessResult begin_string_write(std::uint16_t number, Time) override {
    if (number == kParamName) return {kStatusChangeNotPermitted, {}};
    if (number != kParamText) return {kStatusUnknownParameter, {}};
    return {};
  }
  AccessResult write_string(std::uint16_t number, std::string_view s, Time) override {
    if (number != kParamText) return {kStatusUnknownParameter, {}};
    set_text(s);
    return {};
  }
};

}  // namespace ibs::canlust::test
