// The MC6000's capture kind and value formats by 406-IBCNF (ibs/devices/capture.hpp,
// docs/pcap.md).
#pragma once

#include "ibs/devices/capture.hpp"

namespace ibs::devices::mc6000 {

const CaptureFace& capture_face();

}  // namespace ibs::devices::mc6000
