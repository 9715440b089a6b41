#include "ibs/devices/cda3000/bus_face.hpp"

namespace ibs::devices::cda3000 {

namespace {

std::unique_ptr<Cda3000> make(const CanlustFaceOptions& o) {
  DeviceConfig c;
  c.ids = o.ids;
  c.watchdog_reaction = o.watchdog_reaction;
  if (o.factory) {
    c.connector_address = o.address;
  } else {
    c.saved = commissioned_for_bus(o.address, o.cacnf);
  }
  return std::make_unique<Cda3000>(c);
}

}  // namespace

const CanlustFace& bus_face() {
  static const CanlustFace face{&make};
  return face;
}

}  // namespace ibs::devices::cda3000
