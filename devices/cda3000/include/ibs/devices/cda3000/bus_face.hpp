// The CDA3000's entry for CANLust in the registry of drive and bus (ibs/devices/drives.hpp): the
// drive `ibs canlust emulate` serves and `ibs run` simulates (Cda3000 behind a
// devices::CanlustDrive), the master driver the simulator runs them with (Driver behind a
// devices::CanlustMaster) and the parameter table of parameters.hpp.
#pragma once

#include <string_view>

#include "ibs/devices/canlust_face.hpp"

namespace ibs::devices::cda3000 {

// The name the command line and the registry give the drive ("cda3000@..." on the command line).
inline constexpr std::string_view kDriveName = "cda3000";

const CanlustFace& bus_face();

}  // namespace ibs::devices::cda3000
