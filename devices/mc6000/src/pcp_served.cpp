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
      return e::kNotExecutableNow;  // LUSTBUS manual 3 and 6: repeat once the cause is gone
  }
  return e::kNotExecutableNow;
}

namespace {

// What a PCP request changed, noted for a recording of the process-data words, which do not carry
// PCP (parameter_journal.hpp): the value written, 85-SERR when the request changed it.
class Noted {
 public:
  explicit Noted(DriveAccess& drive) : drive_(drive), serr_(drive.parameters().serr()) {}
  ~Noted() {
    drive::ParameterJournal* j = drive_.changes();
    if (j != nullptr && drive_.parameters().serr() != serr_) j->note(drive::kSiofNumber, drive_.parameters().serr());
  }
  Noted(const Noted&) = delete;
  Noted& operator=(const Noted&) = delete;
  void written(std::uint16_t number, std::uint32_t raw) {
    if (drive::ParameterJournal* j = drive_.changes()) j->note(number, raw);
  }

 private:
  DriveAccess& drive_;
  std::uint8_t serr_;
};

}  // namespace

pcp::PcpError PcpServed::read(Time now, std::uint16_t index, std::uint8_t subindex, pcp::Value& out) {
  const Noted noted(*drive_);  // a read of 85-SERR erases its bits
  // Read errors never enter 85-SERR (LUSTBUS manual 6.1 note).
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
  Noted noted(*drive_);  // a refusal enters its cause in 85-SERR
  const auto number = pcp::number_of(index);
  const pcp::ParameterInfo* p = number ? drive_->parameters().store().info(*number) : nullptr;
  if (p == nullptr) return {pcp_error(drive_->refuse(Refusal::no_parameter).refusal)};
  if (subindex != 0) {
    const WriteResult r = drive_->refuse(Refusal::no_parameter);
    return {r.refusal == Refusal::latched ? pcp_error(r.refusal) : pcp::errors::kInvalidSubindex};
  }
  const auto v = pcp::decode(p->type, data);
  const WriteResult r = drive_->write(now, *number, v ? std::optional<std::uint32_t>(v->raw) : std::nullopt);
  if (r.ok() && v) noted.written(*number, v->raw);
  return {pcp_error(r.refusal), r.busy_for};
}

}  // namespace ibs::devices::mc6000
