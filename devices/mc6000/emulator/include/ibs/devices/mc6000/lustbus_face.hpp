// The MC6000's entry for LUSTBUS in the registry of drive and bus (ibs/devices/drives.hpp).
#pragma once

#include "ibs/devices/lustbus_face.hpp"

namespace ibs::devices::mc6000 {

const LustbusFace& lustbus_face();

// The servo's procedures of the LUSTBUS manual 11 as a LUSTBUS host runs them: the dataset download
// through 80-SLOAD (11.4), the value substitution texts through 108-STEXT (11.3) and PosMOD1 over
// CODE 49999 (11.6). Static: requests may point into it.
const lustbus::DeviceProcedures& lustbus_procedures();

}  // namespace ibs::devices::mc6000
