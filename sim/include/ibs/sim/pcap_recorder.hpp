// Captures of the bus for Wireshark (docs/pcap.md): every bus cycle as one packet of a pcap file
// written through libpcap, under the user link type LINKTYPE_USER0 (147), with the ring's
// configuration in a first packet so that the dissector (tools/wireshark/interbus.lua) knows
// each device's slices, kind and value format. The packet layouts are this project's own and
// docs/pcap.md specifies them; encode_configuration() and encode_cycle() are their one
// implementation. Recording is not the cycle path: it allocates and throws.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <ostream>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "ibs/interbus/process_image.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/devices/capture.hpp"
#include "ibs/pcap/pcap_file.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::sim {

// LINKTYPE_USER0 / DLT_USER0: the link-layer type the captures are written under.
inline constexpr int kLinktypeInterbus = 147;

namespace capture {

inline constexpr std::uint8_t kMagic0 = 0x49;  // 'I'
inline constexpr std::uint8_t kMagic1 = 0x42;  // 'B'
inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::uint8_t kTypeConfiguration = 1;
inline constexpr std::uint8_t kTypeCycle = 2;
inline constexpr std::size_t kConfigurationHeaderSize = 20;
inline constexpr std::size_t kCycleHeaderSize = 16;

// What wrote the capture.
enum class Source : std::uint8_t { run = 0, replay_device = 1, replay_master = 2 };
// A device's kind: the number its drive declares (devices::CaptureFace::kind, from the drive
// registry); kKindOther for a device no registered drive describes.
inline constexpr std::uint8_t kKindOther = 0;
// How a device's reference and actual value read (docs/pcap.md, "Values"): the drive's own
// declaration (devices::CaptureFace::format).
using Values = devices::CaptureValues;

struct Device {
  std::string name;
  std::uint8_t kind = kKindOther;
  Word id_code = 0;
  std::uint8_t first_word = 1;  // the device's process-data word number the slices start with
  interbus::Slice in;           // in the IN area (what the device sends)
  interbus::Slice out;          // in the OUT area (what the master sends)
  interbus::Slice pcp;          // in both PCP areas
  Values values = Values::none;
  std::array<std::uint8_t, 2> layout{};  // layout settings of a drive that has them (CaptureFormat)
  std::string unit;        // of the reference and actual value: "rpm", "Hz"
};

struct Configuration {
  Source source = Source::run;
  Duration cycle_time{0};
  std::size_t in_words = 0;   // the used parts of the areas every cycle packet carries
  std::size_t out_words = 0;
  std::size_t pcp_words = 0;
  std::vector<Device> devices;
};

// The configuration packet; throws std::invalid_argument for a name or unit longer than 255
// bytes, more than 65535 devices or words, or a slice outside the areas.
std::vector<std::uint8_t> encode_configuration(const Configuration& c);
// One cycle packet into `out` (cleared first): the used OUT, IN and both PCP areas of `image`.
void encode_cycle(const Configuration& c, std::uint32_t cycle, bool valid, const interbus::ProcessImage& image,
                  std::vector<std::uint8_t>& out);

// What a capture says of one device besides its slices: its kind number, ID code, unit, layout
// settings and how its values read, from the drive's registry entry (no slices; kKindOther for a
// kind the registry does not know). Throws devices::SettingsError for settings the drive refuses.
Device describe(const std::string& name, const std::string& kind, const devices::DeviceSettings& settings);

// The configuration of a simulated ring: the bus configuration of `sim`, kinds and layouts from
// `scenario` (the one `sim` was built from).
Configuration configuration_of(const Simulator& sim, const Scenario& scenario);

}  // namespace capture

// The pcap file itself (ibs/pcap/pcap_file.hpp), under the names the simulator has always had.
using PcapError = pcap::PcapError;
using PcapFile = pcap::PcapFile;
// Whether this build writes pcap files (libpcap was found at configuration time).
inline bool pcap_available() { return pcap::available(); }
// Now as nanoseconds since 1970 (the system clock), for PcapFile's epoch: read once, at a run's start.
inline Time wall_clock_epoch() { return pcap::wall_clock_epoch(); }

// Records a simulated run as a capture: the configuration at time 0, then one packet per bus
// cycle with the master's process image after its cycle (IN as received in that cycle, OUT as
// the master wrote it for the next one) and the cycle's validity.
class PcapRecorder final : public Observer {
 public:
  // `epoch`: the run's wall-clock start (PcapFile).
  PcapRecorder(Simulator& sim, const Scenario& scenario, std::ostream& out, Time epoch = Time{0});

  void on_cycle(Time at, bool valid, const interbus::ProcessImage& image) override;
  void on_sample(Time /*at*/, std::size_t /*device*/, std::span<const Word> /*m2s*/,
                 std::span<const Word> /*s2m*/) override {}
  // Closes the file at the end of the run (throws PcapError when the stream failed).
  void finish();
  [[nodiscard]] std::uint64_t packets() const { return file_.packets(); }

 private:
  capture::Configuration config_;
  PcapFile file_;
  std::vector<std::uint8_t> buffer_;
  std::uint32_t cycle_ = 0;
};

}  // namespace ibs::sim
