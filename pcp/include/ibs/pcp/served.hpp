// What a PCP server serves (INTERBUS manual 4.2): a drive's parameters behind the channel. The server
// owns the protocol -- link, association, one request at a time, processing latency -- and asks
// the drive for everything about the values: the drive owns its store, its write checks, 85-SERR
// and its timing (EEPROM, PROG), and answers in PCP's terms. Drive-neutral: a drive's INTERBUS face
// implements it (the MC6000's: devices/mc6000/include/ibs/devices/mc6000/pcp_served.hpp).
//
// Every call is on the cycle path: no allocation, no exceptions, time passed in.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "ibs/base/time.hpp"
#include "ibs/pcp/data_types.hpp"
#include "ibs/pcp/parameters.hpp"
#include "ibs/pcp/pdu.hpp"

namespace ibs::pcp {

// A Write's answer: the error (none: positive) and how much later than the server's processing
// time the confirmation goes out (a command that takes long, e.g. a drive's factory reset).
struct WriteAnswer {
  PcpError error{};
  Duration confirm_after = Duration::zero();
};

class ServedParameters {
 public:
  virtual ~ServedParameters() = default;

  // The drive's table: Get-OV long answers from it, and it is what the server's validate() checks.
  [[nodiscard]] virtual std::span<const ParameterInfo> table() const = 0;
  // Time passes (the server's sample): background work of the drive may end.
  virtual void advance(Time now) = 0;
  // Read of (index, subindex): the value into `out`, or the error. Reading may act (85-SERR clears).
  virtual PcpError read(Time now, std::uint16_t index, std::uint8_t subindex, Value& out) = 0;
  // Write of (index, subindex) with the request's data bytes.
  virtual WriteAnswer write(Time now, std::uint16_t index, std::uint8_t subindex,
                            std::span<const std::uint8_t> data) = 0;
  // The value an Information Report carries, read without acting (nullopt: no such parameter).
  [[nodiscard]] virtual std::optional<Value> value(std::uint16_t number) const = 0;
  // Status: the local detail byte (the drive's error flags) and whether it is in a fault.
  [[nodiscard]] virtual std::uint8_t status_detail() const = 0;
  [[nodiscard]] virtual bool fault() const = 0;
};

}  // namespace ibs::pcp
