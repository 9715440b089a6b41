// The MC6000's KEYPAD service structure (LUSTBUS manual 11.2.1, 11.3): per parameter the unit (an
// index into 107-UNIT's texts), the user level, the hardware and structure filters, the subject
// area, the activity area (sc_group: non-zero means the parameter belongs to a dataset, the
// "CardWriteable" attribute of 11.4) and the value substitution texts of ShowText parameters.
// The seeds give the codings, not one parameter's values: every value here is chosen (docs/
// lustbus.md, "The MC6000's service structure", LB-D21). Drive knowledge, bus-neutral.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace ibs::devices::mc6000 {

// 11.2.1 subject areas and activity areas the table uses.
enum class Subject : std::uint8_t {
  conf = 0, opt1 = 2, scon = 6, sio = 9, scty = 12, sys = 14, ref = 15, menu = 20, val = 21,
};
enum class Activity : std::uint8_t {
  nothing = 0, opt1 = 1, sys = 4, drive = 5, ref = 6,
};
// 11.2.1 structure filter: every control type (TorqueCtrl .. ESlave).
inline constexpr std::uint16_t kAllControlTypes = 0x003F;

struct ServiceEntry {
  std::uint16_t number = 0;
  std::uint8_t unit = 0;    // 107-UNIT text index; 0 = "-" (no unit)
  std::uint8_t level = 0x21;  // read level 1 (low nibble), write level 2 (high nibble)
  // 0 = the parameter does not depend on the hardware (a decision: 11.2.1 names only the bits).
  std::uint16_t hardware_filter = 0;
  std::uint16_t structure_filter = kAllControlTypes;
  Subject subject = Subject::conf;
  Activity activity = Activity::nothing;
  // 11.3: the text of value 0, 1, ...; empty: the parameter has none.
  std::span<const std::string_view> texts{};
};

// nullptr for a number the table does not have.
const ServiceEntry* service_entry(std::uint16_t number);
// 11.4: only parameters with an activity area take part in a dataset download.
bool card_writeable(std::uint16_t number);
// 11.3: the substitution text of `value` of parameter `number`; empty when there is none.
std::string_view substitution_text_of(std::uint16_t number, std::uint32_t value);

}  // namespace ibs::devices::mc6000
