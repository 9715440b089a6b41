// Test fixtures: a PCP client and server on one simulated channel.
//
// Two clocks: the master steps the client every bus cycle, the servo steps the server every
// device sample (1 ms, INTERBUS manual 7.2). With cycle == sample it is the trace's lock-step timing.
// `Interface::at_cycle` runs the servo's link at the bus cycle as the MC6000's INTERBUS CPU does
// (Server::cycle every cycle, Server::sample every sample: the simulator's timing); by default
// the link runs in the servo's samples (Server::step), the slower case its guarantees must hold in too.
// Between them the bus: every cycle each side's latest frame is delivered to the other unless a
// fault says otherwise (the fault model of the brief):
//   corrupted - the cycle is discarded: neither direction's data is delivered;
//   lost      - one direction's word does not arrive, the receiver keeps the previous one;
//   repeated  - the receiver sees the same word again (as delivered the cycle before).
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>

#include "ibs/pcp/client.hpp"
#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/pcp_served.hpp"
#include "ibs/pcp/server.hpp"

namespace ibs::pcp::test {

// The server under test serves the MC6000's table; its numbers (85-SERR, 4-PROG, ...) read unqualified.
using namespace ibs::devices::mc6000;

struct FaultRates {
  double corrupted = 0.0;
  double lost_m2s = 0.0;
  double lost_s2m = 0.0;
  double repeated_m2s = 0.0;
  double repeated_s2m = 0.0;
};

struct FaultCounts {
  std::uint64_t corrupted = 0;
  std::uint64_t lost = 0;
  std::uint64_t repeated = 0;
};

enum class Interface : std::uint8_t { at_sample, at_cycle };

class Bus {
 public:
  Bus(Client& client, Server& server, Duration cycle = 1ms, Duration sample = 1ms,
      Interface interface = Interface::at_sample)
      : client_(&client), server_(&server), cycle_(cycle), sample_(sample), interface_(interface) {}

  void set_faults(const FaultRates& f, std::uint32_t seed) {
    faults_ = f;
    rng_.seed(seed);
  }
  void set_client(Client& c) { client_ = &c; }
  void set_server(Server& s) { server_ = &s; }

  [[nodiscard]] Time now() const { return now_; }
  [[nodiscard]] const FaultCounts& fault_counts() const { return counts_; }

  // One bus cycle; the servo samples whenever its next sample time has come.
  void cycle() {
    now_ += cycle_;
    deliver();
    client_->step(now_, client_in_, client_out_);
    if (interface_ == Interface::at_cycle) server_->cycle(now_, server_in_, server_out_);
    while (next_sample_ <= now_) {
      if (interface_ == Interface::at_cycle) {
        server_->sample(next_sample_);
      } else {
        server_->step(next_sample_, server_in_, server_out_);
      }
      next_sample_ += sample_;
    }
  }

  // Runs cycles until `done` or `limit` of simulated time has passed; true when done.
  bool run_until(const std::function<bool()>& done, Duration limit) {
    const Time end = now_ + limit;
    while (!done()) {
      if (now_ >= end) return false;
      cycle();
    }
    return true;
  }

  // Runs until the client has a result and returns it (nullopt after `limit`).
  std::optional<Result> await(Duration limit = 5s) {
    std::optional<Result> r;
    run_until(
        [&] {
          r = client_->take_result();
          return r.has_value();
        },
        limit);
    return r;
  }

  [[nodiscard]] std::span<const Word> client_out() const { return {client_out_.data(), 4}; }
  [[nodiscard]] std::span<const Word> server_out() const { return {server_out_.data(), 4}; }

 private:
  bool chance(double p) {
    return p > 0.0 && std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < p;
  }

  void deliver() {
    if (chance(faults_.corrupted)) {
      ++counts_.corrupted;
      return;
    }
    if (chance(faults_.lost_m2s)) {
      ++counts_.lost;
    } else if (chance(faults_.repeated_m2s)) {
      ++counts_.repeated;  // server_in_ stays what it was: the same word again
    } else {
      server_in_ = client_out_;
    }
    if (chance(faults_.lost_s2m)) {
      ++counts_.lost;
    } else if (chance(faults_.repeated_s2m)) {
      ++counts_.repeated;
    } else {
      client_in_ = server_out_;
    }
  }

  Client* client_;
  Server* server_;
  Duration cycle_;
  Duration sample_;
  Interface interface_;
  Time now_{};
  Time next_sample_{};
  std::array<Word, 4> client_in_{};
  std::array<Word, 4> client_out_{};
  std::array<Word, 4> server_in_{};
  std::array<Word, 4> server_out_{};
  FaultRates faults_{};
  FaultCounts counts_{};
  std::mt19937 rng_{1};
};

inline ClientConfig client_config(int words) {
  ClientConfig c;
  c.channel_words = words;
  return c;
}

inline ServerConfig server_config(int words, std::optional<LatencyModel> latency = std::nullopt) {
  ServerConfig c = ibs::devices::mc6000::server_config(1);
  c.channel_words = words;
  c.latency = latency;
  return c;
}

// The MC6000's parameters (the drive core's, without a servo behind them) as a server serves
// them; `start` power_on keeps 85-SERR's power-on bit, running has read it.
struct Served {
  explicit Served(StartMode start = StartMode::running, std::span<const ParameterInfo> table = ibs::devices::mc6000::parameters())
      : drive([&] {
          auto c = ibs::devices::mc6000::drive_parameters_config();
          c.table = table;
          return c;
        }()),
        served(drive) {
    if (start == StartMode::running) drive.read(Time{}, kSerr);
  }
  Served(const Served&) = delete;
  Served& operator=(const Served&) = delete;
  ibs::devices::mc6000::ParametersOnly drive;
  ibs::devices::mc6000::PcpServed served;
};

// A client and a server on a lock-step bus (1 ms cycles and samples), with shortcuts.
struct Session {
  explicit Session(int words, ServerConfig sc, ClientConfig cc = {})
      : client([&] {
          cc.channel_words = words;
          return cc;
        }()),
        parameters(sc.start),
        server([&] {
          sc.channel_words = words;
          return sc;
        }(), parameters.served),
        bus(client, server) {}
  explicit Session(int words) : Session(words, running_server()) {}

  static ServerConfig running_server() {
    ServerConfig s = ibs::devices::mc6000::server_config(1);
    s.start = StartMode::running;
    return s;
  }

  template <class Submit>
  Result run(Submit submit, Duration limit = 20s) {
    const SubmitStatus st = submit(client, bus.now());
    EXPECT_EQ(st, SubmitStatus::accepted) << to_string(st);
    const auto r = bus.await(limit);
    EXPECT_TRUE(r.has_value()) << "no result";
    return r ? *r : Result{};
  }
  Result initiate() {
    return run([](Client& c, Time t) { return c.initiate(t); });
  }
  Result read(std::uint16_t number) {
    return run([&](Client& c, Time t) { return c.read(t, ParameterRef::number(number)); });
  }
  Result write(std::uint16_t number, Value v) {
    return run([&](Client& c, Time t) { return c.write(t, ParameterRef::number(number), v); });
  }
  // Reads 85-SERR (clearing it) and returns its value.
  std::uint32_t read_serr() {
    const Result r = read(kSerr);
    EXPECT_TRUE(r.ok());
    return r.data.size == 1 ? r.data.data[0] : 0xFFFF;
  }
  void idle(Duration d) {
    const Time end = bus.now() + d;
    while (bus.now() < end) bus.cycle();
  }

  // The servo switched off and on: its parameters (85-SERR power-on bit) and the server's link.
  void power_on() {
    drive().power_on(bus.now());
    server.power_on(bus.now());
  }
  // The drive's parameters behind the server (the core's store, 85-SERR, EEPROM, PROG, SLOAD).
  [[nodiscard]] ibs::devices::mc6000::DriveParameters& drive() { return parameters.drive.parameters(); }

  Client client;
  Served parameters;
  Server server;
  Bus bus;
};

}  // namespace ibs::pcp::test
