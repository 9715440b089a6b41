#include "ibs/devices/vf1000/driver.hpp"

#include <cstdio>

#include "ibs/drive/data_types.hpp"

namespace ibs::devices {

namespace vc = vf1000_channel;

namespace {

ParamKind kind_of(const vc::Outcome& o) {
  switch (o.kind) {
    case vc::OutcomeKind::value: return ParamKind::value;
    case vc::OutcomeKind::written: return ParamKind::written;
    case vc::OutcomeKind::description: return ParamKind::description;
    case vc::OutcomeKind::nak: return ParamKind::nak;
    case vc::OutcomeKind::timeout:
    case vc::OutcomeKind::protocol_error: return ParamKind::timeout;
    case vc::OutcomeKind::inverter_restarted:
    case vc::OutcomeKind::aborted: return ParamKind::aborted;
  }
  return ParamKind::timeout;
}

}  // namespace

Vf1000Driver::Vf1000Driver(const vc::ClientConfig& channel, const drivecom::SequencerConfig& config)
    : master_(config), client_(channel) {}

void Vf1000Driver::initial(const DriverIo& io) {
  master_.initial(io.pd_out);
  io.pd_out[2] = vc::Client::initial_word();
}

void Vf1000Driver::cycle(const DriverIo& io, Time now) {
  // A module error (the inverter initialising, 6.1) shows as words 0000H: the sequencer reads
  // NOT READY and the channel client sees RESET distinction 0.
  // A cycle without valid data: the channel reads nothing (its resync hold must count words the
  // inverter really saw), the sequencer sees the last status word again.
  const Word comm = client_.step(io.pd_in[2], now, io.data_valid);
  master_.cycle(io.pd_in, io.pd_out, now, comm);
}

void Vf1000Driver::restart(Time now) {
  master_.sequencer().restart();
  master_.set_frequency_hz(0.0);
  client_.restart(now);
}

ParamId Vf1000Driver::submit(ParamOp op, std::uint16_t number, std::int64_t value) {
  vc::Request r;
  switch (op) {
    case ParamOp::read: r = vc::value_inquiry(number); break;
    case ParamOp::write:
      if (value < -32768 || value > 65535) {
        last_refusal_ = vc::SubmitError::invalid_number;
        return 0;
      }
      r = vc::value_transfer(number, static_cast<Word>(value & 0xFFFF));
      break;
    case ParamOp::describe: r = vc::description_scan(number); break;
  }
  const vc::Submitted s = client_.submit(r);
  last_refusal_ = s.error;
  return s ? s.id : 0;
}

ParamStatus Vf1000Driver::status(ParamId id) const {
  if (id == 0) return {ParamKind::refused, 0};
  const vc::Outcome* o = client_.outcome(id);
  if (o == nullptr) {
    const vc::Poll p = client_.poll(id);
    if (p.state == vc::RequestState::unknown) return {ParamKind::refused, 0};
    return {ParamKind::pending, 0};
  }
  return {kind_of(*o), static_cast<std::int64_t>(o->value)};
}

std::string Vf1000Driver::describe(ParamId id) const {
  if (id == 0) return "refused: " + std::string(vc::to_string(last_refusal_));
  const vc::Outcome* o = client_.outcome(id);
  if (o == nullptr) return "pending";
  if (o->kind == vc::OutcomeKind::description) {
    const vc::Description d = vc::decode_description(o->description);
    char range[64];
    std::snprintf(range, sizeof range, ", min %04XH, max %04XH, default %04XH", static_cast<unsigned>(d.min),
                  static_cast<unsigned>(d.max), static_cast<unsigned>(d.default_value));
    std::string s = "description " + d.name;
    if (!d.unit.empty()) s += " [" + d.unit + "]";
    if (d.category) s += ", category " + std::string(1, drive::category_code(*d.category));
    if (d.type) s += ", type " + std::string(1, drive::type_code(*d.type));
    return s + range;
  }
  return vc::describe(*o);
}

}  // namespace ibs::devices
