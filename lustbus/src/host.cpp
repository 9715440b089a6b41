#include "ibs/lustbus/host.hpp"

#include <algorithm>

#include "ibs/lustbus/description.hpp"

#include <string>

#include "ibs/lustbus/siof.hpp"

namespace ibs::lustbus {

namespace {

// 11.4: a handshake value, INTEGER16 sent as its 16-bit two's complement (2.3.2).
Value handshake_value(const DownloadProcedure& p, std::int16_t v) {
  return format_raw(p.family, static_cast<std::uint16_t>(v)).value;
}

}  // namespace

std::string_view to_string(RequestKind k) {
  switch (k) {
    case RequestKind::enquiry:
      return "enquiry";
    case RequestKind::select:
      return "select";
    case RequestKind::broadcast:
      return "broadcast";
    case RequestKind::scan:
      return "scan";
    case RequestKind::download:
      return "download";
    case RequestKind::indexed_text:
      return "indexed_text";
    case RequestKind::block_transfer:
      return "block_transfer";
  }
  return "?";
}

std::string_view to_string(OutcomeKind k) {
  switch (k) {
    case OutcomeKind::value:
      return "value";
    case OutcomeKind::acknowledged:
      return "acknowledged";
    case OutcomeKind::sent:
      return "sent";
    case OutcomeKind::nak:
      return "nak";
    case OutcomeKind::no_answer:
      return "no_answer";
    case OutcomeKind::bad_answer:
      return "bad_answer";
    case OutcomeKind::scan:
      return "scan";
    case OutcomeKind::downloaded:
      return "downloaded";
    case OutcomeKind::download_refused:
      return "download_refused";
    case OutcomeKind::download_rejected:
      return "download_rejected";
    case OutcomeKind::download_timeout:
      return "download_timeout";
    case OutcomeKind::aborted:
      return "aborted";
  }
  return "?";
}

std::string_view to_string(SubmitError e) {
  switch (e) {
    case SubmitError::none:
      return "none";
    case SubmitError::queue_full:
      return "queue full";
    case SubmitError::invalid_address:
      return "invalid address";
    case SubmitError::invalid_request:
      return "invalid request";
  }
  return "?";
}

std::string_view to_string(HostState s) {
  switch (s) {
    case HostState::idle:
      return "idle";
    case HostState::pausing:
      return "pausing";
    case HostState::sending:
      return "sending";
    case HostState::awaiting:
      return "awaiting";
    case HostState::receiving:
      return "receiving";
    case HostState::draining:
      return "draining";
    case HostState::turnaround:
      return "turnaround";
    case HostState::closing:
      return "closing";
  }
  return "?";
}

std::string describe(const Outcome& o) {
  std::string s(to_string(o.kind));
  if (o.kind == OutcomeKind::value) s += " " + std::string(o.value.view());
  if (o.answer_error != AnswerError::none) s += ", " + std::string(to_string(o.answer_error));
  if (o.siof) s += ", 85-SIOF " + describe_siof(*o.siof);
  if (o.kind == OutcomeKind::download_rejected) {
    s += ", first invalid parameter " + std::to_string(o.rejected_parameter);
  }
  if (o.kind == OutcomeKind::download_refused) s += ", step " + std::to_string(o.failed_step);
  if (o.kind == OutcomeKind::scan) s += ", " + std::to_string(o.scan.count) + " devices";
  return s;
}

std::optional<Code> parameter_code(Family f, unsigned parameter, bool description) {
  if (f == Family::standard) return vf_code(parameter, description ? VfSpecifier::description : VfSpecifier::value);
  return mc_code(description ? McCodeKind::description : McCodeKind::value, parameter);
}

std::string_view device_kind(Family f) { return f == Family::standard ? "inverter" : "servo"; }

Request enquiry(Address a, const Code& c) {
  Request r;
  r.kind = RequestKind::enquiry;
  r.address = a;
  r.code = c;
  return r;
}
Request select(Address a, const Code& c, const Value& v) {
  Request r;
  r.kind = RequestKind::select;
  r.address = a;
  r.code = c;
  r.value = v;
  return r;
}
Request broadcast(const Code& c, const Value& v) {
  Request r = select(kAddressBroadcast, c, v);
  r.kind = RequestKind::broadcast;
  return r;
}
Request network_scan() {
  Request r;
  r.kind = RequestKind::scan;
  return r;
}
std::optional<Code> text_code(Family f, unsigned parameter) {
  if (f != Family::enhanced) return std::nullopt;  // 2.4.1 has no text CODEs
  return mc_code(McCodeKind::substitution_text, parameter);
}

Request download(const DownloadProcedure& p, Address a, std::span<const Assignment> records) {
  Request r;
  r.kind = RequestKind::download;
  r.address = a;
  r.records = records;
  r.download = &p;
  return r;
}

Request block_transfer_request(const BlockTransferProcedure& p, Address a,
                               std::string_view user_data) {
  Request r;
  r.kind = RequestKind::block_transfer;
  r.address = a;
  r.code = p.code;
  r.block_transfer = &p;
  const auto v = Value::from(user_data);
  r.value = v.value_or(Value{});
  // A user data the VALUE cannot hold, or longer than the device takes: refused by submit().
  r.unfit = !v || user_data.size() > p.max_user_data;
  return r;
}

Request indexed_text_request(const IndexedTextProcedure& p, Address a, std::uint16_t parameter,
                             std::uint32_t index) {
  Request r;
  r.kind = RequestKind::indexed_text;
  r.address = a;
  r.parameter = parameter;
  r.text_index = index;
  r.indexed_text = &p;
  return r;
}

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
  (void)now;
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

void Host::start_job(Time now) {
  job_ = &queue_[head_];
  head_ = (head_ + 1) % queue_.size();
  --queued_;
  active_ = true;
  Finished& f = slot_of(job_->id);
  f.id = 0;  // not readable until it ends
  out_ = &f.outcome;
  out_->kind = OutcomeKind::aborted;
  out_->value.clear();
  out_->answer_error = AnswerError::none;
  out_->siof.reset();
  out_->attempts = 0;
  out_->scan.count = 0;
  out_->failed_step = 0;
  out_->rejected_parameter = 0;
  out_->started = now;
  out_->finished = now;
  tx_attempts_ = 0;
  select_attempts_ = 0;
  const Request& r = request();
  switch (r.kind) {
    case RequestKind::enquiry:
      enquiry_phase(Phase::main, r.address, r.code, timeout_of(r), now);
      return;
    case RequestKind::select:
      select_phase(Phase::main, r.code, r.value, now);
      return;
    case RequestKind::broadcast:
      phase_ = Phase::main;
      send(Tx{kAddressBroadcast, r.code, r.value, false, timeout_of(r)}, now);
      return;
    case RequestKind::scan:
      scan_address_ = 0;
      next_scan_address(now);
      return;
    case RequestKind::download:
      // 11.4 step 1.
      select_phase(Phase::dl_start, handshake_code(),
                   handshake_value(*r.download, r.download->start), now);
      return;
    case RequestKind::block_transfer:
      if (r.value.empty()) {
        enquiry_phase(Phase::block_enquiry, r.address, r.block_transfer->code, timeout_of(r), now);
      } else {
        select_phase(Phase::block_select, r.block_transfer->code, r.value, now);
      }
      return;
    case RequestKind::indexed_text: {
      // 11.3 step 2: the index parameter = the value whose text is wanted (USIGN).
      const IndexedTextProcedure& p = *r.indexed_text;
      const auto v = format_raw(p.family, r.text_index);
      const auto c = parameter_code(p.family, p.index_parameter);
      select_phase(Phase::text_select, c.value_or(Code{}), v.value, now);
      return;
    }
  }
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
  send(select_tx_, now);
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

// A SELECT step succeeded.
void Host::on_select_like_ack(Time now) {
  out_->attempts = select_attempts_;
  switch (select_return_) {
    case Phase::main:
      finish(OutcomeKind::acknowledged, now);
      return;
    case Phase::dl_start:
    case Phase::dl_record: {
      // 11.4 step 2: the records, one SELECT each; then step 3.
      record_ = select_return_ == Phase::dl_start ? 0 : record_ + 1;
      const auto& recs = request().records;
      if (record_ < recs.size()) {
        select_phase(Phase::dl_record, recs[record_].code, recs[record_].value, now);
      } else {
        const DownloadProcedure& p = *request().download;
        select_phase(Phase::dl_end, handshake_code(), handshake_value(p, p.end), now);
      }
      return;
    }
    case Phase::dl_end:
      // 11.4 step 4: poll the handshake, within the timeout.
      poll_started_ = now;
      phase_ = Phase::dl_poll;
      tx_attempts_ = 0;
      send_later(Tx{request().address, handshake_code(), {}, true, timeout_of(request())},
                 now + config_.download_poll_interval);
      return;
    case Phase::text_select: {
      const auto c = text_code(request().indexed_text->family, request().parameter);
      enquiry_phase(Phase::text_enquiry, request().address, c.value_or(Code{}),
                    timeout_of(request()), now);
      return;
    }
    default:
      return;
  }
}

// A SELECT step failed for good: `k` with out_->siof / answer_error already set.
void Host::on_select_like_failure(OutcomeKind k, Time now) {
  out_->attempts = select_attempts_;
  switch (select_return_) {
    case Phase::main:
    case Phase::text_select:
      finish(k, now);
      return;
    case Phase::dl_start:
      out_->failed_step = kDownloadStartStep;
      finish(OutcomeKind::download_refused, now);
      return;
    case Phase::dl_record:
      out_->failed_step = static_cast<std::int32_t>(record_);
      finish(OutcomeKind::download_refused, now);
      return;
    case Phase::dl_end:
      out_->failed_step = static_cast<std::int32_t>(request().records.size());
      finish(OutcomeKind::download_refused, now);
      return;
    default:
      finish(k, now);
      return;
  }
}

// One telegram exchange ended (EOT sent): answer_kind_ / answer_error_ / decoder_.value().
void Host::tx_done(Time now) {
  const Request& r = request();
  const bool answered = answer_kind_ != AnswerKind::none;
  switch (phase_) {
    case Phase::block_select:
    case Phase::block_error_select:
      out_->attempts = tx_attempts_;
      if (answer_kind_ == AnswerKind::ack) {
        const BlockTransferProcedure& p = *r.block_transfer;
        if (phase_ == Phase::block_error_select) {
          enquiry_phase(Phase::block_error_enquiry, r.address, p.code, timeout_of(r), now);
        } else if (p.asks_answer(r.value.view()[0]).value_or(false)) {
          enquiry_phase(Phase::block_enquiry, r.address, p.code, timeout_of(r), now);
        } else {
          finish(OutcomeKind::acknowledged, now);
        }
        return;
      }
      if (answer_kind_ != AnswerKind::nak) {
        finish_unanswered(now);
      } else if (phase_ == Phase::block_select) {
        read_block_error(now);
      } else {
        finish(OutcomeKind::nak, now);  // the error read itself refused
      }
      return;
    case Phase::block_enquiry:
    case Phase::block_error_enquiry:
      out_->attempts = tx_attempts_;
      if (phase_ == Phase::block_error_enquiry) {
        if (answer_kind_ == AnswerKind::text) out_->value = decoder_.value();
        finish(OutcomeKind::nak, now);
        return;
      }
      if (answer_kind_ == AnswerKind::text) {
        out_->value = decoder_.value();
        finish(OutcomeKind::value, now);
      } else if (answer_kind_ == AnswerKind::nak) {
        read_block_error(now);
      } else {
        finish_unanswered(now);
      }
      return;
    case Phase::main:
      if (r.kind == RequestKind::broadcast) {
        out_->attempts = tx_attempts_;
        finish(OutcomeKind::sent, now);
        return;
      }
      if (r.kind == RequestKind::enquiry) {
        out_->attempts = tx_attempts_;
        if (answer_kind_ == AnswerKind::text) {
          out_->value = decoder_.value();
          finish(OutcomeKind::value, now);
        } else if (answer_kind_ == AnswerKind::nak) {
          finish(OutcomeKind::nak, now);  // 6.1 note: no cause in 85 for an ENQUIRY
        } else if (tx_attempts_ <= config_.enquiry_retries && !reads_siof(tx_.code)) {
          send(tx_, now);  // reading is harmless to repeat — except 85, which clears (9.2)
        } else {
          finish_unanswered(now);
        }
        return;
      }
      [[fallthrough]];
    case Phase::dl_start:
    case Phase::dl_record:
    case Phase::dl_end:
    case Phase::text_select:
      // A SELECT step.
      if (answer_kind_ == AnswerKind::ack) {
        on_select_like_ack(now);
        return;
      }
      if (!answered && answer_error_ == AnswerError::no_answer) {
        // No retry: the device may have taken it; the caller decides (LB-D5).
        out_->answer_error = answer_error_;
        on_select_like_failure(OutcomeKind::no_answer, now);
        return;
      }
      // 6.2 note, 9.2: after a NAK read 85-SIOF/SERR before anything else. Also after a broken
      // answer: it may have been a NAK, and the latch would refuse every further SELECT.
      select_failure_ = answer_kind_ == AnswerKind::nak ? OutcomeKind::nak : OutcomeKind::bad_answer;
      select_error_ = answered ? AnswerError::none : answer_error_;
      phase_ = Phase::siof_read;
      tx_attempts_ = 0;
      send(Tx{r.address, kSiofCode, {}, true, timeout_of(r)}, now);
      return;
    case Phase::siof_read: {
      out_->answer_error = select_error_;
      if (answer_kind_ != AnswerKind::text) {
        out_->siof.reset();  // the cause is lost; no second read (it would clear nothing known)
        on_select_like_failure(select_failure_, now);
        return;
      }
      const auto raw = parse_raw(Family::enhanced, decoder_.value().view());
      if (!raw.ok() || raw.value > 0xFFFFU) {
        out_->siof.reset();
        on_select_like_failure(select_failure_, now);
        return;
      }
      const auto siof = static_cast<std::uint8_t>(raw.value & 0xFFU);
      out_->siof = siof;
      // 9.2 "What to do": repeat after EEPROM busy (wait first) or a checksum error, and after a
      // refusal by the latch alone (power on / watchdog, now cleared by the read).
      if (select_failure_ == OutcomeKind::nak && select_may_be_repeated(siof) &&
          select_attempts_ <= config_.select_retries) {
        ++select_attempts_;
        phase_ = select_return_;
        tx_attempts_ = 0;
        if (select_needs_eeprom_wait(siof)) {
          send_later(select_tx_, now + config_.eeprom_busy_wait);
        } else {
          send(select_tx_, now);
        }
        return;
      }
      on_select_like_failure(select_failure_, now);
      return;
    }
    case Phase::scan_type:
      if (answer_kind_ == AnswerKind::text) {
        ScanEntry& e = out_->scan.devices[out_->scan.count++];
        e = ScanEntry{};
        e.address = scan_address_;
        const auto t = parse_raw(Family::enhanced, decoder_.value().view());
        e.type = t.ok() ? t.value : 0;
        enquiry_phase(Phase::scan_probe, scan_address_, kServoProbeCode,
                      config_.scan_response_timeout, now);
        return;
      }
      next_scan_address(now);
      return;
    case Phase::scan_probe: {
      ScanEntry& e = out_->scan.devices[out_->scan.count - 1];
      if (answer_kind_ == AnswerKind::text) {
        e.family = Family::enhanced;
      } else if (answer_kind_ == AnswerKind::nak) {
        e.family = Family::standard;
      }
      next_scan_address(now);
      return;
    }
    case Phase::dl_poll: {
      if (answer_kind_ == AnswerKind::text) {
        const auto v =
            parse_typed(r.download->family, DataType::integer16, decoder_.value().view());
        if (v.ok()) {
          const auto handshake = static_cast<std::int16_t>(v.value);
          if (handshake == 0) {
            finish(OutcomeKind::downloaded, now);
            return;
          }
          if (handshake > 0) {
            out_->rejected_parameter = static_cast<std::uint32_t>(handshake);
            finish(OutcomeKind::download_rejected, now);
            return;
          }
        }
      }
      // -1: still testing and saving; no or a broken answer: keep polling until the timeout.
      if (now - poll_started_ >= config_.download_timeout) {
        finish(OutcomeKind::download_timeout, now);
        return;
      }
      tx_attempts_ = 0;
      send_later(tx_, now + config_.download_poll_interval);
      return;
    }
    case Phase::text_enquiry:
      out_->attempts = tx_attempts_;
      if (answer_kind_ == AnswerKind::text) {
        out_->value = decoder_.value();
        finish(OutcomeKind::value, now);
      } else if (answer_kind_ == AnswerKind::nak) {
        finish(OutcomeKind::nak, now);  // 11.3: no parameter, no text, or the index too large
      } else if (tx_attempts_ <= config_.enquiry_retries) {
        send(tx_, now);
      } else {
        finish_unanswered(now);
      }
      return;
  }
}

// The answer did not come, or failed the checks: the request ends with what the decoder found.
void Host::finish_unanswered(Time now) {
  out_->answer_error = answer_error_;
  finish(answer_error_ == AnswerError::no_answer ? OutcomeKind::no_answer : OutcomeKind::bad_answer, now);
}

// 11.6: after a NAK "the Host computer ascertains the error using the read command" the
// device's description names.
void Host::read_block_error(Time now) {
  const BlockTransferProcedure& p = *request().block_transfer;
  phase_ = Phase::block_error_select;
  tx_attempts_ = 0;
  send(Tx{request().address, p.code, p.error_read, false, timeout_of(request())}, now);
}

Code Host::handshake_code() const {
  const DownloadProcedure& p = *request().download;
  return parameter_code(p.family, p.parameter).value_or(Code{});
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
