#include "ibs/devices/dfs1/status.hpp"

#include <array>
#include <utility>

#include "ibs/devices/dfs1/controller.hpp"

namespace ibs::devices::dfs1 {

namespace {

using Names = std::array<std::pair<std::uint8_t, std::string_view>, 8>;

// Bit 7 down, as the notes list them ("Status (81)"; ST1's order is inferred there).
constexpr Names kSt2Names = {{{kSt2Remote, "remote"},
                              {kSt2Slave, "slave"},
                              {kSt2AtSpeed, "at-speed"},
                              {kSt2Forward, "forward"},
                              {kSt2Fault, "fault"},
                              {kSt2Enabled, "enabled"},
                              {kSt2MicroFault, "uP-fault"},
                              {kSt2ZeroSpeed, "zero-speed"}}};
constexpr Names kSt1Names = {{{kSt1BusNotCharged, "bus-not-charged"},
                              {kSt1Ioc, "IOC"},
                              {kSt1Stall, "stall"},
                              {kSt1I2t, "I2t"},
                              {kSt1HeatsinkOvertemp, "heatsink-overtemp"},
                              {kSt1Commutation, "commutation"},
                              {kSt1Overvolt, "overvolt"},
                              {kSt1Undervolt, "undervolt"}}};

std::vector<std::string_view> set_bits(const Names& names, std::uint8_t s) {
  std::vector<std::string_view> out;
  for (const auto& [bit, name] : names) {
    if ((s & bit) != 0) out.push_back(name);
  }
  return out;
}

}  // namespace

std::vector<std::string_view> st2_flags(std::uint8_t st2) { return set_bits(kSt2Names, st2); }
std::vector<std::string_view> st1_flags(std::uint8_t st1) { return set_bits(kSt1Names, st1); }

}  // namespace ibs::devices::dfs1
