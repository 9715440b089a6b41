#include "ibs/devices/mc6000/capture.hpp"

#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/devices/mc6000/settings.hpp"

namespace ibs::devices::mc6000 {

namespace {

// The reference and actual value as 406-IBCNF lays them out: none when the layout
// exchanges no process data (IBCNF 0) or is the LISIM one; INTERBUS manual 3.2.3.
CaptureFormat format(const DeviceSettings& s) {
  CaptureFormat f;
  const int supi = supi_of(s);
  const int ibcnf = ibcnf_of(s);
  f.layout = {static_cast<std::uint8_t>(supi), static_cast<std::uint8_t>(ibcnf)};
  // The non-throwing form: this is in the master library, which the embedded build compiles
  // without exceptions. Settings the servo refuses never reach a capture; none for them anyway.
  const Expected<Layout> layout = try_make_layout(supi, ibcnf, interbus::BusKind::remote);
  if (!layout) {
    f.values = CaptureValues::none;
    return f;
  }
  switch (layout->exchanges_data ? layout->ibcnf : Ibcnf::none) {
    case Ibcnf::word16: f.values = CaptureValues::word16; break;
    case Ibcnf::q16: f.values = CaptureValues::q16; break;
    case Ibcnf::speed_torque: f.values = CaptureValues::speed_torque; break;
    case Ibcnf::none:
    case Ibcnf::lisim: f.values = CaptureValues::none; break;
  }
  return f;
}

}  // namespace

const CaptureFace& capture_face() {
  static const CaptureFace face{2, "MC6000", &format};
  return face;
}

}  // namespace ibs::devices::mc6000
