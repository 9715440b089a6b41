// The VF1000's campaign profile (devices/campaign_profile.hpp): what the fault campaign needs of
// the inverter. Defined in the device library (ibs_vf1000_device, src/campaign_profile.cpp), since
// it observes the inverter's emulator; the registry hands it out (DriveKind::campaign).
#pragma once

#include "ibs/devices/campaign_profile.hpp"

namespace ibs::devices::vf1000 {

const CampaignProfile& campaign_profile();

}  // namespace ibs::devices::vf1000
