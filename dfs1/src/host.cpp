#include "ibs/dfs1/host.hpp"

#include <algorithm>

namespace ibs::dfs1 {

namespace request {

namespace {

Frame with_value(std::uint8_t uid, Command c, std::uint32_t value) {
  std::array<std::uint8_t, 4> d{};
  put_u32(d, value);
  return make_frame(uid, static_cast<std::uint8_t>(c), d);
}

Frame with_number_and_value(std::uint8_t uid, Command c, std::uint8_t number, std::uint32_t value) {
  std::array<std::uint8_t, 5> d{};
  d[0] = number;
  put_u32(std::span<std::uint8_t, 4>(d.data() + 1, 4), value);
  return make_frame(uid, static_cast<std::uint8_t>(c), d);
}

Frame with_number(std::uint8_t uid, Command c, std::uint8_t number) {
  const std::array<std::uint8_t, 1> d = {number};
  return make_frame(uid, static_cast<std::uint8_t>(c), d);
}

Frame bare(std::uint8_t uid, Command c) {
  return make_frame(uid, static_cast<std::uint8_t>(c));
}

}  // namespace

Frame status(std::uint8_t uid) {
  return bare(uid, Command::status);
}
Frame set_speed(std::uint8_t uid, std::int32_t rpm) {
  return with_value(uid, Command::set_speed, to_unsigned(rpm));
}
Frame execute_speed(std::uint8_t uid) {
  return bare(uid, Command::execute_speed);
}
Frame set_and_execute_speed(std::uint8_t uid, std::int32_t rpm) {
  return with_value(uid, Command::set_and_execute_speed, to_unsigned(rpm));
}
Frame read_parameter(std::uint8_t uid, std::uint8_t parameter) {
  return with_number(uid, Command::read_parameter, parameter);
}
Frame write_parameter(std::uint8_t uid, std::uint8_t parameter, std::uint32_t value) {
  return with_number_and_value(uid, Command::write_parameter, parameter, value);
}
Frame read_analog_input(std::uint8_t uid, std::uint8_t channel) {
  return with_number(uid, Command::read_analog_input, channel);
}
Frame read_analog_output(std::uint8_t uid, std::uint8_t channel) {
  return with_number(uid, Command::read_analog_output, channel);
}
Frame write_analog_output(std::uint8_t uid, std::uint8_t channel, std::uint32_t value) {
  return with_number_and_value(uid, Command::write_analog_output, channel, value);
}
Frame read_digital_input(std::uint8_t uid, std::uint8_t channel) {
  return with_number(uid, Command::read_digital_input, channel);
}
Frame read_digital_output(std::uint8_t uid, std::uint8_t channel) {
  return with_number(uid, Command::read_digital_output, channel);
}
Frame write_digital_output(std::uint8_t uid, std::uint8_t channel, std::uint32_t value) {
  return with_number_and_value(uid, Command::write_digital_output, channel, value);
}
Frame set_operational_mode(std::uint8_t uid, std::uint16_t mask) {
  return with_value(uid, Command::set_operational_mode, mask);
}
Frame read_operational_mode(std::uint8_t uid) {
  return bare(uid, Command::read_operational_mode);
}
Frame application_mode(std::uint8_t uid, std::uint8_t mode, std::uint32_t value) {
  return with_number_and_value(uid, Command::application_mode, mode, value);
}

}  // namespace request

RequestCheck check_request(const Frame& r) {
  const CommandInfo* row = find_command(r.code);
  if (row == nullptr) return RequestCheck::unknown_command;
  if (r.size != row->request_size) return RequestCheck::bad_size;
  if (r.uid == kGlobalUid && row->command != Command::execute_speed) {
    return RequestCheck::global_not_83;
  }
  return RequestCheck::ok;
}

std::string_view to_string(RequestCheck c) {
  switch (c) {
    case RequestCheck::ok:
      return "ok";
    case RequestCheck::unknown_command:
      return "unknown command";
    case RequestCheck::bad_size:
      return "data length does not fit the command";
    case RequestCheck::global_not_83:
      return "UID 0 is only for command 83 (execute speed)";
  }
  return "?";
}

std::string_view to_string(Outcome o) {
  switch (o) {
    case Outcome::ack:
      return "ack";
    case Outcome::nak:
      return "nak";
    case Outcome::timeout:
      return "timeout";
    case Outcome::inter_byte_timeout:
      return "inter-byte timeout";
    case Outcome::bad_response:
      return "bad response";
    case Outcome::sent:
      return "sent";
    case Outcome::line_busy:
      return "line busy";
  }
  return "?";
}

StartStatus HostTransaction::start(const Frame& request, Time now) {
  if (state_ != State::idle) return StartStatus::busy;
  if (check_request(request) != RequestCheck::ok) return StartStatus::rejected;
  request_ = request;
  tx_ = encode(request);
  state_ = State::sending;
  sent_at_ = now;
  last_error_.reset();
  return StartStatus::accepted;
}

void HostTransaction::transmitted(Time now) {
  if (state_ != State::sending) return;
  sent_at_ = now;
  if (request_.uid == kGlobalUid) {
    finish(Outcome::sent, now);  // notes: UID 00 with 83, no response
    return;
  }
  decoder_.reset();
  state_ = State::awaiting_response;
  response_deadline_ = now + timeouts_.response;
  overall_deadline_ = now + timeouts_.overall();
  deadline_ = response_deadline_;
  bytes_heard_ = 0;
  other_frames_ = 0;
  corrupt_frames_ = 0;
}

void HostTransaction::finish(Outcome o, Time now) {
  result_ = HostResult{};
  result_.outcome = o;
  result_.request = request_;
  result_.elapsed = now - sent_at_;
  result_.last_decode_error = last_error_;
  result_.bytes_heard = bytes_heard_;
  result_.other_frames = other_frames_;
  result_.corrupt_frames = corrupt_frames_;
  state_ = State::done;
}

void HostTransaction::receive(std::uint8_t byte, Time now) {
  if (state_ != State::awaiting_response) return;
  if (now >= deadline_) {
    poll(now);
    if (state_ != State::awaiting_response) return;
  }
  ++bytes_heard_;
  const DecodeResult r = decoder_.push(byte);
  if (r.status == DecodeStatus::error) {
    ++decode_errors_;
    ++corrupt_frames_;
    last_error_ = r.error;
  } else if (r.status == DecodeStatus::frame) {
    const Frame& f = decoder_.frame();
    if (f.uid != request_.uid || (!f.is_ack() && !f.is_nak())) {
      ++foreign_frames_;
      ++other_frames_;
    } else {
      const std::uint8_t want = command_info(static_cast<Command>(request_.code)).response_size;
      Outcome o = Outcome::bad_response;
      if (f.is_ack() && f.size == want) o = Outcome::ack;
      if (f.is_nak() && f.size == 1) o = Outcome::nak;
      finish(o, now);
      result_.response = f;
      if (o == Outcome::nak) result_.error = f.data[0];
      return;
    }
  }
  // The first byte of a response switches from the response to the inter-byte timeout; no
  // timer runs past the overall deadline.
  deadline_ = std::min(decoder_.in_frame() ? now + timeouts_.inter_byte : response_deadline_, overall_deadline_);
}

void HostTransaction::receive(std::span<const std::uint8_t> bytes, Time now) {
  for (std::uint8_t b : bytes) receive(b, now);
}

void HostTransaction::poll(Time now) {
  if (state_ != State::awaiting_response || now < deadline_) return;
  // Only bytes that kept a frame open can carry the wait to the overall deadline.
  if (now >= overall_deadline_ && now > response_deadline_) {
    finish(Outcome::line_busy, now);
    return;
  }
  finish(decoder_.in_frame() ? Outcome::inter_byte_timeout : Outcome::timeout, now);
}

std::optional<Time> HostTransaction::next_deadline() const {
  if (state_ != State::awaiting_response) return std::nullopt;
  return deadline_;
}

std::optional<HostResult> HostTransaction::take_result() {
  if (state_ != State::done) return std::nullopt;
  state_ = State::idle;
  return result_;
}

}  // namespace ibs::dfs1
