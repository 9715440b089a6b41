// The drive kinds the project knows: one entry per wing, each a descriptor (its master side,
// descriptor.hpp), a factory of its emulator (its device side, emulator.hpp) and its part in the
// fault campaign (campaign_profile.hpp). The simulator,
// the scenario reader, the command line and the replay adapters find a drive here by the name
// files give it and never name a concrete drive. Adding a drive adds its wing and one entry in
// registry.cpp (docs/architecture.md, "Adding a drive").
#pragma once

#include <memory>
#include <optional>
#include <vector>
#include <span>
#include <string>
#include <string_view>

#include "ibs/devices/campaign_profile.hpp"
#include "ibs/devices/capture.hpp"
#include "ibs/devices/descriptor.hpp"
#include "ibs/devices/emulator.hpp"
#include "ibs/interbus/device_start.hpp"
#include "ibs/base/time.hpp"
#include "ibs/interbus/trace.hpp"

namespace ibs::devices {

using EmulatorFactory = std::unique_ptr<DeviceEmulator> (*)(const Configuration& config, DeviceStart start,
                                                            Time now);

struct DriveKind {
  const DriveDescriptor* descriptor = nullptr;
  EmulatorFactory make_emulator = nullptr;
  const CampaignProfile* campaign = nullptr;
  // The drive's kind number and value formats in INTERBUS captures (capture.hpp, docs/pcap.md).
  const CaptureFace* capture = nullptr;

  [[nodiscard]] const DriveDescriptor& operator*() const { return *descriptor; }
  [[nodiscard]] const DriveDescriptor* operator->() const { return descriptor; }
};

// Every drive kind, sorted by name (static data).
std::span<const DriveKind> drive_kinds();
// The kind a file names ("mc6000"); nullptr for none.
const DriveKind* find_drive_kind(std::string_view name);
// The kinds' names for messages: joined by `separator`, the last two by `last`, each in `quote`:
// drive_kind_names(", ", " or ", "\"") = "\"mc6000\" or \"vf1000\"".
std::string drive_kind_names(std::string_view separator, std::string_view last, std::string_view quote = "");

// A device's own settings against its kind's declarations (settings.hpp): a name the kind does
// not declare (ErrorCode::setting_of_another_drive, in the words of the kind that declares it, or
// setting_invalid for a name no kind declares), a value of the wrong type (setting_invalid) or out
// of the declared range (setting_out_of_range). Each message names the setting, the value and
// the limit. No error: they suit. The wing's own checks (try_configure, validate_watchdog) give
// the manual's words for its ranges; this is what every reader checks besides.
SettingsRefusal check_settings(const DriveKind& kind, const SettingValues& values);
// Only the name: what check_settings says about `name` for `kind`, nullopt when it declares it.
std::optional<SettingsRefusal> refuse_setting_name(const DriveKind& kind, std::string_view name);
// Every kind's declared settings' names, each once, the kinds in order (for a reader's list of
// the keys it knows and its near-miss suggestions).
std::vector<std::string_view> declared_setting_names();
// The kind that declares `name` first in drive_kinds(), and its declaration; nullptr for none.
const SettingSpec* any_declaration(std::string_view name, const DriveKind** owner = nullptr);

// What the trace reader may accept (trace::Vocabulary): the kinds' names and DRIVECOM's targets.
trace::Vocabulary trace_vocabulary();

}  // namespace ibs::devices
