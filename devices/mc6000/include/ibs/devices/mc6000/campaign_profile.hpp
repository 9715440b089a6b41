// The MC6000's campaign profile (devices/campaign_profile.hpp): what the fault campaign needs of
// the servo. Defined in the device library (ibs_mc6000_device, src/campaign_profile.cpp), since it
// observes the servo's emulator; the registry hands it out (DriveKind::campaign).
#pragma once

#include "ibs/devices/campaign_profile.hpp"

namespace ibs::devices::mc6000 {

const CampaignProfile& campaign_profile();

}  // namespace ibs::devices::mc6000
