// The drive kinds the project knows: one entry per wing, each a descriptor (its master side,
// descriptor.hpp), a factory of its emulator (its device side, emulator.hpp) and its part in the
// fault campaign (campaign_profile.hpp). The simulator,
// the scenario reader, the command line and the replay adapters find a drive here by the name
// files give it and never name a concrete drive. Adding a drive adds its wing and one entry in
// registry.cpp (docs/architecture.md, "Adding a drive").
#pragma once

#include <memory>
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

// What the trace reader may accept (trace::Vocabulary): the kinds' names and DRIVECOM's targets.
trace::Vocabulary trace_vocabulary();

}  // namespace ibs::devices
