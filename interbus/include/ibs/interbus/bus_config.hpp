// A bus configuration: the ring of devices in physical order, each placed in the process image by
// its ID code, checked against the INTERBUS limits. Building one is configuration-time work (it
// allocates, and a refusal is an Error, or a ConfigError where exceptions are on); reading it is
// free.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/base/error.hpp"
#include "ibs/interbus/id_code.hpp"
#include "ibs/interbus/process_image.hpp"

#if IBS_EXCEPTIONS
#include <stdexcept>
#endif

namespace ibs::interbus {

// INTERBUS limits (public-facts.md, INTERBUS Club FAQ). The 256-word process-data limit per
// direction and the 62 PCP devices are kMaxProcessWords and kMaxPcpDevices (process_image.hpp).
inline constexpr std::size_t kMaxDevices = 512;
inline constexpr std::size_t kMaxRemoteDevices = 254;
inline constexpr std::size_t kMaxLocalSegmentDevices = 63;

// What the user says about one device of the ring.
struct DeviceSpec {
  std::string name;  // unique, not empty
  IdCode id;
  // Overrides the bus kind the ID code suggests (id_code.hpp: that rule is a modelling choice).
  std::optional<BusKind> bus;
};

// One device as placed by the configuration.
struct Device {
  std::string name;
  IdCode id;
  BusKind bus = BusKind::remote;
  std::size_t ring_position = 0;  // 0 = the first device after the master
  std::size_t ring_words = 0;     // register length on the ring: process data + PCP
  std::size_t pd_in_words = 0;    // process data the device sends
  std::size_t pd_out_words = 0;   // process data the device receives
  std::size_t pcp_words = 0;      // PCP channel width, 0 without PCP
  Slice in;                       // in ProcessImage::in
  Slice out;                      // in ProcessImage::out
  Slice pcp;                      // in ProcessImage::pcp_in and ::pcp_out (same place both ways)
};

struct BusConfig {
  std::vector<Device> devices;  // ring order
  std::size_t in_words = 0;     // used part of ProcessImage::in
  std::size_t out_words = 0;    // used part of ProcessImage::out
  std::size_t pcp_words = 0;    // used part of the PCP areas
  std::size_t ring_words = 0;   // all register words on the ring
  std::size_t remote_devices = 0;
  std::size_t pcp_devices = 0;

  std::size_t ring_bytes() const { return ring_words * 2; }
  // nullptr when no device has that name.
  const Device* find(std::string_view name) const;
};

// Places the devices in ring order: each one's input and output process data follow those of
// the devices before it (a contiguous default mapping, as a master without a user mapping would
// build it; a modelling choice), its PCP words likewise in the PCP areas. A device that sends no
// input (direction out) gets an empty `in` slice at the current offset, and vice versa.
//
// Refuses (ErrorCode::bus_*, the message naming the device, the offending value and the limit):
// an empty or repeated name; an ID code whose length code or PCP width is unknown, whose PCP
// channel is wider than the device, or that has words but no direction; more than 512 devices,
// 254 remote-bus devices, 63 devices in one local bus segment (a run of consecutive local-bus
// devices), 62 PCP devices, 256 process-data words in or out.
Expected<BusConfig> try_make_bus_config(std::span<const DeviceSpec> ring);

#if IBS_EXCEPTIONS
// A configuration was refused; what() is the Error's message.
class ConfigError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};
// try_make_bus_config, throwing ConfigError for what it refuses.
BusConfig make_bus_config(std::span<const DeviceSpec> ring);
#endif

// A device's words in an image (empty spans for a device of another configuration that does not
// fit the image; never for one of the configuration the image is used with).
inline std::span<Word> in_slice(ProcessImage& p, const Device& d) {
  return p.slice(Area::in, d.in);
}
inline std::span<Word> out_slice(ProcessImage& p, const Device& d) {
  return p.slice(Area::out, d.out);
}
inline std::span<Word> pcp_in_slice(ProcessImage& p, const Device& d) {
  return p.slice(Area::pcp_in, d.pcp);
}
inline std::span<Word> pcp_out_slice(ProcessImage& p, const Device& d) {
  return p.slice(Area::pcp_out, d.pcp);
}
inline std::span<const Word> in_slice(const ProcessImage& p, const Device& d) {
  return p.slice(Area::in, d.in);
}
inline std::span<const Word> out_slice(const ProcessImage& p, const Device& d) {
  return p.slice(Area::out, d.out);
}

}  // namespace ibs::interbus
