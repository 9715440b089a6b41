#include "ibs/can/transport.hpp"

namespace ibs::can {

std::string_view to_string(IoStatus s) {
  switch (s) {
    case IoStatus::ok: return "ok";
    case IoStatus::timeout: return "timeout";
    case IoStatus::error: return "error";
  }
  return "?";
}

}  // namespace ibs::can
