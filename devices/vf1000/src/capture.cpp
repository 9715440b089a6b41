#include "ibs/devices/vf1000/capture.hpp"

namespace ibs::devices::vf1000 {

namespace {

// docs/pcap.md, "Values": the reference frequency in 0.05 Hz per bit with the direction in the control
// word, the actual frequency signed in 0.05 Hz; no layout settings.
CaptureFormat format(const DeviceSettings& /*settings*/) { return {CaptureValues::hz_005, {0, 0}}; }

}  // namespace

const CaptureFace& capture_face() {
  static const CaptureFace face{1, "VF1000", &format};
  return face;
}

}  // namespace ibs::devices::vf1000
