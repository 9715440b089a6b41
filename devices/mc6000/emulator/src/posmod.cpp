#include "ibs/devices/mc6000/posmod.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "ibs/lustbus/code.hpp"

namespace ibs::devices::mc6000 {

namespace lb = ibs::lustbus;

namespace {

// A whole decimal number (optional sign) at the start of `s`; advances `s` past it.
std::optional<std::int64_t> take_number(std::string_view& s) {
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end == s.data()) return std::nullopt;
  s.remove_prefix(static_cast<std::size_t>(end - s.data()));
  return v;
}

bool starts(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

// "%P<n>" followed by nothing or a blank and a comment (11.6.4: "%P10 (RPF)").
std::optional<int> program_header(std::string_view s) {
  if (!starts(s, "%P")) return std::nullopt;
  s.remove_prefix(2);
  const auto n = take_number(s);
  if (!n || *n < 0 || *n > 99 || (!s.empty() && s[0] != ' ')) return std::nullopt;
  return static_cast<int>(*n);
}

lb::Value answer(lb::PosmodStatus st, std::string_view text) {
  lb::Value v;
  v.push_back(static_cast<std::uint8_t>(lb::posmod_status_char(st)));
  for (const char c : text) {
    if (!v.push_back(static_cast<std::uint8_t>(c))) break;
  }
  return v;
}

}  // namespace

std::string_view to_string(PosmodError e) {
  switch (e) {
    case PosmodError::none:
      return "no error";
    case PosmodError::syntax:
      return "syntax error";
    case PosmodError::status_byte:
      return "invalid status byte";
    case PosmodError::no_program:
      return "no such program";
    case PosmodError::no_request:
      return "no request pending";
    case PosmodError::memory_full:
      return "program memory full";
    case PosmodError::sequence:
      return "block out of sequence";
    case PosmodError::not_enabled:
      return "drive not enabled";
  }
  return "?";
}

PosMod::PosMod(const PosmodConfig& config) : config_(config), programs_(config.programs) {
  for (auto& p : programs_) p.lines.resize(config_.lines_per_program);
  staging_.lines.resize(config_.lines_per_program);
}

std::size_t PosMod::stored_programs() const {
  std::size_t n = 0;
  for (const auto& p : programs_) n += p.number >= 0 ? 1U : 0U;
  return n;
}

PosMod::Program* PosMod::find(int number) {
  for (auto& p : programs_) {
    if (p.number == number) return &p;
  }
  return nullptr;
}

bool PosMod::fail(PosmodError e) {
  error_ = e;
  return false;
}

void PosMod::restart(Time now) {
  moving_ = false;
  velocity_ = 0;
  carry_ = 0.0;
  transferring_ = false;
  pending_ = Pending::none;
  error_ = PosmodError::none;
  last_ = now;
}

void PosMod::advance(Time now, bool enabled) {
  const Duration dt = now > last_ ? now - last_ : Duration{0};
  last_ = now;
  enabled_ = enabled;
  if (!moving_) return;
  if (!enabled) {  // the power stage went off: the axis stops where it is
    moving_ = false;
    carry_ = 0.0;
    return;
  }
  const double travel = static_cast<double>(velocity_) * static_cast<double>(dt.count()) / 1e9 + carry_;
  const auto whole = static_cast<std::int64_t>(std::floor(travel));
  carry_ = travel - static_cast<double>(whole);
  const std::int64_t left = target_ > position_ ? target_ - position_ : position_ - target_;
  if (whole >= left) {
    position_ = target_;
    moving_ = false;
    carry_ = 0.0;
  } else {
    position_ += target_ > position_ ? whole : -whole;
  }
}

bool PosMod::select(std::string_view user_data, Time now) {
  advance(now, enabled_);
  if (user_data.empty()) return fail(PosmodError::status_byte);
  const auto st = lb::parse_posmod_status(user_data[0]);
  if (!st) return fail(PosmodError::status_byte);
  const std::string_view d = user_data.substr(1);
  return st->request ? request(d) : data(d, st->multiblock, now);
}

bool PosMod::data(std::string_view d, bool multiblock, Time now) {
  (void)now;
  if (transferring_) {
    if (!multiblock) {  // the last block of the transfer
      if (d != "END") {
        transferring_ = false;
        return fail(PosmodError::sequence);
      }
      transferring_ = false;
      Program* slot = find(staging_.number);
      if (slot == nullptr) slot = find(-1);
      if (slot == nullptr) return fail(PosmodError::memory_full);
      slot->number = staging_.number;
      slot->header = staging_.header;
      slot->count = staging_.count;
      for (std::size_t i = 0; i < staging_.count; ++i) slot->lines[i] = staging_.lines[i];
      return true;
    }
    if (staging_.count >= staging_.lines.size()) {
      transferring_ = false;
      return fail(PosmodError::memory_full);
    }
    staging_.lines[staging_.count++] = lb::Value::from(d).value_or(lb::Value{});
    return true;
  }
  if (multiblock) {  // the first block of a transfer: "%P<n>"
    const auto n = program_header(d);
    if (!n) return fail(PosmodError::sequence);
    staging_.number = *n;
    staging_.header = lb::Value::from(d).value_or(lb::Value{});
    staging_.count = 0;
    transferring_ = true;
    return true;
  }
  // A manual command.
  if (d == "ST") {
    moving_ = false;
    return true;
  }
  if (d == "HOME") {
    if (moving_) return fail(PosmodError::sequence);
    position_ = 0;
    referenced_ = true;
    return true;
  }
  if (starts(d, "GOA") || starts(d, "GOR")) {
    const bool absolute = d[2] == 'A';
    std::string_view rest = d.substr(3);
    const auto pos = take_number(rest);
    if (!pos) return fail(PosmodError::syntax);
    std::int64_t vel = config_.default_velocity;
    if (!rest.empty()) {
      if (rest[0] != 'V') return fail(PosmodError::syntax);
      rest.remove_prefix(1);
      const auto v = take_number(rest);
      if (!v || *v <= 0 || !rest.empty()) return fail(PosmodError::syntax);
      vel = *v;
    }
    if (!enabled_) return fail(PosmodError::not_enabled);
    target_ = absolute ? *pos : position_ + *pos;
    velocity_ = vel;
    moving_ = target_ != position_;
    carry_ = 0.0;
    return true;
  }
  return fail(PosmodError::syntax);
}

bool PosMod::request(std::string_view d) {
  if (d == "?") {
    pending_ = Pending::status;
    return true;
  }
  if (d == "%RDF") {
    pending_ = Pending::error;
    return true;
  }
  if (starts(d, "%RDP")) {
    std::string_view rest = d.substr(4);
    const auto n = take_number(rest);
    if (!n || !rest.empty()) return fail(PosmodError::syntax);
    if (find(static_cast<int>(*n)) == nullptr || *n < 0) return fail(PosmodError::no_program);
    pending_ = Pending::program;
    read_program_ = static_cast<int>(*n);
    read_line_ = 0;
    return true;
  }
  return fail(PosmodError::syntax);
}

std::optional<lb::Value> PosMod::enquiry(Time now) {
  advance(now, enabled_);
  char text[lb::kMaxValueLength]{};
  switch (pending_) {
    case Pending::none:
      fail(PosmodError::no_request);
      return std::nullopt;
    case Pending::status: {
      pending_ = Pending::none;
      std::snprintf(text, sizeof text, "G%d%dH%d%d P%lld", enabled_ ? 1 : 0, moving_ ? 1 : 0,
                    referenced_ ? 1 : 0, error_ != PosmodError::none ? 1 : 0,
                    static_cast<long long>(position_));
      return answer({false, false}, text);
    }
    case Pending::error: {
      pending_ = Pending::none;
      std::snprintf(text, sizeof text, "F%02u %.*s", static_cast<unsigned>(error_),
                    static_cast<int>(to_string(error_).size()), to_string(error_).data());
      error_ = PosmodError::none;  // reading clears it
      return answer({false, false}, text);
    }
    case Pending::program: {
      const Program* p = find(read_program_);
      if (p == nullptr) {
        pending_ = Pending::none;
        fail(PosmodError::no_program);
        return std::nullopt;
      }
      if (read_line_ == 0) {
        ++read_line_;
        return answer({false, true}, p->header.view());
      }
      if (read_line_ <= p->count) {
        return answer({false, true}, p->lines[read_line_++ - 1].view());
      }
      pending_ = Pending::none;
      return answer({false, false}, "END");
    }
  }
  return std::nullopt;
}

}  // namespace ibs::devices::mc6000
