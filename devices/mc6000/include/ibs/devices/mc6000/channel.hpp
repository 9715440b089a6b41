// The MC6000's PCP channel as the servo sets it up (INTERBUS manual 4.2): its communication-links-list
// entry (4.2.2), its identity and the parameters of its table that do more than store a value.
#pragma once

#include "ibs/pcp/server.hpp"

namespace ibs::devices::mc6000 {

// INTERBUS manual 4.2.2: 134 bytes each way; server for Get-OV long, Read, Write, Information Report.
inline constexpr pcp::Kbl kKbl = pcp::kDefaultServerKbl;

// The servo's processing time for a PCP request by channel width, calibrated so that a Read or
// Write, end to end at the master, spans INTERBUS manual 7.2's 10..35 ms as the workload goes 0..1 (bus
// cycle 0.567 ms of one MC6000 on the ring, 1 ms samples): 4 words 7..27 ms, 2 words 0..21 ms.
// One word cannot: its segmentation alone takes 33..36 ms, so processing gets 0..2 ms
// (docs/pcp.md, errata).
pcp::LatencyModel pcp_latency(int channel_words);

// The servo's PCP server over `channel_words` words (405-SUPI): "Lust" / "MC6000" / "PCP 2.0" as
// its identity, pcp_latency() for whatever width the server is finally given. What it serves is
// the drive core's (pcp_served.hpp).
pcp::ServerConfig server_config(int channel_words);

}  // namespace ibs::devices::mc6000
