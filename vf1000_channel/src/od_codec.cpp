#include "ibs/vf1000_channel/od_codec.hpp"

#include <string>

namespace ibs::vf1000_channel {

Error check(const od::Dictionary& d) {
  const auto entries = d.entries();
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const od::Entry& e = entries[i];
    if (const char* why = unfit(e)) {
      ErrorCode code = ErrorCode::table_limits_outside_type;
      if (e.number > kMaxParameterNumber) code = ErrorCode::table_number_out_of_range;
      else if (e.name.empty() || e.name.size() > kTextLength) code = ErrorCode::table_bad_name;
      else if (e.unit.size() > kTextLength) code = ErrorCode::table_bad_unit;
      else if (!category_code(e)) code = ErrorCode::table_bad_role;
      return {code, "vf1000_channel: dictionary entry " + std::to_string(i) + " (" +
                        std::to_string(e.number) + "-" + std::string(e.name) + "): " + why};
    }
  }
  if (d.slot_of(od::Role::error_flags) == od::kNoSlot) {
    return {ErrorCode::table_lacks_siof,
            "vf1000_channel: the dictionary has no 85-SIOF, which every value transfer depends on "
            "(INTERBUS manual 4.1.4)"};
  }
  return {};
}

std::array<std::uint8_t, kDescriptionLength> description(const od::Entry& e, od::Raw default_raw) {
  std::array<std::uint8_t, kDescriptionLength> r{};
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = description_byte(e, i, default_raw);
  return r;
}

}  // namespace ibs::vf1000_channel
