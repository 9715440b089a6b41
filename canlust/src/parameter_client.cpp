#include "ibs/canlust/parameter_client.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

namespace ibs::canlust {

std::string_view to_string(RequestKind k) {
  switch (k) {
    case RequestKind::read: return "read";
    case RequestKind::write: return "write";
    case RequestKind::describe: return "describe";
    case RequestKind::read_string: return "read string";
    case RequestKind::write_string: return "write string";
  }
  return "?";
}

std::string_view to_string(OutcomeKind k) {
  switch (k) {
    case OutcomeKind::done: return "done";
    case OutcomeKind::refused: return "refused";
    case OutcomeKind::timeout: return "timeout";
    case OutcomeKind::checksum_mismatch: return "checksum mismatch";
    case OutcomeKind::bad_reply: return "bad reply";
    case OutcomeKind::aborted: return "aborted";
  }
  return "?";
}

std::string_view to_string(SubmitError e) {
  switch (e) {
    case SubmitError::none: return "none";
    case SubmitError::queue_full: return "queue full";
    case SubmitError::invalid_address: return "invalid address";
    case SubmitError::text_too_long: return "text too long";
    case SubmitError::invalid_timeout: return "timeout not positive";
  }
  return "?";
}

std::string describe(const Outcome& o) {
  std::string s(to_string(o.kind));
  if (o.kind == OutcomeKind::refused) s += ", status " + describe_status(o.status);
  if (o.kind == OutcomeKind::done) {
    char buf[32];
    std::snprintf(buf, sizeof buf, ", value %08X", static_cast<unsigned>(o.value));
    s += buf;
    if (o.text.length > 0) s += ", text \"" + std::string(o.text.view()) + "\"";
  }
  return s;
}

Request write_string(Address a, std::uint16_t parameter, std::string_view text) {
  Request r = read(a, parameter);
  r.kind = RequestKind::write_string;
  r.text = FixedString::from(text);
  r.text_too_long = text.size() > kMaxStringChars;
  return r;
}

// A request without the unused part of its text buffer: only a string write reads its text, and
// only its first `length` characters (issue 26: the 100-byte buffer was copied into the queue
// and again into the drive's slot for every numeric request).
void ParameterClient::copy_request(Request& to, const Request& from) {
  copy_numeric(to, from);
  if (from.kind == RequestKind::write_string) {
    const std::size_t n = std::min<std::size_t>(from.text.length, from.text.chars.size());
    std::copy_n(from.text.chars.data(), n, to.text.chars.data());
    to.text.length = from.text.length;
  }
}

ParameterClient::ParameterClient(const ClientConfig& config)
    : config_(config),
      replies_(config_.ids, TelegramKind::parameter_reply),
      outbox_(std::max<std::size_t>(config.outbox_capacity, static_cast<std::size_t>(config.ids.max_address) + 1)) {
  queue_.resize(std::max<std::size_t>(1, config_.queue_capacity));
  queue_capacity_ = queue_.size();
  if (config_.timeout <= Duration::zero()) config_.timeout = 1ms;
  if (config_.string_timeout <= Duration::zero()) config_.string_timeout = 1ms;
  active_.resize(static_cast<std::size_t>(config_.ids.max_address) + 1);
  for (std::size_t k = 0; k < active_.size(); ++k) {
    const auto id = config_.ids.id(TelegramKind::parameter_request, static_cast<Address>(k));
    active_[k].request_id = id ? static_cast<std::int32_t>(*id) : -1;
  }
  busy_.reserve(active_.size());
  completed_.resize(std::max<std::size_t>(1, config_.completed_capacity));
  completed_capacity_ = completed_.size();
}

// submit()'s general path (the header's inline part hands a string write here): the same
// checks, the text checked and copied.
Submitted ParameterClient::submit_general(const Request& r) {
  if (r.address > config_.ids.max_address) return {0, SubmitError::invalid_address};
  if (r.kind == RequestKind::write_string && (r.text_too_long || r.text.length > kMaxStringChars)) {
    return {0, SubmitError::text_too_long};
  }
  if (r.timeout && *r.timeout <= Duration::zero()) return {0, SubmitError::invalid_timeout};
  if (queued_ == queue_capacity_) return {0, SubmitError::queue_full};
  const RequestId id = next_id_++;
  Queued& q = queue_[queued_++];
  q.id = id;
  copy_request(q.request, r);
  return {id, SubmitError::none};
}

void ParameterClient::dequeue(std::size_t k) {
  // Keeps the submission order of the others (the oldest request of a drive starts first).
  for (std::size_t i = k + 1; i < queued_; ++i) {
    queue_[i - 1].id = queue_[i].id;
    copy_request(queue_[i - 1].request, queue_[i].request);
  }
  --queued_;
}

void ParameterClient::send(Active& a, std::uint8_t mode, std::uint32_t data, std::uint8_t block,
                           Time now) {
  (void)now;
  a.awaiting_mode = mode;
  a.block = block;
  a.sent_data = data;
  ++a.telegrams;
  // encode_parameter_request, written straight into the outbox (issue 26), with the identifier
  // the constructor found for the slot (5.5: 1101 + address).
  if (a.request_id < 0) return;  // address checked at submit
  const auto id = static_cast<std::uint16_t>(a.request_id);
  if (!outbox_.push(detail::parameter_frame(id, {a.request.parameter, mode, data, block}))) {
    ++counters_.dropped_frames;
  }
}

void ParameterClient::start(Active& a, Time now) {
  a.started = now;
  const Duration limit = a.request.timeout.value_or(
      a.request.kind == RequestKind::read_string || a.request.kind == RequestKind::write_string
          ? config_.string_timeout
          : config_.timeout);
  a.deadline = now + limit;
  a.telegrams = 0;
  a.checksum = 0;
  a.bytes = 0;
  a.terminator = false;
  a.text.length = 0;  // the characters past the length are never read
  const Request& r = a.request;
  switch (r.kind) {
    case RequestKind::read: send(a, kModeRead, 0, r.index, now); return;
    case RequestKind::write: send(a, kModeWrite, r.value, r.index, now); return;
    case RequestKind::describe: send(a, kModeDescribe, 0, r.index, now); return;
    case RequestKind::read_string: send(a, kModeStringRead, 0, 0, now); return;
    case RequestKind::write_string:
      // The text and its terminator, padded with zeros to whole blocks of 4 (decision D13).
      a.bytes = (static_cast<std::size_t>(r.text.length) + 1 + 3) / 4 * 4;
      send(a, kModeStringWrite, 0, 0, now);
      return;
  }
}

void ParameterClient::list_busy(Active& a, Address address) {
  a.busy = true;
  a.listed_at = static_cast<std::uint8_t>(busy_.size());
  busy_.push_back(address);  // within the reserved capacity: one entry per slot at most
}

void ParameterClient::unlist_busy(Active& a) {
  a.busy = false;
  const Address last = busy_.back();
  busy_[a.listed_at] = last;
  active_[last].listed_at = a.listed_at;
  busy_.pop_back();
}

void ParameterClient::finish(Active& a, OutcomeKind kind, Time now, std::uint8_t status,
                             std::uint32_t value) {
  Completed& c = completed_[completed_next_];
  if (++completed_next_ == completed_capacity_) completed_next_ = 0;
  c.id = a.id;
  c.outcome.kind = kind;
  c.outcome.status = status;
  c.outcome.value = value;
  // Only a string read fills a.text; the others leave an empty text (length 0) without copying
  // the buffer.
  if (kind == OutcomeKind::done && a.text.length > 0) {
    c.outcome.text = a.text;
  } else {
    c.outcome.text.length = 0;
  }
  c.outcome.telegrams = a.telegrams;
  c.outcome.started = a.started;
  c.outcome.finished = now;
  if (a.busy) unlist_busy(a);
}

void ParameterClient::step(Time now) {
  // Backwards: finishing moves the last entry into the place of the one removed, already seen.
  for (std::size_t i = busy_.size(); i-- > 0;) {
    Active& a = active_[busy_[i]];
    if (now >= a.deadline) {
      ++counters_.timeouts;
      finish(a, OutcomeKind::timeout, now);
    }
  }
  // Start the oldest queued request of every free drive (one request per drive at a time).
  for (std::size_t k = 0; k < queued_;) {
    const Queued& q = queue_[k];
    Active& a = active_[q.request.address];
    if (a.busy) {
      ++k;
      continue;
    }
    list_busy(a, q.request.address);
    a.id = q.id;
    copy_request(a.request, q.request);
    start(a, now);
    if (k + 1 == queued_) {
      --queued_;  // the last one: nothing to shift
    } else {
      dequeue(k);  // shifts the later ones into place k
    }
  }
}

void ParameterClient::receive(const CanFrame& f, Time now) {
  // classify(f.id) when it is a parameter reply (KindMatcher).
  const auto address = replies_.match(f.id);
  if (!address) return;
  const auto t = decode_parameter(f);
  if (!t) return;
  Active& a = active_[*address];
  if (!a.busy || now >= a.deadline || t.value.parameter != a.request.parameter ||
      t.value.block != a.block) {
    ++counters_.stray_replies;
    return;
  }
  on_reply(a, t.value, now);
}

void ParameterClient::send_write_block(Active& a, Time now) {
  const std::size_t offset = 4U * (static_cast<std::size_t>(a.block));  // block k carries bytes 4(k-1)..
  const auto next = static_cast<std::uint8_t>(a.block + 1);
  const std::size_t start = offset;  // bytes of block `next` begin at 4 x (next - 1) = offset
  if (start >= a.bytes) {
    send(a, kModeListEnd, a.checksum, next, now);  // closes with the checksum
    return;
  }
  std::array<std::uint8_t, 4> b{};
  for (std::size_t i = 0; i < 4; ++i) {
    const std::size_t k = start + i;
    b[i] = k < a.request.text.length ? static_cast<std::uint8_t>(a.request.text.chars[k]) : 0;
  }
  const std::uint32_t d = get_le32(b);
  a.checksum = string_checksum_step(a.checksum, d);
  send(a, kModeStringWrite, d, next, now);
}

void ParameterClient::on_reply(Active& a, const ParameterTelegram& t, Time now) {
  const Request& r = a.request;
  switch (r.kind) {
    case RequestKind::read:
    case RequestKind::describe:
      if (t.code != kStatusOk) {
        finish(a, OutcomeKind::refused, now, t.code);
      } else {
        finish(a, OutcomeKind::done, now, 0, t.data);
      }
      return;
    case RequestKind::write:
      if (t.code != kStatusOk) {
        finish(a, OutcomeKind::refused, now, t.code);
      } else {
        finish(a, OutcomeKind::done, now, 0, t.data);
      }
      return;
    case RequestKind::read_string: {
      if (t.code == kStatusListEnd && a.block > 0) {
        // The last reply: List_End and the checksum over the blocks before it (D8).
        if (!a.terminator) {
          finish(a, OutcomeKind::bad_reply, now, t.code);
        } else if (t.data != a.checksum) {
          finish(a, OutcomeKind::checksum_mismatch, now, t.code, t.data);
        } else {
          finish(a, OutcomeKind::done, now, 0, t.data);
        }
        return;
      }
      if (t.code != kStatusOk) {
        finish(a, OutcomeKind::refused, now, t.code);
        return;
      }
      if (a.terminator || a.bytes + 4 > kMaxStringBytes) {
        finish(a, OutcomeKind::bad_reply, now);  // data after the terminator, or over 100 bytes
        return;
      }
      a.checksum = string_checksum_step(a.checksum, t.data);
      for (std::size_t i = 0; i < 4 && !a.terminator; ++i) {
        const auto ch = static_cast<char>((t.data >> (8U * i)) & 0xFFU);
        if (ch == '\0') {
          a.terminator = true;
        } else {
          a.text.chars[a.text.length++] = ch;
        }
      }
      a.bytes += 4;
      if (a.text.length >= kMaxStringBytes - 1 && !a.terminator) {
        finish(a, OutcomeKind::bad_reply, now);
        return;
      }
      send(a, kModeStringRead, 0, static_cast<std::uint8_t>(a.block + 1), now);
      return;
    }
    case RequestKind::write_string: {
      if (t.code != kStatusOk) {
        finish(a, OutcomeKind::refused, now, t.code);
        return;
      }
      if (a.awaiting_mode == kModeListEnd) {
        finish(a, OutcomeKind::done, now, 0, t.data);
        return;
      }
      if (a.block > 0 && t.data != a.sent_data) {
        finish(a, OutcomeKind::bad_reply, now);  // every block is echoed
        return;
      }
      send_write_block(a, now);
      return;
    }
  }
}

Time ParameterClient::next_deadline() const {
  if (!outbox_.empty()) return Time::min();  // frames to take now
  for (std::size_t k = 0; k < queued_; ++k) {
    if (!active_[queue_[k].request.address].busy) return Time::min();
  }
  Time t = Time::max();
  for (const Address b : busy_) t = std::min(t, active_[b].deadline);
  return t;
}

Poll ParameterClient::poll_general(RequestId id) const {
  if (id == 0) return {RequestState::unknown, nullptr};
  for (const Address b : busy_) {
    if (active_[b].id == id) return {RequestState::active, nullptr};
  }
  for (std::size_t k = 0; k < queued_; ++k) {
    if (queue_[k].id == id) return {RequestState::queued, nullptr};
  }
  // Newest first: a request is mostly polled right after it finished.
  std::size_t at = completed_next_;  // below completed_.size()
  for (std::size_t k = 0; k < completed_.size(); ++k) {
    at = at == 0 ? completed_.size() - 1 : at - 1;
    const Completed& c = completed_[at];
    if (c.id == id) return {RequestState::done, &c.outcome};
  }
  return {RequestState::unknown, nullptr};
}

bool ParameterClient::idle() const { return queued_ == 0 && busy_.empty(); }

void ParameterClient::abort_all(Time now) {
  while (!busy_.empty()) finish(active_[busy_.back()], OutcomeKind::aborted, now);
  for (std::size_t k = 0; k < queued_; ++k) {
    Active tmp;
    tmp.id = queue_[k].id;
    copy_request(tmp.request, queue_[k].request);
    tmp.started = now;
    finish(tmp, OutcomeKind::aborted, now);
  }
  queued_ = 0;
  outbox_.clear();
}

}  // namespace ibs::canlust
