// DRIVECOM Profile 20 status word (INTERBUS manual 5.1.3). What the manufacturer-specific bits 8, 14
// and 15 mean is the drive's (its descriptor: VF1000 5.2.2, MC6000 5.3.2).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "ibs/drivecom/control_word.hpp"
#include "ibs/base/words.hpp"

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

// One row of the device-state table of 5.1.3: `(status & mask) == value`. `name` is the manual's
// ("START-UP INHIBIT", reports and VCD files), `key` the one scenario files and traces write
// ("start-up-inhibit"): the only place either is spelled.
struct StateRow {
  State state;
  Word mask;
  Word value;
  std::string_view name;
  std::string_view key;
};

inline constexpr std::array<StateRow, kStateCount> kStateTable{{
    {State::not_ready, 0x004F, 0x0000, "NOT READY", "not-ready"},
    {State::start_up_inhibit, 0x004F, 0x0040, "START-UP INHIBIT", "start-up-inhibit"},
    {State::ready, 0x006F, 0x0021, "READY", "ready"},
    {State::on, 0x006F, 0x0023, "ON", "on"},
    {State::enabled, 0x006F, 0x0027, "ENABLED", "enabled"},
    {State::fault, 0x004F, 0x0008, "FAULT", "fault"},
    {State::fault_response_active, 0x004F, 0x000F, "FAULT RESPONSE ACTIVE", "fault-response-active"},
    {State::emergency_stop_active, 0x006F, 0x0007, "EMERGENCY STOP ACTIVE", "emergency-stop-active"},
}};

constexpr const StateRow& state_row(State s) { return kStateTable[static_cast<std::size_t>(s)]; }
constexpr std::string_view to_string(State s) { return state_row(s).name; }
constexpr std::string_view key(State s) { return state_row(s).key; }
// The state a file names by its key; nullopt for no state.
constexpr std::optional<State> state_named(std::string_view key) {
  for (const auto& row : kStateTable) {
    if (row.key == key) return row.state;
  }
  return std::nullopt;
}
// Every state's key, in the table's order.
inline constexpr std::array<std::string_view, kStateCount> kStateKeys = [] {
  std::array<std::string_view, kStateCount> keys{};
  for (std::size_t i = 0; i < kStateCount; ++i) keys[i] = kStateTable[i].key;
  return keys;
}();

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
// The state of a state code of kStateLut; nullopt for kNoState.
constexpr std::optional<State> state_of_code(std::uint8_t code) {
  return code == kNoState ? std::nullopt : std::optional<State>(static_cast<State>(code));
}
}  // namespace detail

// The state a status word shows, or nullopt for a word that matches no row.
constexpr std::optional<State> decode_state(Word status) { return detail::state_of_code(detail::kStateLut[status & 0x7FU]); }

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
  bool message = false;             // bit 8 (manufacturer-specific)
  bool remote = true;               // bit 9: parameters can be changed over the bus
  bool reference_reached = false;   // bit 10
  bool limit_value = false;         // bit 11
  bool bit14 = false;               // manufacturer-specific (a drive's descriptor names it)
  bool bit15 = false;
};
constexpr Word extras_bits(const StatusExtras& e) {
  const auto at = [](bool on, unsigned n) { return static_cast<unsigned>(on) << n; };
  return static_cast<Word>(at(e.alarm, sw::kAlarm) | at(e.message, sw::kMessage) |
                           at(e.remote, sw::kRemote) |
                           at(e.reference_reached, sw::kReferenceReached) |
                           at(e.limit_value, sw::kLimitValue) | at(e.bit14, 14) | at(e.bit15, 15));
}

namespace detail {
// state_bits for every state and both request bits (1 and 2) of the last control word: the
// status word of every device sample is a lookup here plus the extra bits.
constexpr std::array<std::array<Word, 4>, kStateCount> make_state_bits_lut() {
  std::array<std::array<Word, 4>, kStateCount> lut{};
  for (std::size_t s = 0; s < kStateCount; ++s) {
    for (unsigned r = 0; r < 4; ++r) lut[s][r] = state_bits(static_cast<State>(s), static_cast<Word>(r << 1U));
  }
  return lut;
}
inline constexpr auto kStateBitsLut = make_state_bits_lut();
static_assert(cw::kBlockPower == 1 && cw::kEmergencyStop == 2, "the lookup takes control bits 1-2");
}  // namespace detail

constexpr Word status_word(State s, Word last_control, const StatusExtras& e) {
  const Word bits = detail::kStateBitsLut[static_cast<std::size_t>(s)][(last_control >> 1U) & 3U];
  return static_cast<Word>(bits | extras_bits(e));
}

// What a drive calls its manufacturer-specific status bits, as explain_status_word writes them
// when set ("IS00", "bit 8 (not implemented) set").
struct StatusBitNames {
  std::string_view bit8;
  std::string_view bit14;
  std::string_view bit15;
};

// A status word in words, e.g. "0231 READY, remote" or "0637 ENABLED, remote, reference reached".
std::string explain_status_word(Word status, const StatusBitNames& names);

}  // namespace ibs::drivecom
