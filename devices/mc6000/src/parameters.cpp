#include "ibs/devices/mc6000/parameters.hpp"

namespace ibs::devices::mc6000 {

std::span<const pcp::ParameterInfo> parameters() { return kParameters; }

}  // namespace ibs::devices::mc6000
