#include "ibs/devices/mc6000/parameters.hpp"

#include "ibs/devices/mc6000/service.hpp"

namespace ibs::devices::mc6000 {

std::span<const pcp::ParameterInfo> parameters() { return kParameters; }

DriveParametersConfig drive_parameters_config(const DriveTiming& timing) {
  return {parameters(), &card_writeable, timing};
}

}  // namespace ibs::devices::mc6000
