#include "ibs/devices/mc6000/channel.hpp"

#include "ibs/devices/mc6000/parameters.hpp"

namespace ibs::devices::mc6000 {

pcp::ServerConfig server_config(int channel_words) {
  pcp::ServerConfig c;
  c.channel_words = channel_words;
  c.kbl = kKbl;
  c.identity.model = pcp::Name::from("MC6000");
  return c;
}

}  // namespace ibs::devices::mc6000
