#include "ibs/interbus/cycle_time.hpp"

#include <cmath>

#include "ibs/interbus/bus_config.hpp"

namespace ibs::interbus {

RingLoad ring_load(const BusConfig& c) {
  return {c.ring_bytes(), c.remote_devices};
}

Duration cycle_time(RingLoad load, const CycleTimeParams& p) {
  const double line_bits =
      p.line_bits_per_byte * (p.overhead_bytes + static_cast<double>(load.data_bytes)) +
      p.bits_per_remote_device * static_cast<double>(load.remote_devices);
  const double line_ns = line_bits * static_cast<double>(p.bit_time.count()) +
                         p.cable_km * static_cast<double>(p.cable_time_per_km.count());
  return p.software_time + Duration{std::llround(line_ns)};
}

Duration cycle_time(const BusConfig& c, const CycleTimeParams& p) {
  return cycle_time(ring_load(c), p);
}

}  // namespace ibs::interbus
