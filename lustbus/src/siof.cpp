#include "ibs/lustbus/siof.hpp"

namespace ibs::lustbus {

std::string_view to_string(SiofRemedy r) {
  switch (r) {
    case SiofRemedy::none:
      return "no error, the device was started anew";
    case SiofRemedy::fix_host:
      return "fix the host, or it is too slow";
    case SiofRemedy::wait_and_repeat:
      return "wait (> 60 ms) and repeat the telegram";
    case SiofRemedy::repeat:
      return "repeat the telegram";
    case SiofRemedy::host_error:
      return "service error or error in the host's software";
    case SiofRemedy::check_writability:
      return "check whether the parameter is writable at all or in this operating mode";
    case SiofRemedy::other_value:
      return "choose a different value";
  }
  return "?";
}

std::string describe_siof(std::uint8_t siof) { return drive::describe_siof(siof); }

}  // namespace ibs::lustbus
