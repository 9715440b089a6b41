// The items of a CDA3000 parameter's description, mode 04 (CANLust manual leaves what they are to the
// drive, decision D10; this drive's are D29, docs/canlust.md "Descriptions"): 0 the data type
// (canlust::DataType code), 1 the minimum, 2 the maximum, 3 the factory setting, 4 attribute bits,
// 5 and 6 the name's characters 1-4 and 5-8, 7 the unit's first four, each text item up to four
// characters in Intel order; item 8 answers List_End. The emulator answers them (device.cpp), the
// command line reads them back (`ibs canlust describe`).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "ibs/canlust/data_types.hpp"

namespace ibs::devices::cda3000 {

inline constexpr std::size_t kDescriptionItems = 8;

// Item 4.
inline constexpr std::uint32_t kAttrWritable = 0x01;
inline constexpr std::uint32_t kAttrFlash = 0x02;
inline constexpr std::uint32_t kAttrAfterMainsReset = 0x04;
inline constexpr std::uint32_t kAttrChoices = 0x08;  // has substitution texts

// Up to four characters in one item, the first in the lowest byte; more are cut off.
std::uint32_t pack4(std::string_view s);
// The characters of an item up to the first NUL.
std::string unpack4(std::uint32_t item);

struct Description {
  canlust::DataType type = canlust::DataType::usign32;
  std::uint32_t min = 0;  // on the wire, as the type codes them
  std::uint32_t max = 0;
  std::uint32_t factory = 0;
  std::uint32_t attributes = 0;
  std::string short_name;  // items 5 and 6
  std::string unit;        // item 7

  [[nodiscard]] bool writable() const { return (attributes & kAttrWritable) != 0; }
  [[nodiscard]] bool flash() const { return (attributes & kAttrFlash) != 0; }
  [[nodiscard]] bool after_mains_reset() const { return (attributes & kAttrAfterMainsReset) != 0; }
};

// The description the items say; nullopt when they are not this drive's (fewer than eight, or
// item 0 no data type code).
std::optional<Description> read_description(std::span<const std::uint32_t> items);

}  // namespace ibs::devices::cda3000
