#include "ibs/devices/dfs1/bus_face.hpp"

#include "ibs/devices/dfs1/parameters.hpp"

namespace ibs::devices::dfs1 {

namespace {

std::unique_ptr<Controller> make(std::uint8_t uid, unsigned baud) {
  auto c = std::make_unique<Controller>(ControllerConfig{uid});
  // The baud rate code parameter holds the line's rate; a rate without a code leaves the factory one.
  if (auto code = code_for_baud(baud)) (void)c->set_parameter(kBaudCode, *code);
  return c;
}

}  // namespace

const Dfs1Face& bus_face() {
  static const Dfs1Face face{&make};
  return face;
}

}  // namespace ibs::devices::dfs1
