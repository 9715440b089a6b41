// The master loop's skip of holding drivers (MasterLoop::cycle, DeviceDriver::skip_while_holding):
// a driver whose last cycle only held, seeing the same input words and link flags while its
// sequencer still holds, is not called, and the loop writes its words. These tests run the loop
// beside the same drivers called every cycle by hand (what the loop is without the skip) over
// random runs, and compare every word written and every driver's state, cycle by cycle; and they
// pin the safety rule: whatever reaches the sequencer (a stop request through a reference the
// user kept, new application bits, a restart) ends the skip at the next cycle.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "ibs/devices/mc6000/driver.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/devices/vf1000/driver.hpp"
#include "ibs/master/master_loop.hpp"

namespace ibs::master {
namespace {

using namespace std::chrono_literals;
using devices::DeviceDriver;
using devices::DriverIo;

// A driver around another that counts its cycles and passes the inner driver's skip on, as any
// driver may: the loop sees only the interface.
class Counting final : public DeviceDriver {
 public:
  explicit Counting(std::unique_ptr<DeviceDriver> inner) : inner_(std::move(inner)) {}
  void cycle(const DriverIo& io, Time now) override {
    ++cycles;
    inner_->cycle(io, now);
    skip_ = inner_->skip_while_holding();
  }
  void initial(const DriverIo& io) override {
    inner_->initial(io);
    skip_ = inner_->skip_while_holding();
  }
  void restart(Time now) override {
    inner_->restart(now);
    skip_ = inner_->skip_while_holding();
  }
  drivecom::Sequencer& sequencer() override { return inner_->sequencer(); }
  devices::ParameterAccess& parameters() override { return inner_->parameters(); }
  void set_reference(double value) override {
    inner_->set_reference(value);
    skip_ = inner_->skip_while_holding();
  }
  [[nodiscard]] double reference() const override { return inner_->reference(); }
  [[nodiscard]] double actual() const override { return inner_->actual(); }
  [[nodiscard]] std::string_view unit() const override { return inner_->unit(); }

  long cycles = 0;

 private:
  std::unique_ptr<DeviceDriver> inner_;
};

// The kinds of device of a run: MC6000 without a channel (SUPI 12, Q16, 16-bit and no reference
// words), MC6000 with a one-word PCP channel (SUPI 11), VF1000 (communication word).
enum class Kind { q16, word16, none, pcp, vf1000 };

std::unique_ptr<DeviceDriver> make_driver(Kind k) {
  switch (k) {
    case Kind::q16: return std::make_unique<devices::Mc6000Driver>(devices::mc6000::make_layout(12, 2));
    case Kind::word16: return std::make_unique<devices::Mc6000Driver>(devices::mc6000::make_layout(12, 1));
    case Kind::none: return std::make_unique<devices::Mc6000Driver>(devices::mc6000::make_layout(12, 0));
    case Kind::pcp: return std::make_unique<devices::Mc6000Driver>(devices::mc6000::make_layout(11, 2));
    case Kind::vf1000: return std::make_unique<devices::Vf1000Driver>();
  }
  return nullptr;
}

interbus::DeviceSpec spec(Kind k, std::size_t i) {
  const std::string name = "d" + std::to_string(i);
  switch (k) {
    case Kind::q16: return {name, interbus::IdCode{devices::mc6000::make_layout(12, 2).id_code}, std::nullopt};
    case Kind::word16: return {name, interbus::IdCode{devices::mc6000::make_layout(12, 1).id_code}, std::nullopt};
    case Kind::none: return {name, interbus::IdCode{devices::mc6000::make_layout(12, 0).id_code}, std::nullopt};
    case Kind::pcp: return {name, interbus::IdCode{devices::mc6000::make_layout(11, 2).id_code}, std::nullopt};
    case Kind::vf1000: {
      const devices::Configuration vf = devices::vf1000::descriptor().configure({});
      return {name, vf.id_code, vf.bus};
    }
  }
  return {};
}

// A status word: the states a drive shows (ENABLED most often, so that holds happen), or any.
Word status_word(std::mt19937& rng) {
  static constexpr Word kWords[] = {0x0637, 0x0637, 0x0637, 0x0237, 0x0633, 0x0631, 0x0640,
                                    0x0608, 0x0617, 0x0600, 0x0621, 0x0627};
  if (rng() % 16 == 0) return static_cast<Word>(rng());
  return kWords[rng() % std::size(kWords)];
}

// The loop, and beside it the same drivers called every cycle over their own image.
struct Pair {
  explicit Pair(const std::vector<Kind>& kinds) {
    std::vector<interbus::DeviceSpec> specs;
    std::vector<std::unique_ptr<DeviceDriver>> drivers;
    for (std::size_t i = 0; i < kinds.size(); ++i) {
      specs.push_back(spec(kinds[i], i));
      auto c = std::make_unique<Counting>(make_driver(kinds[i]));
      counting.push_back(c.get());
      drivers.push_back(std::move(c));
      plain.push_back(make_driver(kinds[i]));
    }
    config = interbus::make_bus_config(specs);
    loop = std::make_unique<MasterLoop>(config, std::move(drivers));
    loop->initial(images[0]);
    for (std::size_t i = 0; i < plain.size(); ++i) plain[i]->initial(io(i));
  }

  DriverIo io(std::size_t i) {
    const interbus::Device& d = config.devices[i];
    DriverIo x;
    x.pd_in = {plain_image.in.data() + d.in.offset, d.in.length};
    x.pd_out = {plain_image.out.data() + d.out.offset, d.out.length};
    x.pcp_in = {plain_image.pcp_in.data() + d.pcp.offset, d.pcp.length};
    x.pcp_out = {plain_image.pcp_out.data() + d.pcp.offset, d.pcp.length};
    return x;
  }

  // One cycle of both: the loop over images[current], the plain drivers by hand.
  void cycle(Time now, bool valid, const std::vector<LinkState>& links) {
    loop->cycle(images[current], now, Exchange{valid, links});
    for (std::size_t i = 0; i < plain.size(); ++i) {
      DriverIo x = io(i);
      x.data_valid = valid && (i >= links.size() || links[i].data_valid);
      x.module_error = i < links.size() && links[i].module_error;
      plain[i]->cycle(x, now);
    }
  }

  // Everything a user can see of either side, compared.
  void expect_same(int cycle) {
    const interbus::ProcessImage& a = images[current];
    for (std::size_t i = 0; i < plain.size(); ++i) {
      const interbus::Device& d = config.devices[i];
      SCOPED_TRACE("cycle " + std::to_string(cycle) + ", device " + std::to_string(i));
      for (std::size_t w = 0; w < d.out.length; ++w) ASSERT_EQ(a.out[d.out.offset + w], plain_image.out[d.out.offset + w]);
      for (std::size_t w = 0; w < d.pcp.length; ++w) {
        ASSERT_EQ(a.pcp_out[d.pcp.offset + w], plain_image.pcp_out[d.pcp.offset + w]);
      }
      DeviceDriver& l = loop->driver(i);
      const drivecom::Report& r = l.sequencer().report();
      const drivecom::Report& p = plain[i]->sequencer().report();
      ASSERT_EQ(l.sequencer().last_control(), plain[i]->sequencer().last_control());
      ASSERT_EQ(l.sequencer().hold_code(), plain[i]->sequencer().hold_code());
      ASSERT_EQ(r.goal, p.goal);
      ASSERT_EQ(r.target, p.target);
      ASSERT_EQ(r.phase, p.phase);
      ASSERT_EQ(r.failure, p.failure);
      ASSERT_EQ(r.state_seen, p.state_seen);
      ASSERT_EQ(r.status_seen, p.status_seen);
      ASSERT_EQ(r.command_sent, p.command_sent);
      ASSERT_EQ(r.failed_command, p.failed_command);
      ASSERT_EQ(r.transition, p.transition);
      ASSERT_EQ(r.waited, p.waited);
      ASSERT_EQ(r.timeout, p.timeout);
      ASSERT_EQ(r.since, p.since);
      const double la = l.actual();
      const double pa = plain[i]->actual();
      ASSERT_TRUE(la == pa || (la != la && pa != pa)) << la << " " << pa;
      ASSERT_EQ(l.reference(), plain[i]->reference());
    }
  }

  interbus::BusConfig config;
  std::unique_ptr<MasterLoop> loop;
  std::vector<Counting*> counting;
  std::vector<std::unique_ptr<DeviceDriver>> plain;
  interbus::ProcessImage images[2];
  std::size_t current = 0;
  interbus::ProcessImage plain_image;
};

TEST(MasterLoopSkip, WritesAndChangesWhatCallingEveryDriverDoesOverRandomRuns) {
  long skipped = 0;
  long calls_if_no_skip = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    // A random ring; every fourth seed fills the whole image, its last device ending with it.
    std::vector<Kind> kinds;
    if (seed % 4 == 0) {
      kinds.assign(63, Kind::q16);
      kinds.push_back(Kind::none);
    } else {
      const std::size_t n = 1 + rng() % 24;
      for (std::size_t i = 0; i < n; ++i) {
        static constexpr Kind kAll[] = {Kind::q16, Kind::q16, Kind::q16, Kind::word16, Kind::none, Kind::pcp, Kind::vf1000};
        kinds.push_back(kAll[rng() % std::size(kAll)]);
      }
    }
    Pair p(kinds);
    const std::size_t n = kinds.size();
    // References the user keeps: requests reach the sequencers without the driver knowing.
    std::vector<drivecom::Sequencer*> held_loop, held_plain;
    for (std::size_t i = 0; i < n; ++i) {
      held_loop.push_back(&p.loop->driver(i).sequencer());
      held_plain.push_back(&p.plain[i]->sequencer());
      held_loop[i]->request(drivecom::Target::enabled, 0ns);
      held_plain[i]->request(drivecom::Target::enabled, 0ns);
    }
    std::vector<LinkState> links(n);
    bool valid = true;
    Time now{0};
    long calls_here = 0;
    for (int c = 0; c < 600; ++c) {
      // Calm stretches of 100 cycles, where nothing changes and holds last, between stormy ones.
      const bool storm = (c / 100) % 2 == 1;
      // The devices' words: mostly as they were.
      for (std::size_t i = 0; i < n; ++i) {
        const interbus::Device& d = p.config.devices[i];
        // A calm stretch begins with most drives showing ENABLED, as drives that followed would.
        const bool calm_begins = c % 200 == 0;
        if (!(calm_begins || (storm && rng() % 10 == 0))) continue;
        for (std::size_t w = 0; w < d.in.length; ++w) {
          const Word status = calm_begins && rng() % 4 != 0 ? Word{0x0637} : status_word(rng);
          const Word v = w == 0 ? status : static_cast<Word>(rng() % 4 == 0 ? rng() : 1000 + i);
          p.images[p.current].in[d.in.offset + w] = v;
          p.plain_image.in[d.in.offset + w] = v;
        }
        for (std::size_t w = 0; w < d.pcp.length; ++w) {
          const Word v = static_cast<Word>(rng());
          p.images[p.current].pcp_in[d.pcp.offset + w] = v;
          p.plain_image.pcp_in[d.pcp.offset + w] = v;
        }
      }
      // The bus: a failed cycle now and then, link flags that change, a shorter list.
      valid = !storm || rng() % 50 != 0;
      if (storm && rng() % 20 == 0) {
        LinkState& l = links[rng() % n];
        l.data_valid = rng() % 2 == 0;
        l.module_error = rng() % 4 == 0;
      }
      std::vector<LinkState> listed = links;
      if (storm && rng() % 30 == 0) listed.resize(rng() % (n + 1));
      // The user: requests, stop requests, application bits, references, restarts, parameters.
      for (std::size_t i = 0; storm && i < n; ++i) {
        const auto r = static_cast<unsigned>(rng() % 400);
        if (r == 0) {
          const drivecom::Target t = drivecom::kTargets[rng() % 4];
          held_loop[i]->request(t, now);
          held_plain[i]->request(t, now);
        } else if (r == 1) {
          held_loop[i]->request_emergency_stop(now);
          held_plain[i]->request_emergency_stop(now);
        } else if (r == 2) {
          held_loop[i]->request_block_power(now);
          held_plain[i]->request_block_power(now);
        } else if (r < 6) {
          const auto bits = static_cast<Word>(rng() % 3 == 0 ? rng() : 0);
          held_loop[i]->set_application_bits(bits);
          held_plain[i]->set_application_bits(bits);
        } else if (r < 12) {
          const double ref = static_cast<double>(static_cast<int>(rng() % 3000) - 1500);
          p.loop->driver(i).set_reference(ref);
          p.plain[i]->set_reference(ref);
        } else if (r == 12) {
          p.loop->driver(i).parameters().submit(devices::ParamOp::read, 21, 0);
          p.plain[i]->parameters().submit(devices::ParamOp::read, 21, 0);
        }
      }
      if (storm && rng() % 300 == 0) {
        p.loop->restart(now);
        for (auto& d : p.plain) d->restart(now);
      }
      if (storm && rng() % 200 == 0) {  // the loop handed the other image, holding the same words
        p.images[1 - p.current] = p.images[p.current];
        p.current = 1 - p.current;
      }
      p.cycle(now, valid, listed);
      calls_here += static_cast<long>(n);
      ASSERT_NO_FATAL_FAILURE(p.expect_same(c));
      now += std::chrono::milliseconds(1 + rng() % 5);
    }
    long calls = 0;
    for (const Counting* d : p.counting) calls += d->cycles;
    skipped += calls_here - calls;
    calls_if_no_skip += calls_here;
  }
  // The comparison means something only if the skip was taken, and often (about 15 % of the
  // calls: the stormy stretches leave many sequencers on stop goals, which hold nothing).
  EXPECT_GT(skipped, calls_if_no_skip / 10) << skipped << " of " << calls_if_no_skip;
}

// The full bus of the benchmark: once every servo holds ENABLED, the loop calls no driver, and
// writes every control word and reference all the same.
TEST(MasterLoopSkip, AHoldingFullBusCallsNoDriverAndKeepsItsWords) {
  Pair p(std::vector<Kind>(64, Kind::q16));
  for (std::size_t i = 0; i < 64; ++i) {
    p.loop->driver(i).sequencer().request(drivecom::Target::enabled, 0ns);
    p.loop->driver(i).set_reference(1000.0 + static_cast<double>(i));
    p.images[0].in[4 * i] = 0x0637;  // ENABLED
  }
  const std::vector<LinkState> links(64);
  p.loop->cycle(p.images[0], 0ms, Exchange{true, links});
  p.loop->cycle(p.images[0], 1ms, Exchange{true, links});
  const interbus::ProcessImage after_two = p.images[0];
  long calls = 0;
  for (const Counting* d : p.counting) calls += d->cycles;
  p.images[0].out.fill(0xDEAD);  // whatever happened to the words, the loop writes them again
  for (int c = 2; c < 100; ++c) p.loop->cycle(p.images[0], Time{std::chrono::milliseconds(c)}, Exchange{true, links});
  long calls_after = 0;
  for (const Counting* d : p.counting) calls_after += d->cycles;
  EXPECT_EQ(calls_after, calls);
  for (std::size_t i = 0; i < 64; ++i) {
    EXPECT_EQ(p.images[0].out[4 * i], 0x000F) << i;  // ENABLE OPERATION
    for (std::size_t w = 1; w < 4; ++w) EXPECT_EQ(p.images[0].out[4 * i + w], after_two.out[4 * i + w]) << i;
  }
}

// Safety: a skipped driver's sequencer still answers at the next cycle to everything that
// reaches it -- a stop request through a reference kept from before the skip, new application
// bits, a fault the drive shows, a link that loses its data.
TEST(MasterLoopSkip, WhatReachesAHoldingSequencerEndsTheSkipAtTheNextCycle) {
  Pair p(std::vector<Kind>(2, Kind::q16));
  drivecom::Sequencer& kept = p.loop->driver(1).sequencer();
  for (std::size_t i = 0; i < 2; ++i) {
    p.loop->driver(i).sequencer().request(drivecom::Target::enabled, 0ns);
    p.images[0].in[4 * i] = 0x0637;
  }
  std::vector<LinkState> links(2);
  Time now{0};
  auto cycle = [&] {
    p.loop->cycle(p.images[0], now, Exchange{true, links});
    now += 1ms;
  };
  cycle();
  cycle();
  const long before = p.counting[1]->cycles;
  cycle();
  ASSERT_EQ(p.counting[1]->cycles, before);  // skipped
  ASSERT_EQ(p.images[0].out[4], 0x000F);

  kept.request_block_power(now);
  cycle();
  EXPECT_EQ(p.counting[1]->cycles, before + 1);
  EXPECT_EQ(p.images[0].out[4] & 0x008F, 0x0000);  // BLOCK POWER at once

  kept.request(drivecom::Target::enabled, now);
  cycle();
  cycle();
  cycle();
  ASSERT_EQ(p.images[0].out[4], 0x000F);
  const long held = p.counting[1]->cycles;
  cycle();
  ASSERT_EQ(p.counting[1]->cycles, held);
  kept.set_application_bits(0x0800);
  cycle();
  EXPECT_EQ(p.counting[1]->cycles, held + 1);
  EXPECT_EQ(p.images[0].out[4], 0x080F);

  cycle();
  const long again = p.counting[1]->cycles;
  p.images[0].in[4] = 0x0608;  // FAULT
  cycle();
  EXPECT_EQ(p.counting[1]->cycles, again + 1);
  EXPECT_EQ(kept.report().state_seen, drivecom::State::fault);

  p.images[0].in[4] = 0x0637;
  kept.request(drivecom::Target::enabled, now);
  for (int c = 0; c < 6; ++c) cycle();
  const long enabled = p.counting[1]->cycles;
  links[1].data_valid = false;
  cycle();
  EXPECT_EQ(p.counting[1]->cycles, enabled + 1);
}

}  // namespace
}  // namespace ibs::master
