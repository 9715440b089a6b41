#include "ibs/lustbus/line.hpp"

#include <algorithm>

#include "ibs/lustbus/timing.hpp"

namespace ibs::lustbus {

namespace {
constexpr std::size_t kTxCapacity = 4 * kMaxTelegramLength;
}

Line::Line(std::uint32_t baud, Time start) : baud_(baud), now_(start) {}

void Line::attach(Host& host) {
  host_.host = &host;
  host_.index = kHostNode;
  host_.tx.reserve(kTxCapacity);
}

int Line::attach(Receiver& device) {
  Node n;
  n.device = &device;
  n.index = static_cast<int>(devices_.size());
  n.tx.reserve(kTxCapacity);
  devices_.push_back(std::move(n));
  return devices_.back().index;
}

void Line::append(Node& n, std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t b : bytes) n.tx.push_back(b);
}

bool Line::quiet() const {
  auto busy = [](const Node& n) { return n.in_flight || n.tx_head < n.tx.size(); };
  if (busy(host_)) return false;
  for (const Node& d : devices_) {
    if (busy(d) || d.device->answer_due()) return false;
  }
  return true;
}

bool Line::host_idle() const {
  return host_.host == nullptr || (host_.host->idle() && !host_.host->output_pending());
}

Time Line::next_event() const {
  Time t = Time::max();
  auto consider = [&t, this](const Node& n) {
    if (n.in_flight) {
      t = std::min(t, n.current.end);
    } else if (n.tx_head < n.tx.size()) {
      t = std::min(t, now_);
    }
  };
  consider(host_);
  for (const Node& d : devices_) {
    consider(d);
    if (const auto due = d.device->answer_due()) t = std::min(t, *due);
  }
  if (host_.host != nullptr) t = std::min(t, host_.host->next_deadline());
  return std::max(t, now_);
}

void Line::deliver(const Node& from) {
  ++stats_.characters;
  LineChar c = from.current;
  if (tap_) tap_(c);
  auto mismatched = [this](const Node& n) { return n.baud != 0 && n.baud != baud_; };
  std::uint8_t b = c.collided || mismatched(from) ? kGarbled : c.byte;
  if (filter_) {
    LineChar f = c;
    f.byte = b;
    const auto out = filter_(f);
    if (!out) return;  // lost
    b = *out;
  }
  if (from.index != kHostNode && host_.host != nullptr) host_.host->receive(b, c.end);
  for (const Node& d : devices_) {
    if (d.index != from.index) d.device->receive(mismatched(d) ? kGarbled : b, c.end);
  }
}

void Line::start_character(Node& n, Time t) {
  n.in_flight = true;
  n.current = LineChar{n.index, n.tx[n.tx_head++], false, t, t + character_time(baud_)};
  if (n.tx_head == n.tx.size()) {
    n.tx.clear();
    n.tx_head = 0;
  }
  // Two transmitters at once garble both characters (9.1).
  auto check = [&n, t, this](Node& other) {
    if (&other == &n || !other.in_flight || other.current.end <= t) return;
    if (!other.current.collided || !n.current.collided) ++stats_.collisions;
    other.current.collided = true;
    n.current.collided = true;
  };
  check(host_);
  for (Node& d : devices_) check(d);
}

void Line::process(Time t) {
  now_ = t;
  // 1. Characters ending now reach every other node.
  auto finish = [this, t](Node& n) {
    if (!n.in_flight || n.current.end > t) return false;
    n.in_flight = false;
    deliver(n);
    return true;
  };
  if (finish(host_) && host_.tx_head >= host_.tx.size()) host_.host->output_done(t);
  for (Node& d : devices_) finish(d);
  // 2. The host's timeouts and its next telegram.
  if (host_.host != nullptr) {
    host_.host->step(t);
    append(host_, host_.host->take_output());
  }
  // 3. Answers that are due.
  for (Node& d : devices_) append(d, d.device->take_answer(t));
  // 4. Idle transmitters start their next character.
  if (!host_.in_flight && host_.tx_head < host_.tx.size()) start_character(host_, t);
  for (Node& d : devices_) {
    if (!d.in_flight && d.tx_head < d.tx.size()) start_character(d, t);
  }
}

void Line::run_until(Time limit) {
  for (;;) {
    const Time t = next_event();
    if (t > limit) break;
    const auto before = stats_.characters;
    const bool was_quiet = quiet();
    process(t);
    // Nothing moved at this instant (a deadline equal to now that did nothing): step past it.
    if (t == now_ && before == stats_.characters && was_quiet && quiet() && next_event() == t) {
      now_ = t + Duration{1};
    }
  }
  now_ = std::max(now_, limit);
}

bool Line::run_until_idle(Time limit) {
  for (;;) {
    if (quiet() && host_idle()) return true;
    const Time t = next_event();
    if (t > limit) {
      now_ = std::max(now_, limit);
      return false;
    }
    const auto before = stats_.characters;
    const bool was_quiet = quiet();
    process(t);
    if (before == stats_.characters && was_quiet && quiet() && next_event() == t) {
      now_ = t + Duration{1};
    }
  }
}

}  // namespace ibs::lustbus
