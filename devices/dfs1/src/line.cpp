#include "ibs/devices/dfs1/line.hpp"

#include <stdexcept>

namespace ibs::devices::dfs1 {

Duration character_time(std::uint32_t baud) {
  // 10 bits per character (start, 8 data, stop), rounded to the nearest nanosecond.
  return Duration((10'000'000'000LL + baud / 2) / baud);
}

SimulatedLine::SimulatedLine(Master& master, std::vector<Controller*> controllers,
                             std::uint32_t baud)
    : master_(master), controllers_(std::move(controllers)), char_time_(0) {
  if (baud == 0) throw std::invalid_argument("dfs1 line: the baud rate must be positive");
  for (const Controller* c : controllers_) {
    if (c == nullptr) throw std::invalid_argument("dfs1 line: a controller is missing (null)");
  }
  char_time_ = dfs1::character_time(baud);
}

void SimulatedLine::start_transmission() {
  if (in_flight_) return;
  std::optional<InFlight> first;
  std::size_t ready = 0;
  const auto offer = [&](std::span<const std::uint8_t> bytes, std::size_t sender) {
    if (bytes.empty()) return;
    ++ready;
    if (!first) first = InFlight{bytes[0], sender, now_ + char_time_};
  };
  offer(master_.pending(now_), 0);
  for (std::size_t i = 0; i < controllers_.size(); ++i)
    offer(controllers_[i]->pending(now_), i + 1);
  if (ready > 1) ++collisions_;
  in_flight_ = first;
}

std::optional<Time> SimulatedLine::next_event() const {
  std::optional<Time> next;
  const auto consider = [&](std::optional<Time> t) {
    if (t && *t > now_ && (!next || *t < *next)) next = t;
  };
  if (in_flight_) consider(in_flight_->ends);
  consider(master_.next_deadline());
  for (const Controller* c : controllers_) consider(c->next_deadline());
  return next;
}

void SimulatedLine::advance_to(Time t) {
  now_ = t;
  master_.poll(now_);
  for (Controller* c : controllers_) c->step(now_);
  if (in_flight_ && in_flight_->ends == now_) {
    const InFlight f = *in_flight_;
    in_flight_.reset();
    ++bytes_;
    if (observer_) observer_(now_, f.sender, f.byte);
    if (f.sender != 0) master_.receive(f.byte, now_);
    for (std::size_t i = 0; i < controllers_.size(); ++i) {
      if (i + 1 != f.sender) controllers_[i]->receive(f.byte, now_);
    }
    if (f.sender == 0) {
      master_.consume(1, now_);
    } else {
      controllers_[f.sender - 1]->consume(1);
    }
  }
}

bool SimulatedLine::quiet() {
  if (in_flight_ || !master_.idle()) return false;
  for (const Controller* c : controllers_) {
    if (c->next_deadline()) return false;
  }
  return true;
}

void SimulatedLine::run_until(Time t) {
  advance_to(now_);
  for (;;) {
    start_transmission();
    const std::optional<Time> next = next_event();
    if (!next || *next > t) break;
    advance_to(*next);
  }
  if (t > now_) advance_to(t);
}

Time SimulatedLine::run_until_idle(Time limit) {
  advance_to(now_);
  for (;;) {
    start_transmission();
    if (quiet()) return now_;
    const std::optional<Time> next = next_event();
    if (!next || *next > limit) break;
    advance_to(*next);
  }
  if (limit > now_) advance_to(limit);
  return now_;
}

}  // namespace ibs::devices::dfs1
