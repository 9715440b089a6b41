#include "ibs/devices/mc6000/channel.hpp"

#include "ibs/devices/mc6000/parameters.hpp"

namespace ibs::devices::mc6000 {

pcp::LatencyModel pcp_latency(int channel_words) {
  // Seed 001, 7.2: a Read or Write takes 10..35 ms at the master.
  pcp::LatencyModel m;
  switch (channel_words) {
    case 4:
      m.processing_min = 7ms;
      m.processing_max = 27ms;
      break;
    case 2:
      m.processing_min = 0ms;
      m.processing_max = 21ms;
      break;
    default:
      m.processing_min = 0ms;
      m.processing_max = 2ms;
      break;
  }
  return m;
}

pcp::ServerConfig server_config(int channel_words) {
  pcp::ServerConfig c;
  c.channel_words = channel_words;
  c.latency_for = &pcp_latency;
  c.kbl = kKbl;
  c.identity.model = pcp::Name::from("MC6000");
  return c;
}

}  // namespace ibs::devices::mc6000
