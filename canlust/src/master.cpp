#include "ibs/canlust/master.hpp"

#include <algorithm>

namespace ibs::canlust {

namespace {
ClientConfig with_ids(ClientConfig c, const IdentifierMap& ids) {
  c.ids = ids;
  return c;
}
}  // namespace

Master::Master(const MasterConfig& config)
    : config_(config),
      client_(with_ids(config.client, config.ids)),
      outbox_(std::max<std::size_t>(4, config.outbox_capacity)) {
  drives_.resize(static_cast<std::size_t>(config_.ids.max_address) + 1);
  for (auto& d : drives_) d.layout = config_.layout;
  logon_order_.resize(drives_.size());
  errors_.resize(std::max<std::size_t>(1, config_.error_capacity));
}

bool Master::push(const std::optional<CanFrame>& f) {
  if (!f) return false;
  if (!outbox_.push(*f)) {
    ++counters_.dropped_frames;
    return false;
  }
  return true;
}

bool Master::take_frame(CanFrame& out) {
  // Own frames (broadcasts, control) first, then the parameter client's.
  if (!outbox_.empty()) {
    out = outbox_.front();
    outbox_.pop();
    return true;
  }
  return client_.take_frame(out);
}

// Written out rather than through the form above, so that
// CanlustShortcuts.MasterTakeFrameIntoTheCallersFrameIsTheOptionalForm compares two codings.
std::optional<CanFrame> Master::take_frame() {
  if (!outbox_.empty()) {
    const CanFrame f = outbox_.front();
    outbox_.pop();
    return f;
  }
  return client_.take_frame();
}

void Master::system_start() { push(encode_system(SystemCommand::start)); }
void Master::system_stop() { push(encode_system(SystemCommand::stop)); }

bool Master::send_control(Address a, const ControlTelegram& t) {
  if (a > config_.ids.max_address) return false;
  return push(encode_control(config_.ids, a, drives_[a].layout, t));
}

void Master::set_layout(Address a, const ProcessLayout& l) {
  if (a <= config_.ids.max_address) drives_[a].layout = l;
}

void Master::step(Time now) { client_.step(now); }

void Master::receive(const CanFrame& f, Time now) {
  ++counters_.frames_in;
  const auto c = config_.ids.classify(f.id);
  if (!c) {
    ++counters_.foreign_frames;
    return;
  }
  DriveView& d = drives_[c->address];
  switch (c->kind) {
    case TelegramKind::logon:
      if (f.rtr) {
        ++counters_.bad_frames;
        return;
      }
      if (!d.logged_on) {
        d.logged_on = true;
        d.first_logon = now;
        logon_order_[logon_count_++] = c->address;
      }
      d.last_logon = now;
      ++d.logons;
      return;
    case TelegramKind::status: {
      const auto s = decode_status(f, d.layout);
      if (!s) {
        ++counters_.bad_frames;
        return;
      }
      d.has_status = true;
      d.status = s.value;
      d.status_time = now;
      ++d.statuses;
      return;
    }
    case TelegramKind::error: {
      const auto e = decode_error(f);
      if (!e) {
        ++counters_.bad_frames;
        return;
      }
      ++d.errors;
      if (err_size_ == errors_.size()) {
        ++counters_.lost_errors;
        err_head_ = (err_head_ + 1) % errors_.size();
        --err_size_;
      }
      errors_[(err_head_ + err_size_) % errors_.size()] = {c->address, e.value, now};
      ++err_size_;
      return;
    }
    case TelegramKind::parameter_reply:
      client_.receive(f, now);
      return;
    default:
      return;  // the master's own telegrams (control, requests, broadcasts)
  }
}

std::optional<ErrorEvent> Master::take_error() {
  if (err_size_ == 0) return std::nullopt;
  const ErrorEvent e = errors_[err_head_];
  err_head_ = (err_head_ + 1) % errors_.size();
  --err_size_;
  return e;
}

}  // namespace ibs::canlust
