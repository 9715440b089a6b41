#include "ibs/devices/mc6000/channel.hpp"

#include "ibs/devices/mc6000/parameters.hpp"

namespace ibs::devices::mc6000 {

pcp::LatencyModel pcp_latency(int channel_words) {
  // INTERBUS manual 7.2: a Read or Write takes 10..35 ms at the master "depending on processor
  // workload". The channel's own share depends on its width (the link moves one fragment per bus
  // cycle on the servo's INTERBUS CPU, docs/pcp.md): 3.4..5.9 ms over 4 words, 5.1..10.9 ms over 2
  // and 12.5..25.7 ms over 1 on buses of 0.567..0.989 ms cycles. The servo processor's time is
  // calibrated per width so that the sum spans the manual's window on those buses.
  pcp::LatencyModel m;
  switch (channel_words) {
    case 4:
      m.processing_min = 7ms;
      m.processing_max = 27ms;
      break;
    case 2:
      m.processing_min = 6ms;
      m.processing_max = 22ms;
      break;
    default:
      m.processing_min = 0ms;
      m.processing_max = 8ms;
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
