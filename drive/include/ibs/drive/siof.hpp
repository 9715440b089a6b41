// 85-SIOF/SERR, the family's serial-interface error flags: written once, in the object dictionary
// (od/include/ibs/od/siof.hpp, issue 38). This header keeps drive::'s names for the code that has
// not moved to od:: yet.
#pragma once

#include "ibs/od/siof.hpp"

namespace ibs::drive {

using od::describe_siof;
using od::kSiofBits;
using od::kSiofNumber;
using od::siof_has;
using od::siof_mask;
using od::SiofBit;
using od::to_string;

}  // namespace ibs::drive
