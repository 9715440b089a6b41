// The MC6000's procedures of the LUSTBUS manual 11 (download, substitution texts, PosMOD1) as its wing
// describes them to a host, for the wings' LUSTBUS tests that run them (ibs::mc6000_lustbus).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "ibs/devices/mc6000/lustbus_face.hpp"
#include "ibs/lustbus/host.hpp"

namespace ibs::lustbus::devtest {

inline const DeviceProcedures& servo_procedures() {
  return devices::mc6000::lustbus_procedures();
}
inline Request servo_download(Address a, std::span<const Assignment> records) {
  return download(*servo_procedures().download, a, records);
}
inline Request substitution_text_request(Address a, std::uint16_t parameter, std::uint32_t index) {
  return indexed_text_request(*servo_procedures().indexed_text, a, parameter, index);
}
inline Request posmod_request(Address a, std::string_view user_data) {
  return block_transfer_request(*servo_procedures().block_transfer, a, user_data);
}

}  // namespace ibs::lustbus::devtest
