#include "ibs/devices/dfs1/parameters.hpp"

namespace ibs::devices::dfs1 {

namespace {
constexpr std::array<std::uint32_t, 8> kBaudCodes = {1200,  2400,  4800,  9600,
                                                     19200, 38400, 57600, 115200};
}  // namespace

const ParameterInfo* find_parameter(std::uint8_t number) {
  for (const auto& p : kParameters) {
    if (p.number == number) return &p;
  }
  return nullptr;
}

std::optional<std::uint32_t> baud_for_code(std::uint32_t code) {
  if (code >= kBaudCodes.size()) return std::nullopt;
  return kBaudCodes[code];
}

std::optional<std::uint32_t> code_for_baud(std::uint32_t baud) {
  for (std::size_t i = 0; i < kBaudCodes.size(); ++i) {
    if (kBaudCodes[i] == baud) return static_cast<std::uint32_t>(i);
  }
  return std::nullopt;
}

}  // namespace ibs::devices::dfs1
