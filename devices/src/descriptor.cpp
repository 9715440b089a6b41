#include "ibs/devices/descriptor.hpp"

namespace ibs::devices {

std::string_view to_string(SettingKind k) {
  switch (k) {
    case SettingKind::integer: return "integer";
    case SettingKind::boolean: return "boolean";
    case SettingKind::duration: return "time";
    case SettingKind::choice: return "choice";
  }
  return "?";
}

// The throwing forms, on top of the drives' non-throwing ones (not in the embedded build).
#if IBS_EXCEPTIONS
Configuration DriveDescriptor::configure(const DeviceSettings& s) const {
  Expected<Configuration, SettingsRefusal> c = try_configure(s);
  detail::require<SettingsError>(c.error());
  return std::move(c).value();
}

void DriveDescriptor::check_watchdog(const DeviceSettings& s) const {
  detail::require<SettingsError>(validate_watchdog(s));
}

RingEntry DriveDescriptor::ring_entry(std::span<const std::string_view> fields) const {
  Expected<RingEntry, SettingsRefusal> e = try_ring_entry(fields);
  detail::require<SettingsError>(e.error());
  return std::move(e).value();
}
#endif

}  // namespace ibs::devices
