#include "ibs/pcp/client.hpp"

#include <stdexcept>
#include <string>

namespace ibs::pcp {

std::string_view to_string(SubmitStatus s) {
  switch (s) {
    case SubmitStatus::accepted:
      return "accepted";
    case SubmitStatus::busy:
      return "busy: a request is outstanding";
    case SubmitStatus::not_initiated:
      return "not initiated";
    case SubmitStatus::invalid_argument:
      return "invalid argument";
  }
  return "?";
}

std::string_view to_string(ResultKind k) {
  switch (k) {
    case ResultKind::ok:
      return "ok";
    case ResultKind::negative:
      return "negative";
    case ResultKind::incompatible:
      return "incompatible KBL";
    case ResultKind::type_mismatch:
      return "type mismatch";
    case ResultKind::aborted:
      return "aborted";
    case ResultKind::link_reset:
      return "link reset";
    case ResultKind::timeout:
      return "timeout";
    case ResultKind::protocol_error:
      return "protocol error";
  }
  return "?";
}

namespace {

LinkConfig link_config(const ClientConfig& cfg) {
  LinkConfig l;
  l.channel_words = cfg.channel_words;
  l.direction = Direction::to_server;
  l.ack_timeout = cfg.link_ack_timeout;
  return l;
}

const ClientConfig& checked(const ClientConfig& cfg) {
  detail::require<std::invalid_argument>(Client::validate(cfg));
  return cfg;
}

}  // namespace

Error Client::validate(const ClientConfig& cfg) {
  // The Initiate request and its negative confirmation are 20 bytes: below that no association.
  constexpr std::uint16_t kInitiateSize = 20;
  if (cfg.kbl.max_pdu_sending < kInitiateSize || cfg.kbl.max_pdu_sending > kMaxPduSize ||
      cfg.kbl.max_pdu_receiving < kInitiateSize || cfg.kbl.max_pdu_receiving > kMaxPduSize) {
    return {ErrorCode::channel_pdu_size_invalid,
            "PCP client KBL: max PDU sizes must be 20..134 bytes (got sending " +
                std::to_string(cfg.kbl.max_pdu_sending) + ", receiving " +
                std::to_string(cfg.kbl.max_pdu_receiving) + ")"};
  }
  if (cfg.request_timeout <= Duration::zero()) {
    return {ErrorCode::channel_timeout_not_positive, "PCP client request_timeout must be positive"};
  }
  return Link::validate(link_config(cfg));
}

Client::Client(const ClientConfig& cfg) : cfg_(checked(cfg)), link_(link_config(cfg)) {}

SubmitStatus Client::submit(Time now, RequestPdu& req, Duration timeout, bool needs_association) {
  if (outstanding_) return SubmitStatus::busy;
  if (needs_association && !associated_) return SubmitStatus::not_initiated;
  req.invoke_id = next_invoke_id_;
  req.cr = cfg_.communication_reference;
  if (!encode(req, pdu_) || pdu_.size > cfg_.kbl.max_pdu_sending)
    return SubmitStatus::invalid_argument;
  next_invoke_id_ = static_cast<std::uint8_t>(next_invoke_id_ + 1U);
  request_service_ = req.service;
  request_invoke_id_ = req.invoke_id;
  request_cr_ = req.cr;
  outstanding_ = true;
  sent_ = false;
  deadline_ = now + (timeout > Duration::zero() ? timeout : cfg_.request_timeout);
  reset_result();
  result_.service = req.service;
  result_.index = req.index;
  result_.invoke_id = req.invoke_id;
  result_.submitted_at = now;
  result_ready_ = false;
  expected_type_.reset();
  ++stats_.requests;
  return SubmitStatus::accepted;
}

void Client::reset_result() {
  // After a Read (or none yet) only what a Read's completion writes can differ from a fresh
  // Result: kind and completed_at (complete), abort_reason (abort, the server's Abort), error (a
  // negative confirmation), data and value (handle_message). Only data's first data.size bytes
  // can be non-zero: it is set only as a whole copy of a decoded PDU's data, which is fresh past
  // its size. So clearing those gives a fresh Result without clearing all of its 312 bytes on
  // every Read. After any other service, the whole Result.
  if (result_.service != ServiceCode::read) {
    result_ = Result{};
    return;
  }
  result_.kind = ResultKind::ok;
  result_.error = PcpError{};
  result_.abort_reason = AbortReason::user;
  result_.data.clear_zero_tail();
  result_.value.reset();
  result_.completed_at = Time{};
}

SubmitStatus Client::initiate(Time now, Duration timeout) {
  RequestPdu r;
  r.service = ServiceCode::initiate;
  r.password = cfg_.password;
  r.access_groups = cfg_.access_groups;
  r.kbl = cfg_.kbl;
  return submit(now, r, timeout, false);
}

SubmitStatus Client::read(Time now, ParameterRef p, Duration timeout) {
  return read_subindex(now, p, 0, timeout);
}

SubmitStatus Client::read(Time now, ParameterRef p, DataType expected, Duration timeout) {
  const SubmitStatus s = read_subindex(now, p, 0, timeout);
  if (s == SubmitStatus::accepted) expected_type_ = expected;
  return s;
}

SubmitStatus Client::read_subindex(Time now, ParameterRef p, std::uint8_t subindex,
                                   Duration timeout) {
  // A member rather than a fresh RequestPdu (which clears its 124-byte data on every Read): only a
  // Read's fields are ever written to it (service, index, subindex here; InvokeID and CR in
  // submit()), so it always equals a fresh Read request with them.
  RequestPdu& r = read_request_;
  r.service = ServiceCode::read;
  r.index = p.index;
  r.subindex = subindex;
  return submit(now, r, timeout, true);
}

SubmitStatus Client::write(Time now, ParameterRef p, Value v, Duration timeout) {
  std::array<std::uint8_t, kMaxValueSize> b{};
  const std::size_t n = encode(v, b);
  return write_bytes(now, p, std::span<const std::uint8_t>(b.data(), n), 0, timeout);
}

SubmitStatus Client::write(Time now, ParameterRef p, DataType t, double value, Duration timeout) {
  const Converted c = from_engineering(t, value);
  if (!c.ok()) return outstanding_ ? SubmitStatus::busy : SubmitStatus::invalid_argument;
  return write(now, p, c.value, timeout);
}

SubmitStatus Client::write_bytes(Time now, ParameterRef p, std::span<const std::uint8_t> data,
                                 std::uint8_t subindex, Duration timeout) {
  if (outstanding_) return SubmitStatus::busy;
  RequestPdu r;
  r.service = ServiceCode::write;
  r.index = p.index;
  r.subindex = subindex;
  if (!r.data.assign(data)) return SubmitStatus::invalid_argument;
  return submit(now, r, timeout, true);
}

SubmitStatus Client::get_ov(Time now, ParameterRef p, Duration timeout) {
  RequestPdu r;
  r.service = ServiceCode::get_ov;
  r.index = p.index;
  return submit(now, r, timeout, true);
}

SubmitStatus Client::identify(Time now, Duration timeout) {
  RequestPdu r;
  r.service = ServiceCode::identify;
  return submit(now, r, timeout, true);
}

SubmitStatus Client::status(Time now, Duration timeout) {
  RequestPdu r;
  r.service = ServiceCode::status;
  return submit(now, r, timeout, true);
}

void Client::abort(Time now) {
  if (outstanding_) {
    result_.abort_reason = AbortReason::user;
    complete(now, ResultKind::aborted);
    associated_ = false;
    abort_pending_ = false;
    link_.abort();  // the request may be half-way on the channel: drop it on both sides
    return;
  }
  if (!associated_) return;
  associated_ = false;
  RequestPdu r;
  r.service = ServiceCode::abort;
  r.cr = cfg_.communication_reference;
  r.reason = AbortReason::user;
  abort_pending_ = encode(r, abort_pdu_);
}

void Client::complete(Time now, ResultKind kind) {
  if (!outstanding_) return;
  outstanding_ = false;
  sent_ = false;
  result_.kind = kind;
  result_.completed_at = now;
  result_ready_ = true;
}

std::optional<Result> Client::take_result() {
  if (!result_ready_) return std::nullopt;
  result_ready_ = false;
  return result_;
}

std::optional<InformationReport> Client::take_information_report() {
  if (!report_ready_) return std::nullopt;
  report_ready_ = false;
  return report_;
}

void Client::fail_protocol(Time now) {
  ++stats_.protocol_errors;
  complete(now, ResultKind::protocol_error);
  associated_ = false;
  abort_pending_ = false;
  link_.abort();
}

void Client::handle_message(Time now, std::span<const std::uint8_t> msg) {
  // decode() sets every field: the member saves building a second one each message.
  ResponsePdu& r = response_;
  if (decode(msg, r) != PduError::none) {
    fail_protocol(now);
    return;
  }
  if (r.kind == ResponsePdu::Kind::abort) {
    ++stats_.aborts_received;
    associated_ = false;
    result_.abort_reason = r.reason;
    complete(now, ResultKind::aborted);
    return;
  }
  if (r.kind == ResponsePdu::Kind::information_report) {
    if (!associated_) return;
    report_.index = r.index;
    report_.data = r.data;
    report_.at = now;
    report_ready_ = true;
    return;
  }
  if (!outstanding_ || !sent_ || r.service != request_service_ ||
      r.invoke_id != request_invoke_id_ || r.cr != request_cr_) {
    fail_protocol(now);  // a confirmation nobody asked for: the channel is not what we think
    return;
  }
  ++stats_.confirmations;
  if (!r.positive) {
    result_.error = r.error;
    if (r.service == ServiceCode::initiate) result_.peer_kbl = r.kbl;
    complete(now, ResultKind::negative);
    return;
  }
  switch (r.service) {
    case ServiceCode::initiate:
      result_.peer_kbl = r.kbl;
      result_.mismatch = check_kbl(cfg_.kbl, r.kbl);
      if (result_.mismatch != KblMismatch::none) {
        // The server accepted, we do not: end the association with Abort (docs/pcp.md).
        RequestPdu a;
        a.service = ServiceCode::abort;
        a.cr = cfg_.communication_reference;
        a.reason = AbortReason::kbl_mismatch;
        abort_pending_ = encode(a, abort_pdu_);
        associated_ = false;
        complete(now, ResultKind::incompatible);
        return;
      }
      peer_kbl_ = r.kbl;
      associated_ = true;
      break;
    case ServiceCode::read:
      result_.data = r.data;
      if (expected_type_) {
        result_.value = decode(*expected_type_, r.data.view());
        if (!result_.value) {
          complete(now, ResultKind::type_mismatch);
          return;
        }
      }
      break;
    case ServiceCode::get_ov:
      if (!decode(r.data.view(), result_.description)) {
        fail_protocol(now);
        return;
      }
      break;
    case ServiceCode::identify:
      result_.identity = r.identity;
      break;
    case ServiceCode::status:
      result_.status = r.status;
      break;
    case ServiceCode::write:
    case ServiceCode::abort:
    case ServiceCode::information_report:
      break;
  }
  complete(now, ResultKind::ok);
}

void Client::show(Time now, std::span<Word> m2s) {
  link_.transmit(now, m2s);
}

void Client::step(Time now, std::span<const Word> s2m, std::span<Word> m2s) {
  const LinkEvents ev = link_.receive(now, s2m);
  if (ev.reset) {
    ++stats_.link_resets;
    associated_ = false;
    abort_pending_ = false;
    // An Initiate that has not left yet may still go once the channel is back.
    if (outstanding_ && (sent_ || request_service_ != ServiceCode::initiate)) {
      complete(now, ResultKind::link_reset);
    }
  }
  if (link_.has_message()) {
    handle_message(now, link_.message());
    link_.release_message();
  }
  if (outstanding_ && now >= deadline_) {
    ++stats_.timeouts;
    complete(now, ResultKind::timeout);
    associated_ = false;
    abort_pending_ = false;
    link_.abort();
  }
  if (abort_pending_ && link_.can_send()) {
    if (link_.send(abort_pdu_.view())) abort_pending_ = false;
  } else if (outstanding_ && !sent_ && !abort_pending_ && link_.can_send()) {
    sent_ = link_.send(pdu_.view());
  }
  link_.transmit(now, m2s);
}

}  // namespace ibs::pcp
