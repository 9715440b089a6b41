#include "ibs/devices/mc6000/driver.hpp"

#include <algorithm>

#include "ibs/devices/mc6000/parameters.hpp"

namespace ibs::devices {

namespace {

ParamKind kind_of(const pcp::Result& r, ParamOp op) {
  switch (r.kind) {
    case pcp::ResultKind::ok:
      return op == ParamOp::read ? ParamKind::value : op == ParamOp::write ? ParamKind::written
                                                                           : ParamKind::description;
    case pcp::ResultKind::negative:
    case pcp::ResultKind::incompatible:
    case pcp::ResultKind::type_mismatch: return ParamKind::nak;
    case pcp::ResultKind::timeout:
    case pcp::ResultKind::protocol_error: return ParamKind::timeout;
    case pcp::ResultKind::aborted:
    case pcp::ResultKind::link_reset: return ParamKind::aborted;
  }
  return ParamKind::timeout;
}

}  // namespace

Mc6000Driver::Mc6000Driver(const mc6000::Layout& layout, const drivecom::SequencerConfig& config)
    : master_(layout, config) {
  if (layout.pcp_words > 0) {
    channel_ = true;
    pcp_config_.channel_words = layout.pcp_words;
    client_.emplace(pcp_config_);
  }
}

bool Mc6000Driver::use_pcp_client(pcp::ParameterClient& client) {
  if (!channel_) return false;
  carrier_ = &client;
  client_.reset();
  return true;
}

void Mc6000Driver::initial(const DriverIo& io) {
  skip_ = nullptr;
  master_.initial(io.pd_out);
  std::fill(io.pcp_out.begin(), io.pcp_out.end(), Word{0});
  if (client_ && !io.pcp_out.empty()) client_->show(Time{0}, io.pcp_out);
}

Duration Mc6000Driver::request_timeout(Duration at_least) const {
  const Duration base = at_least > Duration::zero() ? at_least : pcp_config_.request_timeout;
  return std::max(base, period_ * kTimeoutCycles);
}

void Mc6000Driver::cycle(const DriverIo& io, Time now) {
  // A driver with a PCP channel out of line; one without (SUPI 12) is the process data alone,
  // and its common case calls nothing (Mc6000PdMaster::cycle) and saves no register: every call
  // from here is the last thing it does.
  if (channel_) {
    cycle_with_pcp(io, now);
    return;
  }
  // Without a channel, the process data is all there is and nothing waits for time: a cycle that
  // only held lets the master loop skip the next ones while the hold lasts (skip_while_holding).
  if (master_.cycle_holding(io.pd_in, io.pd_out)) {
    skip_ = &master_.sequencer();
    return;
  }
  skip_ = nullptr;
  master_.cycle_general(io.pd_in, io.pd_out, now);  // nothing for no words out
}

void Mc6000Driver::cycle_with_pcp(const DriverIo& io, Time now) {
  // The bus period, learnt from the times cycle() is called with, sets the PCP requests'
  // timeouts (request_timeout, start_next) and nothing else: a driver without a channel has no
  // use for it.
  if (cycled_ && now > last_cycle_) period_ = std::max(period_, now - last_cycle_);
  last_cycle_ = now;
  cycled_ = true;
  if (!io.pd_out.empty()) master_.cycle(io.pd_in, io.pd_out, now);
  if (carrier_ != nullptr) {
    run_channel(*carrier_, now, {}, {});  // the channel is not in the words
    return;
  }
  if (io.pcp_out.empty()) return;
  run_channel(*client_, now, io.pcp_in, io.pcp_out);
}

template <typename Channel>
void Mc6000Driver::run_channel(Channel& c, Time now, std::span<const Word> s2m, std::span<Word> m2s) {
  take_results(c);
  start_next(c, now);
  c.step(now, s2m, m2s);
  take_results(c);
}

void Mc6000Driver::restart(Time now) {
  skip_ = nullptr;
  master_.sequencer().restart();
  master_.set_reference_rpm(0.0);
  if (!channel_) return;
  // Everything queued ends aborted; the channel starts over without an association.
  pcp::Result r;
  r.kind = pcp::ResultKind::aborted;
  r.completed_at = now;
  for (; !queue_.empty(); queue_.pop()) complete(queue_.front(), ParamKind::aborted, 0, r);
  active_ = initiating_ = false;
  if (carrier_ != nullptr) {
    carrier_->abort(now);  // ends the association; an outstanding request's result is nobody's
    while (carrier_->take_result_view() != nullptr) {
    }
  } else {
    client_.emplace(pcp_config_);
  }
}

void Mc6000Driver::complete(const Pending& p, ParamKind kind, std::int64_t value, const pcp::Result& r) {
  Completed& c = completed_[completed_next_];
  completed_next_ = (completed_next_ + 1) % kCompletedCapacity;
  c.id = p.id;
  c.kind = kind;
  c.value = value;
  c.result = r;
}

template <typename Channel>
void Mc6000Driver::take_results(Channel& c) {
  while (const pcp::Result* r = c.take_result_view()) {  // no copy: complete() makes one
    if (!active_ || queue_.empty()) continue;  // nobody waits for it (e.g. after a restart)
    const Pending head = queue_.front();
    active_ = false;
    if (initiating_) {
      initiating_ = false;
      if (r->ok()) continue;  // associated: the request itself goes out next
      complete(head, r->kind == pcp::ResultKind::timeout ? ParamKind::timeout : ParamKind::aborted, 0, *r);
    } else {
      std::int64_t value = 0;
      if (r->ok() && head.op == ParamOp::read) {
        if (r->value) {
          value = pcp::signed_raw(*r->value);
        } else {
          for (const std::uint8_t b : r->data.view()) value = (value << 8) | b;
        }
      }
      complete(head, kind_of(*r, head.op), value, *r);
    }
    queue_.pop();
  }
}

template <typename Channel>
void Mc6000Driver::start_next(Channel& c, Time now) {
  // The first request waits for a second cycle: its timeout needs the cycle time.
  if (active_ || queue_.empty() || c.busy() || period_ == Duration::zero()) return;
  const Pending& p = queue_.front();
  if (!c.associated()) {
    if (c.initiate(now, request_timeout(Duration::zero())) == pcp::SubmitStatus::accepted) {
      active_ = initiating_ = true;
    }
    return;
  }
  const pcp::ParameterRef ref = pcp::ParameterRef::number(p.number);
  const pcp::ParameterInfo* info = pcp::find_parameter(mc6000::kParameters, p.number);
  pcp::SubmitStatus s = pcp::SubmitStatus::invalid_argument;
  switch (p.op) {
    case ParamOp::read:
      s = info != nullptr ? c.read(now, ref, info->type, request_timeout(Duration::zero()))
                          : c.read(now, ref, request_timeout(Duration::zero()));
      break;
    case ParamOp::write: {
      // The value's type is the parameter's; for a number the table does not know, 16 bits (the
      // servo refuses it as a missing object anyway).
      const pcp::DataType t = info != nullptr ? info->type : pcp::DataType::usign16;
      // 4-PROG = 1 loads the factory defaults; the servo confirms after up to 10 s (LUSTBUS manual,
      // 10): that write gets the time it needs, plus the usual confirmation time.
      const Duration timeout = request_timeout(p.number == mc6000::kProg && p.value == mc6000::kProgFactoryDefaults
                                                   ? kFactoryDefaultsTimeout
                                                   : Duration::zero());
      if (const auto v = pcp::value_from_signed_raw(t, p.value)) s = c.write(now, ref, *v, timeout);
      break;
    }
    case ParamOp::describe: s = c.get_ov(now, ref, request_timeout(Duration::zero())); break;
  }
  if (s == pcp::SubmitStatus::accepted) {
    active_ = true;
    return;
  }
  pcp::Result r;
  r.kind = pcp::ResultKind::negative;
  r.submitted_at = r.completed_at = now;
  complete(p, ParamKind::refused, 0, r);
  queue_.pop();
}

ParamId Mc6000Driver::submit(ParamOp op, std::uint16_t number, std::int64_t value) {
  if (!channel_) {
    refusal_ = Refusal::no_channel;
    return 0;
  }
  if (queue_.full()) {
    refusal_ = Refusal::queue_full;
    return 0;
  }
  const ParamId id = next_id_++;
  if (next_id_ == 0) next_id_ = 1;
  queue_.push({id, op, number, value});
  return id;
}

const Mc6000Driver::Completed* Mc6000Driver::find_completed(ParamId id) const {
  for (const Completed& c : completed_) {
    if (c.id == id && id != 0) return &c;
  }
  return nullptr;
}

ParamStatus Mc6000Driver::status(ParamId id) const {
  if (id == 0) return {ParamKind::refused, 0};
  if (const Completed* c = find_completed(id)) return {c->kind, c->value};
  for (std::size_t i = 0; i < queue_.size(); ++i) {
    if (queue_[i].id == id) return {ParamKind::pending, 0};
  }
  return {ParamKind::refused, 0};  // unknown, or pushed out of the completed ring
}

std::string Mc6000Driver::describe(ParamId id) const {
  if (id == 0) {
    switch (refusal_) {
      case Refusal::no_channel: return "refused: this layout (405-SUPI) has no PCP channel";
      case Refusal::queue_full: return "refused: the request queue is full";
      case Refusal::bad_value:
      case Refusal::none: break;
    }
    return "refused";
  }
  const Completed* c = find_completed(id);
  if (c == nullptr) return status(id).kind == ParamKind::pending ? "pending" : "unknown request";
  const pcp::Result& r = c->result;
  switch (c->kind) {
    case ParamKind::value: {
      std::string s = "value " + std::to_string(c->value);
      if (r.value) s += " (" + std::string(pcp::to_string(r.value->type)) + ")";
      return s;
    }
    case ParamKind::written: return "written (PCP Write confirmed)";
    case ParamKind::description: {
      const pcp::ObjectDescription& d = r.description;
      return "description " + std::string(d.name.view()) + ", " + std::string(pcp::to_string(d.type)) + ", " +
             std::string(pcp::to_string(d.category)) + ", " + std::to_string(d.min) + ".." +
             std::to_string(d.max) + ", default " + std::to_string(d.default_value);
    }
    case ParamKind::nak:
      if (r.kind == pcp::ResultKind::negative) return "negative confirmation: " + pcp::to_string(r.error);
      return "refused: " + std::string(pcp::to_string(r.kind));
    case ParamKind::refused: return "refused: the value does not fit the parameter's type";
    case ParamKind::timeout:
    case ParamKind::aborted:
    case ParamKind::pending: break;
  }
  return std::string(to_string(c->kind)) + " (" + std::string(pcp::to_string(r.kind)) + ")";
}

}  // namespace ibs::devices
