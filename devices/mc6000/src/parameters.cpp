#include "ibs/devices/mc6000/parameters.hpp"

#include "ibs/devices/mc6000/service.hpp"

namespace ibs::devices::mc6000 {

std::span<const pcp::ParameterInfo> parameters() { return kParameters; }

std::optional<std::uint32_t> trace_raw(pcp::DataType t, std::int64_t value) {
  if (value < 0) {
    const auto v = pcp::value_from_signed_raw(t, value);
    return v ? std::optional<std::uint32_t>(v->raw) : std::nullopt;
  }
  const std::size_t bytes = pcp::size_of(t);
  if (bytes < 4 && value >= (std::int64_t{1} << (8U * bytes))) return std::nullopt;
  if (value > 0xFFFFFFFFLL) return std::nullopt;
  return static_cast<std::uint32_t>(value);
}

DriveParametersConfig drive_parameters_config(const DriveTiming& timing) {
  return {parameters(), &card_writeable, timing};
}

}  // namespace ibs::devices::mc6000
