// The DFS-1 controller's entry for its bus in the registry of drive and bus
// (ibs/devices/drives.hpp): the controller `ibs dfs1 emulate` serves, one per UID.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "ibs/devices/dfs1/controller.hpp"

namespace ibs::devices::dfs1 {

// The name the command line and the registry give the drive ("dfs1@..." on the command line).
inline constexpr std::string_view kDriveName = "dfs1";

struct Dfs1Face {
  // The controller at `uid` (1..255), answering at `baud` where its baud rate code parameter has a
  // code for it (docs/dfs1.md); throws std::invalid_argument for UID 0.
  std::unique_ptr<Controller> (*make)(std::uint8_t uid, unsigned baud) = nullptr;
};

const Dfs1Face& bus_face();

}  // namespace ibs::devices::dfs1
