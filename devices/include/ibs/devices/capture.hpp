// What a drive declares for the INTERBUS captures (docs/pcap.md): its kind number in the
// configuration packet and how its reference and actual value read. The capture writer
// (sim/pcap_recorder.hpp) takes both from the registry entry of the drive (DriveKind::capture)
// and the Wireshark dissector (tools/wireshark/interbus.lua) decodes by the same numbers; the
// registry test holds the two together. The numbers are the format's: a new drive takes the next
// free kind number and never reuses one, so existing captures keep decoding.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "ibs/devices/descriptor.hpp"

namespace ibs::devices {

// How a device's reference and actual value read (docs/pcap.md, "Values").
enum class CaptureValues : std::uint8_t {
  none = 0,          // no values (no process data exchanged, or channel words only)
  word16 = 1,        // one signed word each, whole units
  q16 = 2,           // 32-bit Q16 each, high word first
  speed_torque = 3,  // Q16 reference; actual speed and torque as signed words
  hz_005 = 4,        // reference 0.05 Hz per bit (absolute), actual 0.05 Hz signed
};

// A device's value format in a capture, and the layout settings the dissector shows with it.
struct CaptureFormat {
  CaptureValues values = CaptureValues::none;
  // The two layout bytes the dissector shows (docs/pcap.md; the MC6000's 405-SUPI and 406-IBCNF):
  // the drive's own settings that lay out its words, 0 where it has none.
  std::array<std::uint8_t, 2> layout{};
};

struct CaptureFace {
  std::uint8_t kind = 0;          // 0 is "other": no drive has it
  std::string_view label;         // as the dissector names the kind ("VF1000")
  // The format for the settings (already checked by the descriptor's configure()).
  CaptureFormat (*format)(const DeviceSettings& settings) = nullptr;
};

}  // namespace ibs::devices
