#include "ibs/od/dictionary.hpp"

#include <stdexcept>
#include <string>

namespace ibs::od {

std::string_view to_string(Storage s) {
  switch (s) {
    case Storage::ram_control:
      return "RAM control value";
    case Storage::ram_actual:
      return "RAM actual value";
    case Storage::eeprom:
      return "EEPROM";
    case Storage::eeprom_ram:
      return "EEPROM/RAM variable";
    case Storage::flash:
      return "flash";
  }
  return "?";
}

std::string_view to_string(Role r) {
  switch (r) {
    case Role::value:
      return "value";
    case Role::load_defaults:
      return "load defaults (PROG)";
    case Role::download:
      return "download handshake (SLOAD)";
    case Role::error_flags:
      return "error flags (85-SIOF/SERR)";
    case Role::save:
      return "save (SAVE)";
  }
  return "?";
}

std::string_view to_string(Profile p) {
  switch (p) {
    case Profile::none:
      return "none";
    case Profile::lust_standard:
      return "LUST standard";
    case Profile::lust_enhanced:
      return "LUST enhanced";
  }
  return "?";
}

Error Dictionary::validate(std::span<const Entry> entries) {
  const Finding f = check(entries);
  if (f.ok()) return {};
  std::string who = "dictionary entry " + std::to_string(f.entry);
  if (f.entry < entries.size()) {
    who += " (" + std::to_string(entries[f.entry].number) + "-" +
           std::string(entries[f.entry].name) + ")";
  }
  return {f.code, who + ": " + std::string(f.what)};
}

void Dictionary::refused(std::span<const Entry> entries) {
  ibs::detail::require<std::invalid_argument>(validate(entries));
}

}  // namespace ibs::od
