// A simulated CANLust bus for the CDA3000 tests: the virtual bus, one master side (the core's
// canlust::Master for byte-level tests, or the wing's Driver) and emulated CDA3000 drives, run
// event by event in simulated time. Every frame on the bus is recorded with its start and end.
#pragma once

#include <algorithm>
#include <memory>
#include <vector>

#include "ibs/can/virtual_bus.hpp"
#include "ibs/canlust/master.hpp"
#include "ibs/devices/cda3000/device.hpp"

namespace ibs::devices::cda3000::test {

struct Seen {
  canlust::CanFrame frame;
  Time start;
  Time end;
};

template <typename MasterT>
class Bus {
 public:
  explicit Bus(MasterT& master, std::uint32_t bitrate = 500'000) : bus_({bitrate, 256, 4096}), master_(&master) {
    master_id_ = bus_.attach("master");
    spy_ = bus_.attach("spy");
    seen_.reserve(200000);
  }

  // An emulated drive, powered on at `at`.
  std::size_t add(const DeviceConfig& c, Time at = Time{0}) {
    auto d = std::make_unique<Drive>(c);
    d->bus_id = bus_.attach("cda3000");
    d->power_on = at;
    drives_.push_back(std::move(d));
    return drives_.size() - 1;
  }

  void run_until(Time end) {
    for (int guard = 0; guard < 50'000'000; ++guard) {
      const Time t = std::max(now_, next_time());
      if (t > end) {
        process(end);
        return;
      }
      process(t);
    }
  }
  void run_for(Duration d) { run_until(now_ + d); }
  // Runs until `done()` or `limit` has passed; true when done.
  template <typename F>
  bool run_until_true(F done, Duration limit) {
    const Time end = now_ + limit;
    while (now_ < end) {
      if (done()) return true;
      run_for(std::min<Duration>(1ms, end - now_));
    }
    return done();
  }
  // Mains off and on again at the current time.
  void mains_reset(std::size_t i) { drives_[i]->device.power_on(now_); }

  Cda3000& drive(std::size_t i) { return drives_[i]->device; }
  can::VirtualBus& bus() { return bus_; }
  [[nodiscard]] Time now() const { return now_; }
  [[nodiscard]] const std::vector<Seen>& seen() const { return seen_; }
  [[nodiscard]] std::vector<Seen> seen_with_id(std::uint16_t id, Time from = Time::min()) const {
    std::vector<Seen> v;
    for (const auto& s : seen_) {
      if (s.frame.id == id && s.start >= from) v.push_back(s);
    }
    return v;
  }
  // A frame on the bus from the master's port, bypassing the master object.
  void inject(const canlust::CanFrame& f) { bus_.send(master_id_, f, now_); }

 private:
  struct Drive {
    explicit Drive(const DeviceConfig& c) : device(c) {}
    Cda3000 device;
    can::NodeId bus_id = 0;
    Time power_on{};
    bool on = false;
  };

  Time next_time() const {
    Time t = std::min(bus_.next_event(), master_->next_deadline());
    for (const auto& d : drives_) t = std::min(t, d->on ? d->device.next_deadline() : d->power_on);
    return t;
  }

  void master_step(Time now) {
    if constexpr (requires { master_->cycle(now); }) {
      master_->cycle(now);
    } else {
      master_->step(now);
    }
  }

  void process(Time now) {
    now_ = now;
    for (auto& d : drives_) {
      if (!d->on && now >= d->power_on) {
        d->on = true;
        d->device.power_on(d->power_on);
      }
    }
    bus_.advance(now);
    while (auto s = bus_.receive(spy_)) seen_.push_back({s->frame, s->start, s->time});
    while (auto r = bus_.receive(master_id_)) master_->receive(r->frame, r->time);
    for (auto& d : drives_) {
      while (auto r = bus_.receive(d->bus_id)) d->device.receive(r->frame, r->time);
    }
    master_step(now);
    while (auto f = master_->take_frame()) bus_.send(master_id_, *f, now);
    for (auto& d : drives_) {
      if (!d->on) continue;
      d->device.step(now);
      while (auto f = d->device.take_frame()) bus_.send(d->bus_id, *f, now);
    }
    bus_.advance(now);
  }

  can::VirtualBus bus_;
  MasterT* master_;
  can::NodeId master_id_ = 0;
  can::NodeId spy_ = 0;
  std::vector<std::unique_ptr<Drive>> drives_;
  std::vector<Seen> seen_;
  Time now_{0};
};

inline DeviceConfig commissioned(std::uint8_t address, std::uint8_t cacnf = 2) {
  DeviceConfig c;
  c.saved = commissioned_for_bus(address, cacnf);
  return c;
}

}  // namespace ibs::devices::cda3000::test
