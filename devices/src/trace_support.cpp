#include "ibs/devices/trace_support.hpp"

namespace ibs::devices {

std::optional<trace::Outcome> trace_outcome(const drivecom::Report& r) {
  using trace::Outcome;
  switch (r.phase) {
    case drivecom::Phase::idle:
    case drivecom::Phase::moving: return std::nullopt;
    case drivecom::Phase::reached: return Outcome{Outcome::Kind::ok, std::nullopt};
    case drivecom::Phase::failed:
      return Outcome{r.failure == drivecom::Failure::timeout ? Outcome::Kind::timeout
                                                             : Outcome::Kind::nak,
                     std::nullopt};
  }
  return std::nullopt;
}

}  // namespace ibs::devices
