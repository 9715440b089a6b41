// How a request begins, and what the host does once an exchange has ended (its EOT sent): the next step of the request's
// procedure -- a repetition where LUSTBUS manual allows one (6.1, 9.2, LB-D5), the read of 85-SIOF/SERR
// after a NAK (6.2, 9.2), the scan's probe (5.2), the download's next record and its poll (11.4),
// the text after its index (11.3), the block transfer's answer or error read (11.6) -- or its
// outcome. The rest of the host (queue, line, timeouts) is host.cpp.
#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/siof.hpp"

namespace ibs::lustbus {

namespace {

// 11.4: a handshake value, INTEGER16 sent as its 16-bit two's complement (2.3.2).
Value handshake_value(const DownloadProcedure& p, std::int16_t v) {
  return format_raw(p.family, static_cast<std::uint16_t>(v)).value;
}

}  // namespace

// A request begins: its first telegram (or the scan's first address).
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
  out_->eeprom_wait = Duration{0};
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
      send_select(Tx{kAddressBroadcast, r.code, r.value, false, timeout_of(r)}, true, now);
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

// A SELECT step succeeded.
void Host::on_select_like_ack(Time now) {
  out_->attempts = select_attempts_;
  switch (select_return_) {
    case Phase::main:
      note_eeprom_save();  // 10.2.2: the servo saves it in the background from now
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
        note_eeprom_save();  // every device saves it (4.2: none answers)
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

}  // namespace ibs::lustbus
