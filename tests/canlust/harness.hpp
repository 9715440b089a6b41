// A simulated CANLust bus for the tests: the virtual bus, the master and fake drive nodes,
// stepped event by event in simulated time. Every frame on the bus is recorded.
#pragma once

#include <algorithm>
#include <memory>
#include <vector>

#include "fake_drive.hpp"
#include "ibs/can/virtual_bus.hpp"
#include "ibs/canlust/master.hpp"
#include "ibs/canlust/node.hpp"

namespace ibs::canlust::test {

struct Seen {
  CanFrame frame;
  Time start;
  Time end;
  can::NodeId sender;
};

class Harness {
 public:
  explicit Harness(const MasterConfig& mc = {}, std::uint32_t bitrate = 500'000)
      : bus_({bitrate, 64, 1024}), master_(mc) {
    master_id_ = bus_.attach("master");
    spy_ = bus_.attach("spy");
    seen_.reserve(100000);
  }

  // Adds a drive node; powered on at `at` by run_until().
  std::size_t add_drive(const NodeConfig& nc, Time power_on = Time{0}) {
    auto d = std::make_unique<Drive>();
    d->drive = std::make_unique<FakeDrive>();
    d->node = std::make_unique<Node>(nc, *d->drive, *d->drive);
    d->bus_id = bus_.attach("drive");
    d->power_on = power_on;
    drives_.push_back(std::move(d));
    return drives_.size() - 1;
  }

  void run_until(Time end) {
    for (int guard = 0; guard < 10'000'000; ++guard) {
      Time t = std::max(now_, next_time());
      if (t > end) {
        process(end);
        return;
      }
      process(t);
    }
  }
  void run_for(Duration d) { run_until(now_ + d); }

  Master& master() { return master_; }
  Node& node(std::size_t i) { return *drives_[i]->node; }
  FakeDrive& drive(std::size_t i) { return *drives_[i]->drive; }
  can::VirtualBus& bus() { return bus_; }
  [[nodiscard]] Time now() const { return now_; }
  [[nodiscard]] const std::vector<Seen>& seen() const { return seen_; }
  std::vector<Seen> seen_with_id(std::uint16_t id) const {
    std::vector<Seen> v;
    for (const auto& s : seen_) {
      if (s.frame.id == id) v.push_back(s);
    }
    return v;
  }
  // Sends a frame as if from the master's bus port (bypassing the Master object).
  void inject(const CanFrame& f) { bus_.send(master_id_, f, now_); }

 private:
  struct Drive {
    std::unique_ptr<FakeDrive> drive;
    std::unique_ptr<Node> node;
    can::NodeId bus_id = 0;
    Time power_on{};
    bool on = false;
  };

  Time next_time() const {
    Time t = std::min(bus_.next_event(), master_.next_deadline());
    for (const auto& d : drives_) {
      t = std::min(t, d->on ? d->node->next_deadline() : d->power_on);
    }
    return t;
  }

  void process(Time now) {
    now_ = now;
    for (auto& d : drives_) {
      if (!d->on && now >= d->power_on) {
        d->on = true;
        d->node->power_on(d->power_on);
      }
    }
    bus_.advance(now);
    while (auto s = bus_.receive(spy_)) seen_.push_back({s->frame, s->start, s->time, s->sender});
    while (auto r = bus_.receive(master_id_)) master_.receive(r->frame, r->time);
    for (auto& d : drives_) {
      while (auto r = bus_.receive(d->bus_id)) d->node->receive(r->frame, r->time);
    }
    master_.step(now);
    while (auto f = master_.take_frame()) bus_.send(master_id_, *f, now);
    for (auto& d : drives_) {
      if (!d->on) continue;
      d->node->step(now);
      while (auto f = d->node->take_frame()) bus_.send(d->bus_id, *f, now);
    }
    bus_.advance(now);
  }

  can::VirtualBus bus_;
  Master master_;
  can::NodeId master_id_ = 0;
  can::NodeId spy_ = 0;
  std::vector<std::unique_ptr<Drive>> drives_;
  std::vector<Seen> seen_;
  Time now_{0};
};

inline NodeConfig node_config(Address a, Duration cascy = 80ms, Duration cawdg = 0ms) {
  NodeConfig c;
  c.address = a;
  c.status_period = cascy;
  c.watchdog = cawdg;
  return c;
}

}  // namespace ibs::canlust::test
