// The LUSTBUS host (host.hpp): its queue, the line side (the telegram handed out, characters in,
// the response, inter-character and exchange timeouts, the closing EOT), restart and the ring of
// outcomes. How a request begins and goes on after each exchange is host_steps.cpp; the requests
// and outcomes as values, host_requests.cpp.
#include "ibs/lustbus/host.hpp"

#include <algorithm>

#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/siof.hpp"

namespace ibs::lustbus {

namespace {

// Whether the request carries what its kind needs: the procedure's description, a CODE for its
// parameters, user data the device takes.
bool runnable(const Request& r) {
  switch (r.kind) {
    case RequestKind::download:
      return r.download != nullptr && parameter_code(r.download->family, r.download->parameter);
    case RequestKind::indexed_text:
      return r.indexed_text != nullptr &&
             parameter_code(r.indexed_text->family, r.indexed_text->index_parameter) &&
             text_code(r.indexed_text->family, r.parameter);
    case RequestKind::block_transfer: {
      const BlockTransferProcedure* p = r.block_transfer;
      if (p == nullptr || p->asks_answer == nullptr || r.unfit) return false;
      if (r.value.size() > p->max_user_data) return false;
      return r.value.empty() || p->asks_answer(r.value.view()[0]).has_value();
    }
    default:
      return true;
  }
}

}  // namespace

Host::Host(const HostConfig& config) : config_(config) {
  capacity_ = config_.queue_capacity == 0 ? 1 : config_.queue_capacity;
  queue_.resize(capacity_ + 1);
  done_.resize(config_.completed_capacity == 0 ? 1 : config_.completed_capacity);
  eeprom_free_.fill(Time::min());
}

Submitted Host::submit(const Request& r) {
  Submitted s;
  if (queued_ >= capacity_) {
    s.error = SubmitError::queue_full;
    return s;
  }
  switch (r.kind) {
    case RequestKind::enquiry:
    case RequestKind::select:
    case RequestKind::download:
    case RequestKind::indexed_text:
    case RequestKind::block_transfer:
      // 4.2 / 9.1: nothing answers at 31.
      if (r.address > kLastDeviceAddress) {
        s.error = SubmitError::invalid_address;
        return s;
      }
      break;
    case RequestKind::broadcast:
      if (r.address != kAddressBroadcast) {
        s.error = SubmitError::invalid_address;
        return s;
      }
      break;
    case RequestKind::scan:
      break;
  }
  if (!runnable(r)) {
    s.error = SubmitError::invalid_request;
    return s;
  }
  s.id = next_id_++;
  queue_[(head_ + queued_) % queue_.size()] = Slot{s.id, r};
  ++queued_;
  return s;
}

Duration Host::timeout_of(const Request& r) const {
  return r.response_timeout.value_or(config_.response_timeout);
}

Time Host::next_deadline() const {
  if (state_ == HostState::idle) return queued_ > 0 ? last_now_ : Time::max();
  if (out_size_ > 0 && !out_taken_) return last_now_;
  return deadline_;
}

std::span<const std::uint8_t> Host::take_output() {
  if (out_size_ == 0 || out_taken_) return {};
  out_taken_ = true;
  return {out_frame_.bytes.data(), out_size_};
}

void Host::step(Time now) {
  last_now_ = now;
  switch (state_) {
    case HostState::idle:
      if (queued_ > 0) start_job(now);
      return;
    case HostState::pausing:
      if (now >= deadline_) transmit_tx(now);
      return;
    case HostState::awaiting:
      if (now >= deadline_) {
        answer_kind_ = AnswerKind::none;
        answer_error_ = AnswerError::no_answer;
        start_eot(now);
      }
      return;
    case HostState::receiving:
    case HostState::draining:
      if (now >= deadline_) {
        if (now >= exchange_ends_) {
          // LB-D24: characters never stopped; the EOT goes out now, whatever is on the line.
          answer_kind_ = AnswerKind::none;
          answer_error_ = AnswerError::line_busy;
        } else if (state_ == HostState::receiving) {
          answer_kind_ = AnswerKind::none;
          answer_error_ = AnswerError::incomplete;
        }
        start_eot(now);
      }
      return;
    case HostState::turnaround:
      if (now >= deadline_) start_eot(now);
      return;
    case HostState::sending:
    case HostState::closing:
      return;
  }
}

void Host::receive(std::uint8_t b, Time now) { receive(std::span<const std::uint8_t>(&b, 1), now); }

void Host::receive(std::span<const std::uint8_t> bytes, Time now) {
  if (bytes.empty()) return;  // no character: nothing happened at `now` (last_now_ stays)
  last_now_ = now;
  std::size_t i = 0;
  while (i < bytes.size()) {
    switch (state_) {
      case HostState::awaiting:
      case HostState::receiving: {
        // The characters of one read share `now`, and so the deadline each would set.
        state_ = HostState::receiving;
        deadline_ = std::min(now + config_.inter_char_timeout, exchange_ends_);
        i += decoder_.feed(bytes.subspan(i));
        const auto st = decoder_.status();
        if (st == AnswerDecoder::Status::done) {
          answer_kind_ = decoder_.kind();
          answer_error_ = AnswerError::none;
          state_ = HostState::turnaround;
          deadline_ = now + config_.turnaround;
          if (config_.turnaround <= Duration{0}) start_eot(now);
        } else if (st == AnswerDecoder::Status::error) {
          answer_kind_ = AnswerKind::none;
          answer_error_ = decoder_.error();
          state_ = HostState::draining;
        }
        continue;
      }
      case HostState::draining:
        deadline_ = std::min(now + config_.inter_char_timeout, exchange_ends_);
        return;
      default:
        return;  // characters outside an answer are noise: ignored
    }
  }
}

void Host::output_done(Time now) {
  last_now_ = now;
  if (out_size_ == 0 || !out_taken_) return;
  out_size_ = 0;
  out_taken_ = false;
  if (state_ == HostState::sending) {
    if (tx_.address == kAddressBroadcast) {  // EOT telegram EOT went out in one piece
      answer_kind_ = AnswerKind::none;
      answer_error_ = AnswerError::none;
      tx_done(now);
      return;
    }
    state_ = HostState::awaiting;
    deadline_ = now + tx_.timeout;
    exchange_ends_ = now + config_.exchange_limit(tx_.timeout);
  } else if (state_ == HostState::closing) {
    if (!active_) {  // the EOT of restart()
      state_ = HostState::idle;
      deadline_ = Time::max();
      if (queued_ > 0) start_job(now);
      return;
    }
    tx_done(now);
  }
}

void Host::start_eot(Time now) {
  (void)now;
  out_frame_.size = 0;
  out_frame_.push(kEot);  // 3: EOT after each data sequence
  out_size_ = 1;
  out_taken_ = false;
  state_ = HostState::closing;
  deadline_ = Time::max();
}

void Host::send(const Tx& tx, Time now) {
  tx_ = tx;
  ++tx_attempts_;
  transmit_tx(now);
}

void Host::send_later(const Tx& tx, Time at) {
  tx_ = tx;
  ++tx_attempts_;
  state_ = HostState::pausing;
  deadline_ = at;
}

void Host::transmit_tx(Time now) {
  tx_started_ = now;
  if (tx_.enquiry) {
    encode_enquiry(out_frame_, tx_.address, tx_.code);
    decoder_.start(tx_.address, tx_.code, AnswerDecoder::Expect::text_or_nak, answer_binary_prefix(tx_.code));
  } else {
    encode_select(out_frame_, tx_.address, tx_.code, tx_.value);
    if (tx_.address == kAddressBroadcast) out_frame_.push(kEot);
    decoder_.start(tx_.address, tx_.code, AnswerDecoder::Expect::ack_or_nak);
  }
  out_size_ = out_frame_.size;
  out_taken_ = false;
  state_ = HostState::sending;
  deadline_ = Time::max();
}

void Host::enquiry_phase(Phase p, Address a, const Code& c, Duration timeout, Time now) {
  phase_ = p;
  tx_attempts_ = 0;
  // send(Tx{a, c, {}, true, timeout}, now), the fields set in place: an ENQUIRY carries no VALUE
  // (6.1), and a Value shows nothing past its size, so clearing it is the empty one.
  tx_.address = a;
  tx_.code = c;
  tx_.value.clear();
  tx_.enquiry = true;
  tx_.timeout = timeout;
  ++tx_attempts_;
  transmit_tx(now);
}

void Host::select_phase(Phase p, const Code& c, const Value& v, Time now) {
  phase_ = p;
  select_return_ = p;
  tx_attempts_ = 0;
  select_attempts_ = 1;
  select_tx_ = Tx{request().address, c, v, false, timeout_of(request())};
  send_select(select_tx_, p == Phase::main, now);
}

void Host::send_select(const Tx& tx, bool own_step, Time now) {
  // 10.2.2: "For SELECT-telegrams to EEPROM parameters, a wait time is needed, if the duration
  // of a telegram sequence is shorter than the time required to save the parameter in EEPROM."
  const Time free = own_step && request().eeprom_width > 0 ? eeprom_free_at(tx.address) : Time::min();
  if (free > now) {
    out_->eeprom_wait = free - now;
    send_later(tx, free);
    return;
  }
  send(tx, now);
}

Time Host::eeprom_free_at(Address a) const {
  // Address 0 reaches whichever device answers there, 31 every device: wait for all of them.
  if (a != kAddressAny && a != kAddressBroadcast) return std::max(eeprom_free_[a], eeprom_free_[kAddressAny]);
  return *std::max_element(eeprom_free_.begin(), eeprom_free_.end());
}

void Host::note_eeprom_save() {
  const std::uint8_t width = request().eeprom_width;
  if (width == 0) return;
  // 10.2.2: "memory time = parameter data width · 3 · 5 ms", from the start of the sequence whose
  // duration the wait time subtracts; the device saves while the sequence goes on.
  const Time done = tx_started_ + eeprom_wait(width, config_.eeprom_write_time, Duration{0});
  const Address a = request().address;
  if (a != kAddressAny && a != kAddressBroadcast) {
    eeprom_free_[a] = std::max(eeprom_free_[a], done);
    return;
  }
  for (Time& t : eeprom_free_) t = std::max(t, done);
}

void Host::next_scan_address(Time now) {
  ++scan_address_;
  if (scan_address_ > kLastDeviceAddress) {
    finish(OutcomeKind::scan, now);
    return;
  }
  enquiry_phase(Phase::scan_type, scan_address_, kTypeCode, config_.scan_response_timeout, now);
}

void Host::finish(OutcomeKind k, Time now) {
  out_->kind = k;
  out_->finished = now;
  slot_of(job_->id).id = job_->id;
  active_ = false;
  state_ = HostState::idle;
  deadline_ = Time::max();
  if (queued_ > 0) start_job(now);
}

void Host::restart(Time now) {
  if (active_) {
    out_->kind = OutcomeKind::aborted;
    out_->finished = now;
    slot_of(job_->id).id = job_->id;
    active_ = false;
  }
  while (queued_ > 0) {
    const Slot& q = queue_[head_];
    Finished& f = slot_of(q.id);
    f.id = q.id;
    f.outcome = Outcome{};
    f.outcome.kind = OutcomeKind::aborted;
    f.outcome.started = now;
    f.outcome.finished = now;
    head_ = (head_ + 1) % queue_.size();
    --queued_;
  }
  // An EOT resets whatever the devices had received (3); output_done() then ends in idle.
  start_eot(now);
  last_now_ = now;
}

const Outcome* Host::outcome(RequestId id) const {
  if (id == 0) return nullptr;
  const Finished& f = done_[(id - 1) % done_.size()];
  return f.id == id ? &f.outcome : nullptr;
}

Poll Host::poll(RequestId id) const {
  if (active_ && job_->id == id) return {RequestState::active, nullptr};
  for (std::size_t i = 0; i < queued_; ++i) {
    if (queue_[(head_ + i) % queue_.size()].id == id) return {RequestState::queued, nullptr};
  }
  if (const Outcome* o = outcome(id)) return {RequestState::done, o};
  return {RequestState::unknown, nullptr};
}

BaudScan::BaudScan(std::span<const std::uint32_t> rates) : rates_(rates) {}

std::optional<std::uint32_t> BaudScan::current() const {
  if (finished()) return std::nullopt;
  return rates_[next_];
}

Request BaudScan::request() const { return enquiry(kAddressAny, kTypeCode); }

void BaudScan::report(const Outcome& o) {
  if (finished()) return;
  if (o.kind == OutcomeKind::value || o.kind == OutcomeKind::nak) {
    found_ = rates_[next_];  // anything readable answered at this rate
    return;
  }
  ++next_;
}

}  // namespace ibs::lustbus
