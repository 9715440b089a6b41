// DRIVECOM Profile 20 status word (seed 001, 5.1.3) and the device-specific bits of the VF1000
// (5.2.2) and the MC6000 (5.3.2).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "ibs/drivecom/control_word.hpp"
#include "ibs/interbus/words.hpp"

namespace ibs::drivecom {

enum class State : std::uint8_t {
  not_ready,
  start_up_inhibit,
  ready,
  on,
  enabled,
  fault,
  fault_response_active,
  emergency_stop_active,
};
inline constexpr std::size_t kStateCount = 8;

namespace sw {
inline constexpr unsigned kReady = 0;
inline constexpr unsigned kOn = 1;
inline constexpr unsigned kEnabled = 2;
inline constexpr unsigned kFault = 3;
inline constexpr unsigned kPowerBlocked = 4;   // 0 = block-power request received
inline constexpr unsigned kEmergencyStop = 5;  // 0 = emergency-stop request received
inline constexpr unsigned kStartUpInhibit = 6;
inline constexpr unsigned kAlarm = 7;
inline constexpr unsigned kMessage = 8;
inline constexpr unsigned kRemote = 9;
inline constexpr unsigned kReferenceReached = 10;
inline constexpr unsigned kLimitValue = 11;
}  // namespace sw

// One row of the device-state table of 5.1.3: `(status & mask) == value`.
struct StateRow {
  State state;
  Word mask;
  Word value;
  std::string_view name;
};

inline constexpr std::array<StateRow, kStateCount> kStateTable{{
    {State::not_ready, 0x004F, 0x0000, "NOT READY"},
    {State::start_up_inhibit, 0x004F, 0x0040, "START-UP INHIBIT"},
    {State::ready, 0x006F, 0x0021, "READY"},
    {State::on, 0x006F, 0x0023, "ON"},
    {State::enabled, 0x006F, 0x0027, "ENABLED"},
    {State::fault, 0x004F, 0x0008, "FAULT"},
    {State::fault_response_active, 0x004F, 0x000F, "FAULT RESPONSE ACTIVE"},
    {State::emergency_stop_active, 0x006F, 0x0007, "EMERGENCY STOP ACTIVE"},
}};

constexpr const StateRow& state_row(State s) { return kStateTable[static_cast<std::size_t>(s)]; }
constexpr std::string_view to_string(State s) { return state_row(s).name; }

namespace detail {
// Bits 0-6 -> state (or none), derived once from kStateTable; every row's mask lies in 0x7F.
inline constexpr std::uint8_t kNoState = 0xFF;
constexpr std::array<std::uint8_t, 128> make_state_lut() {
  std::array<std::uint8_t, 128> lut{};
  for (unsigned bits = 0; bits < 128; ++bits) {
    lut[bits] = kNoState;
    for (const auto& row : kStateTable) {
      if ((bits & row.mask) == row.value) {
        lut[bits] = static_cast<std::uint8_t>(row.state);
        break;
      }
    }
  }
  return lut;
}
inline constexpr std::array<std::uint8_t, 128> kStateLut = make_state_lut();
}  // namespace detail

// The state a status word shows, or nullopt for a word that matches no row.
constexpr std::optional<State> decode_state(Word status) {
  const std::uint8_t s = detail::kStateLut[status & 0x7FU];
  if (s == detail::kNoState) return std::nullopt;
  return static_cast<State>(s);
}

// Bits 0-6 of the status word for a state, with bits 4 and 5 showing the block-power and
// emergency-stop requests of the last control word received (5.1.3: 0 = request received; the
// MC6000 start-up table of 5.3.4 shows 0240H for control word 0000H). In EMERGENCY STOP ACTIVE
// bit 5 is 0 whatever the control word says, as the state table requires.
constexpr Word state_bits(State s, Word last_control) {
  Word w = state_row(s).value;
  w = with_bit(w, sw::kPowerBlocked, bit(last_control, cw::kBlockPower));
  const bool estop_bit =
      s != State::emergency_stop_active && bit(last_control, cw::kEmergencyStop);
  w = with_bit(w, sw::kEmergencyStop, estop_bit);
  // READY, ON and ENABLED show bit 5 = 1 by definition (no e-stop request can be pending there).
  if (s == State::ready || s == State::on || s == State::enabled) w = with_bit(w, sw::kEmergencyStop, true);
  return w;
}

// The bits 7-15 a device adds to the state bits.
struct StatusExtras {
  bool alarm = false;               // bit 7
  bool message = false;             // bit 8 (MC6000, VF1000: not implemented)
  bool remote = true;               // bit 9: parameters can be changed over the bus
  bool reference_reached = false;   // bit 10
  bool limit_value = false;         // bit 11
  bool bit14 = false;               // VF1000 S2OUT, MC6000 IS00
  bool bit15 = false;               // VF1000 S1OUT, MC6000 IS01
};
constexpr Word extras_bits(const StatusExtras& e) {
  Word w = 0;
  w = with_bit(w, sw::kAlarm, e.alarm);
  w = with_bit(w, sw::kMessage, e.message);
  w = with_bit(w, sw::kRemote, e.remote);
  w = with_bit(w, sw::kReferenceReached, e.reference_reached);
  w = with_bit(w, sw::kLimitValue, e.limit_value);
  w = with_bit(w, 14, e.bit14);
  w = with_bit(w, 15, e.bit15);
  return w;
}

constexpr Word status_word(State s, Word last_control, const StatusExtras& e) {
  return static_cast<Word>(state_bits(s, last_control) | extras_bits(e));
}

// A status word in words, e.g. "0231 READY, remote" or "0637 ENABLED, remote, reference reached".
std::string explain_status_word(DeviceType d, Word status);

}  // namespace ibs::drivecom
