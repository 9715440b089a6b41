#include "ibs/canlust/errors.hpp"

namespace ibs::canlust {

std::optional<ErrorInfo> find_error(std::uint8_t number) {
  for (const auto& e : kErrorTable) {
    if (e.number == number) return e;
  }
  return std::nullopt;
}

std::string_view to_string(ErrorReaction r) {
  switch (r) {
    case ErrorReaction::warning: return "WRN";
    case ErrorReaction::stop: return "STOP";
    case ErrorReaction::quick_stop: return "quick stop";
    case ErrorReaction::disable_power: return "disable power";
  }
  return "?";
}

}  // namespace ibs::canlust
