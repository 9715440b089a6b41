// The CDA3000's entry for CANLust in the registry of drive and bus (ibs/devices/drives.hpp):
// the drive `ibs canlust emulate` serves, one per address.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "ibs/devices/cda3000/device.hpp"

namespace ibs::devices::cda3000 {

// The name the command line and the registry give the drive ("cda3000@..." on the command line).
inline constexpr std::string_view kDriveName = "cda3000";

struct CanlustFaceOptions {
  canlust::IdentifierMap ids{};
  // 6.1: the reaction programmed for the bus watchdog (574-CAWDG).
  canlust::ErrorReaction watchdog_reaction = canlust::ErrorReaction::disable_power;
  // true: an uncommissioned drive at the connector's address (2.1, 0..7); false: a drive
  // commissioned for the bus as 7.1.2 does it, at 571-CLADR = address with 492-CACNF = cacnf.
  bool factory = false;
  std::uint8_t address = 1;
  std::uint8_t cacnf = 2;
};

struct CanlustFace {
  // Throws std::invalid_argument for a configuration the drive refuses.
  std::unique_ptr<Cda3000> (*make)(const CanlustFaceOptions& options) = nullptr;
};

const CanlustFace& bus_face();

}  // namespace ibs::devices::cda3000
