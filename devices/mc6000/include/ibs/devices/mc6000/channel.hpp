// The MC6000's PCP channel as the servo sets it up (seed 001, 4.2): its communication-links-list
// entry (4.2.2), its identity and the parameters of its table that do more than store a value.
#pragma once

#include "ibs/pcp/server.hpp"

namespace ibs::devices::mc6000 {

// Seed 001, 4.2.2: 134 bytes each way; server for Get-OV long, Read, Write, Information Report.
inline constexpr pcp::Kbl kKbl = pcp::kDefaultServerKbl;

// The servo's PCP server over `channel_words` words (405-SUPI): "Lust" / "MC6000" / "PCP 2.0" as
// its identity. What it serves is the drive core's (pcp_served.hpp).
pcp::ServerConfig server_config(int channel_words);

}  // namespace ibs::devices::mc6000
