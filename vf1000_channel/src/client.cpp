#include "ibs/vf1000_channel/client.hpp"

#include <stdexcept>

#include "ibs/base/number_text.hpp"
#include "ibs/drive/siof.hpp"

namespace ibs::vf1000_channel {

namespace {

constexpr Code code_of(RequestKind k) {
  switch (k) {
    case RequestKind::value_inquiry:
      return Code::value_inquiry;
    case RequestKind::value_transfer:
      return Code::value_transfer;
    case RequestKind::description_scan:
      return Code::description_scan;
  }
  return Code::value_inquiry;
}

// i mod n for i < 2n, without a division on the cycle path.
constexpr std::size_t wrap(std::size_t i, std::size_t n) {
  return i >= n ? i - n : i;
}

std::string hex4(Word w) { return hex_text(w, 4) + "H"; }

}  // namespace

std::string_view to_string(RequestKind k) {
  switch (k) {
    case RequestKind::value_inquiry:
      return "value inquiry";
    case RequestKind::value_transfer:
      return "value transfer";
    case RequestKind::description_scan:
      return "description scan";
  }
  return "?";
}

std::string_view to_string(OutcomeKind k) {
  switch (k) {
    case OutcomeKind::value:
      return "value";
    case OutcomeKind::written:
      return "written";
    case OutcomeKind::description:
      return "description";
    case OutcomeKind::nak:
      return "NAK";
    case OutcomeKind::timeout:
      return "timeout";
    case OutcomeKind::inverter_restarted:
      return "inverter restarted";
    case OutcomeKind::aborted:
      return "aborted by a master restart";
    case OutcomeKind::protocol_error:
      return "protocol error";
  }
  return "?";
}

std::string_view to_string(NakCause c) {
  switch (c) {
    case NakCause::none:
      return "none";
    case NakCause::no_parameter:
      return "no such parameter";
    case NakCause::control_bits:
      return "unintended control bits";
    case NakCause::siof:
      return "cause read from 85-SIOF";
    case NakCause::siof_unread:
      return "85-SIOF could not be read";
  }
  return "?";
}

std::string_view to_string(SubmitError e) {
  switch (e) {
    case SubmitError::none:
      return "none";
    case SubmitError::queue_full:
      return "request queue full";
    case SubmitError::invalid_number:
      return "parameter number above 3FFH";
  }
  return "?";
}

std::string_view to_string(ClientState s) {
  switch (s) {
    case ClientState::resync:
      return "resync";
    case ClientState::idle:
      return "idle";
    case ClientState::exchanging:
      return "exchanging";
    case ClientState::closing:
      return "closing";
  }
  return "?";
}

std::string describe(const Outcome& o) {
  switch (o.kind) {
    case OutcomeKind::value:
      return "value " + hex4(o.value);
    case OutcomeKind::written:
      return "written " + hex4(o.value);
    case OutcomeKind::description: {
      const Description d = decode_description(o.description);
      return "description " + d.name + " [" + d.unit + "] category " +
             static_cast<char>(o.description[10]) + " type " +
             static_cast<char>(o.description[11]) + " min " + hex4(d.min) + " max " + hex4(d.max) +
             " default " + hex4(d.default_value);
    }
    case OutcomeKind::nak:
      if (o.nak_cause == NakCause::siof) return "NAK: 85-SIOF " + drive::describe_siof(o.siof);
      return "NAK: " + std::string(to_string(o.nak_cause));
    case OutcomeKind::timeout:
    case OutcomeKind::inverter_restarted:
    case OutcomeKind::aborted:
    case OutcomeKind::protocol_error:
      return std::string(to_string(o.kind)) + " after " + std::to_string(o.answers) +
             " answers of the inverter";
  }
  return "?";
}

Error Client::validate(const ClientConfig& config) {
  if (config.queue_capacity == 0 || config.completed_capacity == 0) {
    return {ErrorCode::channel_capacity_zero,
            "vf1000_channel::Client: queue_capacity and completed_capacity must be at least 1"};
  }
  if (config.timeout <= Duration{0}) {
    return {ErrorCode::channel_timeout_not_positive,
            "vf1000_channel::Client: timeout must be positive"};
  }
  return {};
}

namespace {
const ClientConfig& checked(const ClientConfig& config) {
  detail::require<std::invalid_argument>(Client::validate(config));
  return config;
}
}  // namespace

Client::Client(const ClientConfig& config)
    : config_(checked(config)),
      queue_(config.queue_capacity),
      completed_(config.completed_capacity) {
  state_ = config.start_synchronised ? ClientState::idle : ClientState::resync;
}

Submitted Client::submit(const Request& r) {
  if (r.number > kMaxParameterNumber) return {0, SubmitError::invalid_number};
  if (queue_.full()) return {0, SubmitError::queue_full};
  const RequestId id = next_id_++;
  queue_.push({id, r});
  return {id, SubmitError::none};
}

Poll Client::poll(RequestId id) const {
  if (id == 0 || id >= next_id_) return {};
  if (active_ && current().id == id) return {RequestState::active, {}};
  for (std::size_t i = active_ ? 1 : 0; i < queue_.size(); ++i) {
    if (queue_[i].id == id) return {RequestState::queued, {}};
  }
  const Outcome* o = outcome(id);
  if (o == nullptr) return {};
  return {RequestState::done, *o};
}

const Outcome* Client::outcome(RequestId id) const {
  if (id == 0 || id >= next_id_) return nullptr;
  std::size_t i = completed_next_;
  for (std::size_t n = 0; n < completed_.size(); ++n) {
    i = (i == 0 ? completed_.size() : i) - 1;
    if (completed_[i].id == id) return &completed_[i].outcome;
  }
  return nullptr;
}

void Client::restart(Time now) {
  if (active_) fail(OutcomeKind::aborted, answers_so_far());
  while (!queue_.empty()) {
    activate_next(now);
    fail(OutcomeKind::aborted, 0);
  }
  // As a freshly started master: knows nothing of the inverter, holds CODE 0 to resync.
  siof_unread_ = false;
  last_siof_.reset();
  enter_resync(now);
}

void Client::activate_next(Time now) {
  // The active request stays at the head of the queue until it completes.
  active_ = true;
  transfer_refused_ = false;
  const Request& r = current().request;
  const Duration t = r.timeout > Duration{0} ? r.timeout : config_.timeout;
  deadline_ = now + t;
}

Outcome& Client::complete(OutcomeKind k, std::uint8_t answers) {
  // Filled in place, field by field: no temporary to copy on the cycle path.
  Completed& c = completed_[completed_next_];
  completed_next_ = wrap(completed_next_ + 1, completed_.size());
  c.id = current().id;
  queue_.pop();
  Outcome& o = c.outcome;
  o.kind = k;
  o.nak_cause = NakCause::none;
  o.siof = 0;
  o.answers = answers;
  o.value = 0;
  if (k != OutcomeKind::description) o.description.fill(0);
  active_ = false;
  transfer_refused_ = false;
  return o;
}

void Client::fail(OutcomeKind k, std::uint8_t answers) {
  // After a refused transfer the NAK is known; only its cause is missing (4.1.4).
  const bool refused = transfer_refused_;
  Outcome& o = complete(refused ? OutcomeKind::nak : k, answers);
  if (refused) o.nak_cause = NakCause::siof_unread;
}

std::uint8_t Client::answers_so_far() const {
  return state_ == ClientState::exchanging ? answers_ : 0;
}

Word Client::enter_resync(Time now) {
  state_ = ClientState::resync;
  resync_since_ = now;
  resync_started_ = true;
  out_ = kMasterIdleWord;
  return out_;
}

Word Client::enter_closing() {
  // Back to the starting position (4.1.3.1.1 row 5); the inverter answers with wait mode.
  state_ = ClientState::closing;
  out_ = kMasterIdleWord;
  return out_;
}

Word Client::step(Word in, Time now, bool data_valid) {
  if (!active_ && !queue_.empty()) activate_next(now);
  if (!data_valid) {
    // The bus delivered nothing this cycle: `in` is an old word and the master's word did not
    // reach the inverter either. Only time runs: a transaction's deadline still ends it, and a
    // resync hold starts over, since it counts CODE 0 words the inverter has really seen.
    if (active_ && now >= deadline_) {
      if (transfer_refused_) siof_unread_ = true;
      const bool was_exchanging = state_ == ClientState::exchanging;
      fail(OutcomeKind::timeout, answers_so_far());
      if (was_exchanging) enter_resync(now);
    }
    if (state_ == ClientState::resync) resync_started_ = false;
    return out_;
  }

  const bool ready = inverter_ready(in);
  if (!ready) {
    // RESET distinction 0: the inverter (re)initialises (4.1.2.2, 6.1). Whatever was running is
    // gone on its side; its 85-SIOF now carries the power-on bit.
    if (active_ && (state_ == ClientState::exchanging || transfer_refused_)) {
      fail(OutcomeKind::inverter_restarted, answers_so_far());
    }
    siof_unread_ = true;
    enter_resync(now);
  }

  if (active_ && now >= deadline_) {
    if (transfer_refused_) siof_unread_ = true;
    const bool was_exchanging = state_ == ClientState::exchanging;
    fail(OutcomeKind::timeout, answers_so_far());
    // Mid-telegram the inverter's state is unknown: resync. Closing / resync go on as they are.
    if (was_exchanging) return enter_resync(now);
  }
  if (!ready) return out_;

  switch (state_) {
    case ClientState::resync:
      if (!resync_started_) {
        resync_since_ = now;
        resync_started_ = true;
      }
      if (!inverter_idle(in) || now - resync_since_ < config_.resync_hold) return out_;
      state_ = ClientState::idle;
      break;
    case ClientState::closing:
      // The ACK/NAK word has been seen, so the first word without it proves the CODE 0 arrived.
      if (!inverter_idle(in)) return out_;
      state_ = ClientState::idle;
      break;
    case ClientState::exchanging:
      return answer(in, now);
    case ClientState::idle:
      break;
  }

  // Idle: start the next telegram of the active transaction.
  if (!active_) return out_ = kMasterIdleWord;
  if (transfer_refused_) return start_exchange(Exchange::siof_after);
  if (current().request.kind == RequestKind::value_transfer && siof_unread_) {
    return start_exchange(Exchange::siof_before);
  }
  return start_exchange(Exchange::main);
}

Word Client::start_exchange(Exchange e) {
  exchange_ = e;
  answers_ = 0;
  toggle_ = true;  // a change from the starting position's toggle 0 (4.1.3.1.1 row 1)
  const bool main = e == Exchange::main;
  code_ = main ? code_of(current().request.kind) : Code::value_inquiry;
  const std::uint16_t number = main ? current().request.number : drive::kSiofNumber;
  state_ = ClientState::exchanging;
  out_ = master_start_word(toggle_, code_, number);
  return out_;
}

Word Client::send_next(std::uint8_t data) {
  toggle_ = !toggle_;  // "new data can be accepted" (4.1.2.1 bit 5)
  out_ = master_word(toggle_, code_, 0, data);
  return out_;
}

Word Client::answer(Word in, Time now) {
  // The inverter has answered the last word when its toggle equals ours (4.1.2.2 bit 5).
  if (inverter_toggle(in) != toggle_) return out_;

  const bool ack = inverter_ack(in);
  const std::uint8_t data = low_byte(in);
  const std::uint8_t taken = answers_;
  ++answers_;

  if (inverter_nak(in)) {
    switch (exchange_) {
      case Exchange::main:
        if (code_ == Code::value_transfer) {
          // 4.1.4: read 85-SIOF before anything else, for the cause and to unlock transfers.
          transfer_refused_ = true;
          return enter_closing();
        }
        complete(OutcomeKind::nak, answers_).nak_cause =
            taken == 0 ? NakCause::no_parameter : NakCause::control_bits;
        return enter_closing();
      case Exchange::siof_before:
        // 85-SIOF could not be read; go on with the transfer, which reads it after a NAK.
        siof_unread_ = false;
        return enter_closing();
      case Exchange::siof_after:
        siof_unread_ = true;
        complete(OutcomeKind::nak, answers_).nak_cause = NakCause::siof_unread;
        return enter_closing();
    }
  }

  // Which answers carry ACK is fixed by the tables: only the last one.
  const std::uint8_t expected = code_ == Code::value_inquiry    ? 2
                                : code_ == Code::value_transfer ? 3
                                                                : kDescriptionLength;
  const bool last = answers_ == expected;
  if (ack != last) {
    if (exchange_ == Exchange::siof_after) siof_unread_ = true;
    fail(OutcomeKind::protocol_error, answers_);
    return enter_resync(now);  // the inverter's state is unclear
  }

  switch (code_) {
    case Code::value_inquiry: {
      if (!last) {
        high_ = data;
        return send_next(0);
      }
      const Word value = make_word(high_, data);
      const std::uint16_t number =
          exchange_ == Exchange::main ? current().request.number : drive::kSiofNumber;
      if (number == drive::kSiofNumber) {
        last_siof_ = low_byte(value);
        siof_unread_ = false;
      }
      switch (exchange_) {
        case Exchange::main:
          complete(OutcomeKind::value, answers_).value = value;
          break;
        case Exchange::siof_before:
          break;  // the transfer follows
        case Exchange::siof_after: {
          Outcome& o = complete(OutcomeKind::nak, answers_);
          o.nak_cause = NakCause::siof;
          o.siof = low_byte(value);
          break;
        }
      }
      return enter_closing();
    }
    case Code::value_transfer:
      if (!last) {
        // Answer 1: PNR taken, DAT1 goes out; answer 2: DAT1 taken, DAT2 (4.1.3.2.1 rows 3, 5).
        return send_next(taken == 0 ? high_byte(current().request.value)
                                    : low_byte(current().request.value));
      }
      complete(OutcomeKind::written, answers_).value = current().request.value;
      return enter_closing();
    case Code::description_scan:
      record_[taken] = data;
      if (!last) return send_next(0);
      complete(OutcomeKind::description, answers_).description = record_;
      return enter_closing();
    case Code::reset:
      break;
  }
  return out_;
}

}  // namespace ibs::vf1000_channel
