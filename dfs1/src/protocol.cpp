#include "ibs/dfs1/protocol.hpp"

namespace ibs::dfs1 {

std::string_view to_string(Command c) {
  const CommandInfo* row = find_command(static_cast<std::uint8_t>(c));
  return row != nullptr ? row->name : "unknown command";
}

std::string_view error_name(std::uint8_t code) {
  switch (code) {
    case 0x80:
      return "not in remote";
    case 0x81:
      return "illegal speed";
    case 0x82:
      return "illegal parameter number";
    case 0x83:
      return "illegal parameter value";
    case 0x84:
      return "illegal channel";
    case 0x85:
      return "illegal channel value";
    case 0x86:
      return "illegal command";
    default:
      return "unknown error";
  }
}

}  // namespace ibs::dfs1
