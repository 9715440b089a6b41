#include "ibs/devices/vf1000/channel.hpp"

#include "ibs/devices/vf1000/parameters.hpp"

namespace ibs::devices::vf1000 {

vf1000_channel::ServerConfig server_config() {
  vf1000_channel::ServerConfig c;
  c.factory_defaults_parameter = pnr::kProg;
  return c;
}

}  // namespace ibs::devices::vf1000
