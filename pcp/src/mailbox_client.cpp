#include "ibs/pcp/mailbox_client.hpp"

#include <stdexcept>
#include <string>

namespace ibs::pcp {

namespace {

constexpr std::uint16_t code_of(ServiceCode s) { return static_cast<std::uint16_t>(s); }

bool is_confirmable(std::uint16_t code) {
  return code == code_of(ServiceCode::read) || code == code_of(ServiceCode::write) ||
         code == code_of(ServiceCode::get_ov) || code == code_of(ServiceCode::initiate) ||
         code == code_of(ServiceCode::status) || code == code_of(ServiceCode::identify);
}

const MailboxConfig& checked(const MailboxConfig& cfg) {
  detail::require<std::invalid_argument>(MailboxClient::validate(cfg));
  return cfg;
}

// Big-endian bytes of `words` (a confirmation's data, high byte first), `length` of them.
bool data_of(std::span<const Word> words, std::size_t length, DataBytes& out) {
  if (length > out.data.size() || (length + 1) / 2 > words.size()) return false;
  for (std::size_t i = 0; i < length; ++i) {
    const Word w = words[i / 2];
    out.data[i] = static_cast<std::uint8_t>(i % 2 == 0 ? w >> 8U : w & 0xFFU);
  }
  out.size = length;
  return true;
}

}  // namespace

namespace mailbox {

std::optional<std::uint8_t> communication_reference(std::span<const Word> message) {
  if (message.size() < 3) return std::nullopt;
  const std::uint16_t code = message[0];
  const bool pcp_confirmation = (code & kConfirmationBit) != 0 && is_confirmable(code & 0x7FFFU);
  if (!pcp_confirmation && code != kAbortIndication && code != kInformationReportIndication) return std::nullopt;
  return static_cast<std::uint8_t>(message[2] & 0xFFU);
}

}  // namespace mailbox

Error MailboxClient::validate(const MailboxConfig& cfg) {
  if (cfg.communication_reference < 2) {
    return {ErrorCode::channel_reference_invalid,
            "PCP mailbox client: communication reference " + std::to_string(cfg.communication_reference) +
                " (a board numbers its PCP devices from 2)"};
  }
  if (cfg.request_timeout <= Duration::zero()) {
    return {ErrorCode::channel_timeout_not_positive, "PCP mailbox client request_timeout must be positive"};
  }
  return {};
}

MailboxClient::MailboxClient(const MailboxConfig& cfg) : cfg_(checked(cfg)) {}

SubmitStatus MailboxClient::submit(Time now, ServiceCode service, std::uint16_t index, Duration timeout,
                                   bool needs_association) {
  if (outstanding_) return SubmitStatus::busy;
  if (needs_association && !associated_) return SubmitStatus::not_initiated;
  request_invoke_id_ = next_invoke_id_;
  next_invoke_id_ = static_cast<std::uint8_t>(next_invoke_id_ + 1U);
  request_service_ = service;
  request_[0] = code_of(service);
  request_[2] = static_cast<Word>((request_invoke_id_ << 8U) | cfg_.communication_reference);
  outstanding_ = true;
  sent_ = false;
  deadline_ = now + (timeout > Duration::zero() ? timeout : cfg_.request_timeout);
  result_ = Result{};
  result_.service = service;
  result_.index = index;
  result_.invoke_id = request_invoke_id_;
  result_.submitted_at = now;
  result_ready_ = false;
  expected_type_.reset();
  ++stats_.requests;
  return SubmitStatus::accepted;
}

SubmitStatus MailboxClient::initiate(Time now, Duration timeout) {
  const SubmitStatus s = submit(now, ServiceCode::initiate, 0, timeout, false);
  if (s != SubmitStatus::accepted) return s;
  // [id,CR][password][access groups]: the board's firmware brings its own KBL entry.
  request_[1] = 3;
  request_[3] = cfg_.password;
  request_[4] = cfg_.access_groups;
  request_words_ = 5;
  return s;
}

SubmitStatus MailboxClient::read(Time now, ParameterRef p, Duration timeout) {
  const SubmitStatus s = submit(now, ServiceCode::read, p.index, timeout, true);
  if (s != SubmitStatus::accepted) return s;
  request_[1] = 3;  // [id,CR][index][subindex << 8]
  request_[3] = p.index;
  request_[4] = 0;
  request_words_ = 5;
  return s;
}

SubmitStatus MailboxClient::read(Time now, ParameterRef p, DataType expected, Duration timeout) {
  const SubmitStatus s = read(now, p, timeout);
  if (s == SubmitStatus::accepted) expected_type_ = expected;
  return s;
}

SubmitStatus MailboxClient::write(Time now, ParameterRef p, Value v, Duration timeout) {
  std::array<std::uint8_t, kMaxValueSize> b{};
  const std::size_t n = encode(v, b);
  return write_bytes(now, p, std::span<const std::uint8_t>(b.data(), n), 0, timeout);
}

SubmitStatus MailboxClient::write_bytes(Time now, ParameterRef p, std::span<const std::uint8_t> data,
                                        std::uint8_t subindex, Duration timeout) {
  if (outstanding_) return SubmitStatus::busy;
  if (data.empty() || data.size() > kMaxDataSize) return SubmitStatus::invalid_argument;
  const SubmitStatus s = submit(now, ServiceCode::write, p.index, timeout, true);
  if (s != SubmitStatus::accepted) return s;
  // [id,CR][index][subindex << 8 | length][data words, the last padded]
  const std::size_t words = (data.size() + 1) / 2;
  request_[1] = static_cast<Word>(3 + words);
  request_[3] = p.index;
  request_[4] = static_cast<Word>((static_cast<std::size_t>(subindex) << 8U) | data.size());
  for (std::size_t k = 0; k < words; ++k) {
    const std::uint8_t lo = 2 * k + 1 < data.size() ? data[2 * k + 1] : 0;
    request_[5 + k] = static_cast<Word>((data[2 * k] << 8U) | lo);
  }
  request_words_ = 5 + words;
  return s;
}

SubmitStatus MailboxClient::get_ov(Time now, ParameterRef p, Duration timeout) {
  const SubmitStatus s = submit(now, ServiceCode::get_ov, p.index, timeout, true);
  if (s != SubmitStatus::accepted) return s;
  request_[1] = 2;  // [id,CR][index]: one object per request
  request_[3] = p.index;
  request_words_ = 4;
  return s;
}

void MailboxClient::complete(Time now, ResultKind kind) {
  if (!outstanding_) return;
  outstanding_ = false;
  result_.kind = kind;
  result_.completed_at = now;
  result_ready_ = true;
  ended_invoke_id_ = request_invoke_id_;
}

void MailboxClient::end_association(bool tell_board) {
  associated_ = false;
  if (!tell_board) return;
  // Abort, unconfirmed: [00,CR][reason 0, the user's]. The board drops an outstanding request of
  // the CR and never confirms it.
  abort_ = {code_of(ServiceCode::abort), 2, cfg_.communication_reference, 0};
  abort_pending_ = true;
}

void MailboxClient::abort(Time now) {
  const bool board_knows = associated_ || (outstanding_ && sent_);
  if (outstanding_) {
    result_.abort_reason = AbortReason::user;
    complete(now, ResultKind::aborted);
  }
  end_association(board_knows);
}

void MailboxClient::step(Time now, std::span<const Word> /*s2m*/, std::span<Word> /*m2s*/) {
  if (!outstanding_ || now < deadline_) return;
  ++stats_.timeouts;
  const bool board_knows = associated_ || sent_;
  complete(now, ResultKind::timeout);
  end_association(board_knows);
}

std::span<const Word> MailboxClient::outgoing() const {
  if (abort_pending_) return {abort_.data(), abort_.size()};
  if (outstanding_ && !sent_) return {request_.data(), request_words_};
  return {};
}

void MailboxClient::sent() {
  if (abort_pending_) {
    abort_pending_ = false;
  } else if (outstanding_) {
    sent_ = true;
  }
}

std::optional<InformationReport> MailboxClient::take_information_report() {
  if (!report_ready_) return std::nullopt;
  report_ready_ = false;
  return report_;
}

void MailboxClient::receive(Time now, std::span<const Word> m) {
  if (m.size() < 3 || m[1] != m.size() - 2) {
    fail_protocol(now);
    return;
  }
  if ((m[0] & kConfirmationBit) != 0) {
    confirmation(now, m);
  } else {
    indication(now, m);
  }
}

void MailboxClient::indication(Time now, std::span<const Word> m) {
  if (m[0] == mailbox::kAbortIndication && m.size() == 4) {
    // The board ended the association by itself; the request it carried is not confirmed.
    ++stats_.abort_indications;
    associated_ = false;
    // An Initiate that has not left may still go; any other request would find no association.
    if (outstanding_ && (sent_ || request_service_ != ServiceCode::initiate)) {
      switch (static_cast<mailbox::AbortCause>(m[3])) {
        case mailbox::AbortCause::timeout: complete(now, ResultKind::timeout); break;
        case mailbox::AbortCause::link_reset: complete(now, ResultKind::link_reset); break;
        case mailbox::AbortCause::protocol: complete(now, ResultKind::protocol_error); break;
        case mailbox::AbortCause::by_device:
        case mailbox::AbortCause::transfer_stopped:
        default:
          result_.abort_reason = AbortReason::user;
          complete(now, ResultKind::aborted);
          break;
      }
    }
    return;
  }
  if (m[0] == mailbox::kInformationReportIndication && m.size() >= 5) {
    if (!associated_) return;
    InformationReport r;
    r.index = m[3];
    r.at = now;
    if (!data_of(m.subspan(5), m[4], r.data)) {
      fail_protocol(now);
      return;
    }
    report_ = r;
    report_ready_ = true;
    return;
  }
  fail_protocol(now);
}

void MailboxClient::confirmation(Time now, std::span<const Word> m) {
  const auto service = static_cast<std::uint16_t>(m[0] & 0x7FFFU);
  const auto invoke_id = static_cast<std::uint8_t>(m[2] >> 8U);
  if (!outstanding_ || !sent_ || service != code_of(request_service_) || invoke_id != request_invoke_id_) {
    if (ended_invoke_id_ && invoke_id == *ended_invoke_id_) {
      ++stats_.late_confirmations;  // the request it answers has ended already
      return;
    }
    fail_protocol(now);
    return;
  }
  if (m.size() < 4) {
    fail_protocol(now);
    return;
  }
  ++stats_.confirmations;
  if (m[3] != 0) {
    // Negative: [class << 8 | code][additional] (an Initiate may add the device's two sizes).
    if (m.size() < 5) {
      fail_protocol(now);
      return;
    }
    result_.error = PcpError{static_cast<std::uint8_t>(m[3] >> 8U), static_cast<std::uint8_t>(m[3] & 0xFFU), m[4]};
    if (request_service_ == ServiceCode::initiate && m.size() >= 7) {
      result_.peer_kbl.max_pdu_sending = m[5];
      result_.peer_kbl.max_pdu_receiving = m[6];
    }
    complete(now, ResultKind::negative);
    return;
  }
  switch (request_service_) {
    case ServiceCode::initiate:
      if (m.size() < 6) return fail_protocol(now);
      result_.peer_kbl.max_pdu_sending = m[4];
      result_.peer_kbl.max_pdu_receiving = m[5];
      associated_ = true;
      break;
    case ServiceCode::read:
      if (m.size() < 5 || !data_of(m.subspan(5), m[4], result_.data)) return fail_protocol(now);
      if (expected_type_) {
        result_.value = decode(*expected_type_, result_.data.view());
        if (!result_.value) {
          complete(now, ResultKind::type_mismatch);
          return;
        }
      }
      break;
    case ServiceCode::get_ov: {
      DataBytes d;
      if (m.size() < 5 || !data_of(m.subspan(5), m[4], d) || !decode(d.view(), result_.description)) {
        return fail_protocol(now);
      }
      break;
    }
    default:
      break;
  }
  complete(now, ResultKind::ok);
}

void MailboxClient::fail_protocol(Time now) {
  // A message that answers nothing this client asked: the association is not what it thinks.
  ++stats_.protocol_errors;
  const bool board_knows = associated_ || (outstanding_ && sent_);
  complete(now, ResultKind::protocol_error);
  end_association(board_knows);
}

}  // namespace ibs::pcp
