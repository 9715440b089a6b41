#include "ibs/canlust/node.hpp"

#include <algorithm>

namespace ibs::canlust {

std::string_view to_string(SystemState s) {
  switch (s) {
    case SystemState::logon: return "System Logon";
    case SystemState::stop: return "System Stop";
    case SystemState::start: return "System Start";
  }
  return "?";
}

Node::Node(const NodeConfig& config, DriveProcess& drive, ParameterAccess& parameters)
    : config_(config),
      drive_(&drive),
      server_(parameters),
      outbox_(std::max<std::size_t>(4, config.outbox_capacity)) {
  const auto own = [&](TelegramKind k) -> std::int32_t {
    const auto id = config_.ids.own_id(k, config_.address);
    return id ? static_cast<std::int32_t>(*id) : -1;
  };
  control_id_ = own(TelegramKind::control);
  const auto reply = config_.ids.id(TelegramKind::parameter_reply, config_.address);
  reply_id_ = reply ? static_cast<std::int32_t>(*reply) : -1;
  request_id_ = own(TelegramKind::parameter_request);
}

void Node::push(const std::optional<CanFrame>& f) {
  if (f) push_frame(*f);
}

void Node::push_frame(const CanFrame& f) {
  if (!outbox_.push(f)) ++counters_.dropped_frames;
}

void Node::power_on(Time now) {
  powered_ = true;
  state_ = SystemState::logon;
  stored_.reset();
  tripped_ = false;
  server_.reset();
  outbox_.clear();
  next_status_ = Time::max();
  // 5.2: in System Logon the drive sends its logon identifier every 100 ms; the first one at
  // power-on (decision D14).
  next_logon_ = now;
  step(now);
}

void Node::send_status(Time now) {
  push(encode_status(config_.ids, config_.address, config_.layout, drive_->status(now)));
  ++counters_.statuses;
}

void Node::apply(SystemEvent e, Time now) {
  const SystemTransition& t = system_transition(state_, e);
  const SystemState old = state_;
  state_ = t.to;
  if (old != state_) drive_->system_state_changed(state_, now);
  if (t.execute_stored && stored_) {
    // 5.2: "On System Start all the devices then receive their start command synchronously".
    drive_->execute(*stored_, now);
    stored_.reset();
  }
  if (state_ == SystemState::start && old != SystemState::start) {
    next_logon_ = Time::max();
    last_control_ = now;  // the watchdog runs from the System Start (decision D16)
    tripped_ = false;
    if (old == SystemState::logon) {
      // 5.2: "from then on" the status every 575-CASCY; the first one at the Start (D16).
      send_status(now);
      next_status_ = now + config_.status_period;
    }
  }
}

void Node::receive(const CanFrame& f, Time now) {
  if (!powered_) return;
  // What classify(f.id) says, for the three telegrams a node acts on: the broadcast (classify
  // takes its identifier first), and this address's control and parameter request (own_id);
  // everything else - other kinds, other drives, unused identifiers - is ignored (5.5).
  TelegramKind kind = TelegramKind::system;
  if (f.id == kIdSystem) {
    const auto d = decode_system(f);
    if (!d) return;
    apply(d.value == SystemCommand::start ? SystemEvent::start_broadcast
                                          : SystemEvent::stop_broadcast,
          now);
    return;
  }
  if (f.id == request_id_) {
    kind = TelegramKind::parameter_request;
  } else if (f.id == control_id_) {
    kind = TelegramKind::control;
  } else {
    return;
  }
  switch (kind) {
    case TelegramKind::control: {
      const auto d = decode_control(f, config_.layout);
      if (!d) {
        ++counters_.bad_frames;
        return;
      }
      ++counters_.controls;
      if (state_ == SystemState::start) {
        drive_->execute(d.value, now);
        last_control_ = now;
        tripped_ = false;  // re-armed by a control telegram
      } else {
        // 5.2 System Stop: "only stored (1 reference / 1 control command)": the last one wins.
        stored_ = d.value;
        ++counters_.stored;
      }
      return;
    }
    case TelegramKind::parameter_request: {
      const auto d = decode_parameter(f);
      if (!d) {
        ++counters_.bad_frames;
        return;
      }
      // 5.2: parameter access is possible in every system state.
      server_.receive(d.value, now);
      for (ParameterTelegram r; server_.take_reply(now, r);) push_reply(r);
      return;
    }
    default:
      return;  // telegrams other drives or the node itself send
  }
}

void Node::step(Time now) {
  if (!powered_) return;
  if (state_ == SystemState::logon && now >= next_logon_) {
    push(encode_logon(config_.ids, config_.address));
    ++counters_.logons;
    next_logon_ += config_.logon_period;
    if (next_logon_ <= now) next_logon_ = now + config_.logon_period;
  }
  if (state_ != SystemState::logon && now >= next_status_) {
    send_status(now);
    next_status_ += config_.status_period;
    if (next_status_ <= now) next_status_ = now + config_.status_period;
  }
  if (state_ == SystemState::start && config_.watchdog > Duration::zero() && !tripped_ &&
      now >= last_control_ + config_.watchdog) {
    // 574-CAWDG ran out: the drive's programmable error reaction (6.1).
    tripped_ = true;
    ++counters_.watchdog_trips;
    WatchdogEvent ev;
    ev.reaction = config_.watchdog_reaction;
    ev.error = {config_.watchdog_error_number, config_.watchdog_error_location,
                static_cast<std::uint8_t>(config_.watchdog_reaction)};
    ev.last_control = last_control_;
    ev.now = now;
    if (const auto e = drive_->watchdog_expired(ev)) {
      push(encode_error(config_.ids, config_.address, *e));
    }
  }
  for (ParameterTelegram r; server_.take_reply(now, r);) push_reply(r);
}

void Node::push_reply(const ParameterTelegram& t) {
  // encode_parameter_reply(config_.ids, config_.address, t) with the identifier found once.
  if (reply_id_ < 0) return;
  push_frame(detail::parameter_frame(static_cast<std::uint16_t>(reply_id_), t));
}

Time Node::next_deadline() const {
  if (!powered_) return Time::max();
  if (!outbox_.empty()) return Time::min();  // frames to take now
  Time t = server_.next_deadline();
  if (state_ == SystemState::logon) t = std::min(t, next_logon_);
  if (state_ != SystemState::logon) t = std::min(t, next_status_);
  if (state_ == SystemState::start && config_.watchdog > Duration::zero() && !tripped_) {
    t = std::min(t, last_control_ + config_.watchdog);
  }
  return t;
}

void Node::report_error(const ErrorTelegram& e, Time now) {
  (void)now;
  if (!powered_) return;
  push(encode_error(config_.ids, config_.address, e));
}

void Node::set_watchdog(Duration d, Time now) {
  config_.watchdog = d;
  last_control_ = now;
  tripped_ = false;
}

void Node::set_status_period(Duration d) { config_.status_period = d; }

}  // namespace ibs::canlust
