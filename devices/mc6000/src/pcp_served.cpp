#include "ibs/devices/mc6000/pcp_served.hpp"

namespace ibs::devices::mc6000 {

pcp::PcpError pcp_error(Refusal r) {
  namespace e = pcp::errors;
  switch (r) {
    case Refusal::none:
      return {};
    case Refusal::no_parameter:
      return e::kObjectDoesNotExist;
    case Refusal::read_only:
      return e::kNoAccess;
    case Refusal::bad_value:
      return e::kDataLength;  // the bytes do not make a value of the type
    case Refusal::too_high:
      return e::kValueTooHigh;
    case Refusal::too_low:
      return e::kValueTooLow;
    case Refusal::latched:
    case Refusal::not_now:
    case Refusal::eeprom_busy:
      return e::kNotExecutableNow;  // seed 000, 3 and 6: repeat once the cause is gone
  }
  return e::kNotExecutableNow;
}

pcp::PcpError PcpServed::read(Time now, std::uint16_t index, std::uint8_t subindex, pcp::Value& out) {
  // Read errors never enter 85-SERR (seed 000, 6.1 note).
  const auto number = pcp::number_of(index);
  if (!number || drive_->parameters().store().info(*number) == nullptr) return pcp::errors::kObjectDoesNotExist;
  if (subindex != 0) return pcp::errors::kInvalidSubindex;
  const auto v = drive_->read(now, *number);
  if (!v) return pcp::errors::kObjectDoesNotExist;
  out = *v;
  return {};
}

pcp::WriteAnswer PcpServed::write(Time now, std::uint16_t index, std::uint8_t subindex,
                                  std::span<const std::uint8_t> data) {
  const auto number = pcp::number_of(index);
  const pcp::ParameterInfo* p = number ? drive_->parameters().store().info(*number) : nullptr;
  if (p == nullptr) return {pcp_error(drive_->refuse(Refusal::no_parameter).refusal)};
  if (subindex != 0) {
    const WriteResult r = drive_->refuse(Refusal::no_parameter);
    return {r.refusal == Refusal::latched ? pcp_error(r.refusal) : pcp::errors::kInvalidSubindex};
  }
  const auto v = pcp::decode(p->type, data);
  const WriteResult r = drive_->write(now, *number, v ? std::optional<std::uint32_t>(v->raw) : std::nullopt);
  return {pcp_error(r.refusal), r.busy_for};
}

}  // namespace ibs::devices::mc6000
