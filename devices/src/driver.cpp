#include "ibs/devices/driver.hpp"

namespace ibs::devices {

std::string_view to_string(ParamOp op) {
  switch (op) {
    case ParamOp::read: return "read";
    case ParamOp::write: return "write";
    case ParamOp::describe: return "describe";
  }
  return "?";
}

std::string_view to_string(ParamKind k) {
  switch (k) {
    case ParamKind::pending: return "pending";
    case ParamKind::value: return "value";
    case ParamKind::written: return "written";
    case ParamKind::description: return "description";
    case ParamKind::nak: return "nak";
    case ParamKind::timeout: return "timeout";
    case ParamKind::aborted: return "aborted";
    case ParamKind::refused: return "refused";
  }
  return "?";
}

}  // namespace ibs::devices
