// The VF1000's entry for LUSTBUS in the registry of drive and bus (ibs/devices/drives.hpp).
#pragma once

#include "ibs/devices/lustbus_face.hpp"

namespace ibs::devices::vf1000 {

const LustbusFace& lustbus_face();

}  // namespace ibs::devices::vf1000
