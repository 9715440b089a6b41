#include "ibs/interbus/bus_config.hpp"

#include <algorithm>
#include <functional>
#include <set>
#include <string>

namespace ibs::interbus {

const Device* BusConfig::find(std::string_view name) const {
  const auto it =
      std::find_if(devices.begin(), devices.end(), [&](const Device& d) { return d.name == name; });
  return it == devices.end() ? nullptr : &*it;
}

namespace {

std::string who(const DeviceSpec& s, std::size_t position) {
  return "device '" + s.name + "' (ring position " + std::to_string(position) + ")";
}

Error refuse(ErrorCode code, const DeviceSpec& s, std::size_t position, const std::string& what) {
  return {code, "bus configuration: " + who(s, position) + ": " + what};
}

std::string length_code_hex(IdCode id) {
  constexpr std::string_view kDigits = "0123456789ABCDEF";
  const unsigned c = id.length_code();
  return {kDigits[c >> 4U], kDigits[c & 0x0FU], 'H'};
}

std::string n_words(std::size_t n) {
  return std::to_string(n) + (n == 1 ? " word" : " words");
}

// Decodes the spec's ID code into the word counts; refuses what does not decode.
Expected<Device> place(const DeviceSpec& s, std::size_t position) {
  const IdCode id = s.id.without_errors();
  const auto ring = id.ring_words();
  if (!ring) {
    return refuse(ErrorCode::bus_unknown_length_code, s, position,
                  "ID code " + to_hex(id) + " has the unknown length code " + length_code_hex(id) +
                      " in bits 8..12 (known: 00H..07H, 0EH, 0FH, 11H..13H, 15H..17H)");
  }
  const auto pcp = id.pcp_words();
  if (!pcp) {
    return refuse(ErrorCode::bus_unassigned_pcp_width, s, position,
                  "ID code " + to_hex(id) +
                      " is a PCP device with the unassigned PCP width bits 10b "
                      "(11b = 1 word, 00b = 2 words, 01b = 4 words)");
  }
  if (*pcp > *ring) {
    return refuse(ErrorCode::bus_pcp_wider_than_device, s, position,
                  "ID code " + to_hex(id) + " has a PCP channel of " +
                      n_words(static_cast<std::size_t>(*pcp)) + ", more than its " +
                      n_words(static_cast<std::size_t>(*ring)) + " on the bus");
  }
  const Direction dir = id.direction();
  const auto pd = static_cast<std::size_t>(*ring - *pcp);
  if (dir == Direction::none && pd > 0) {
    return refuse(ErrorCode::bus_no_direction, s, position,
                  "ID code " + to_hex(id) + " has " + n_words(pd) +
                      " of process data but no direction (bits 1..0 = 00b)");
  }
  Device d;
  d.name = s.name;
  d.id = id;
  d.bus = s.bus.value_or(id.bus());
  d.ring_position = position;
  d.ring_words = static_cast<std::size_t>(*ring);
  d.pcp_words = static_cast<std::size_t>(*pcp);
  const bool sends = dir == Direction::in || dir == Direction::in_out;
  const bool receives = dir == Direction::out || dir == Direction::in_out;
  d.pd_in_words = sends ? pd : 0;
  d.pd_out_words = receives ? pd : 0;
  return d;
}

}  // namespace

Expected<BusConfig> try_make_bus_config(std::span<const DeviceSpec> ring) {
  if (ring.size() > kMaxDevices) {
    const DeviceSpec& s = ring[kMaxDevices];
    return refuse(ErrorCode::bus_too_many_devices, s, kMaxDevices,
                  "the ring holds " + std::to_string(ring.size()) + " devices, the limit is " +
                      std::to_string(kMaxDevices) + " devices per INTERBUS system");
  }
  BusConfig c;
  c.devices.reserve(ring.size());
  std::set<std::string, std::less<>> names;
  std::size_t segment_size = 0;              // devices in the current local bus segment
  std::string segment_after = "the master";  // the device the current segment follows
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const DeviceSpec& s = ring[i];
    if (s.name.empty()) return refuse(ErrorCode::bus_device_unnamed, s, i, "a device needs a name");
    if (!names.insert(s.name).second) {
      return refuse(ErrorCode::bus_name_repeated, s, i, "the name is used by an earlier device");
    }

    Expected<Device> placed = place(s, i);
    if (!placed) return placed.error();
    Device d = std::move(placed).value();

    if (d.bus == BusKind::remote) {
      ++c.remote_devices;
      if (c.remote_devices > kMaxRemoteDevices) {
        return refuse(ErrorCode::bus_too_many_remote_devices, s, i,
                      "remote bus device number " + std::to_string(c.remote_devices) +
                          " exceeds the limit of " + std::to_string(kMaxRemoteDevices) +
                          " remote bus devices");
      }
      segment_size = 0;
      segment_after = "'" + s.name + "'";
    } else {
      ++segment_size;
      if (segment_size > kMaxLocalSegmentDevices) {
        return refuse(ErrorCode::bus_local_segment_too_long, s, i,
                      "local bus segment after " + segment_after + " would hold " +
                          std::to_string(segment_size) + " devices, the limit is " +
                          std::to_string(kMaxLocalSegmentDevices) + " per local bus segment");
      }
    }

    if (d.pcp_words > 0) {
      ++c.pcp_devices;
      if (c.pcp_devices > kMaxPcpDevices) {
        return refuse(ErrorCode::bus_too_many_pcp_devices, s, i,
                      "PCP device number " + std::to_string(c.pcp_devices) +
                          " exceeds the limit of " + std::to_string(kMaxPcpDevices) +
                          " PCP devices");
      }
    }

    d.in = Slice{c.in_words, d.pd_in_words};
    d.out = Slice{c.out_words, d.pd_out_words};
    d.pcp = Slice{c.pcp_words, d.pcp_words};
    if (d.in.end() > kMaxProcessWords) {
      return refuse(ErrorCode::bus_too_many_input_words, s, i,
                    "its " + n_words(d.pd_in_words) + " of input data would end at word " +
                        std::to_string(d.in.end()) + ", the limit is " +
                        std::to_string(kMaxProcessWords) + " input words (4096 bits)");
    }
    if (d.out.end() > kMaxProcessWords) {
      return refuse(ErrorCode::bus_too_many_output_words, s, i,
                    "its " + n_words(d.pd_out_words) + " of output data would end at word " +
                        std::to_string(d.out.end()) + ", the limit is " +
                        std::to_string(kMaxProcessWords) + " output words (4096 bits)");
    }
    c.in_words = d.in.end();
    c.out_words = d.out.end();
    c.pcp_words = d.pcp.end();  // at most 62 * 4 = kMaxPcpWords, guaranteed by the PCP limit
    c.ring_words += d.ring_words;
    c.devices.push_back(std::move(d));
  }
  return c;
}

#if IBS_EXCEPTIONS
BusConfig make_bus_config(std::span<const DeviceSpec> ring) {
  Expected<BusConfig> c = try_make_bus_config(ring);
  detail::require<ConfigError>(c.error());
  return std::move(c).value();
}
#endif

}  // namespace ibs::interbus
