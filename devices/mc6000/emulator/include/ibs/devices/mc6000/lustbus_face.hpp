// The MC6000's entry for LUSTBUS in the registry of drive and bus (ibs/devices/drives.hpp).
#pragma once

#include "ibs/devices/lustbus_face.hpp"

namespace ibs::devices::mc6000 {

const LustbusFace& lustbus_face();

}  // namespace ibs::devices::mc6000
