// The VF1000's communication-word channel as the drive sets it up (INTERBUS manual 4.1; LUSTBUS manual 10):
// the inverter's server configuration for its parameter table (parameters.hpp).
#pragma once

#include "ibs/vf1000_channel/server.hpp"

namespace ibs::devices::vf1000 {

// 71-PROG = 1 loads the factory defaults; the ~4 s initialisation after power-on (6.1).
vf1000_channel::ServerConfig server_config();

}  // namespace ibs::devices::vf1000
