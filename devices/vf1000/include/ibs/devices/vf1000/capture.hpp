// The VF1000's capture kind and value format (ibs/devices/capture.hpp, docs/pcap.md).
#pragma once

#include "ibs/devices/capture.hpp"

namespace ibs::devices::vf1000 {

const CaptureFace& capture_face();

}  // namespace ibs::devices::vf1000
