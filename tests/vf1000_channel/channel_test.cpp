// Master against inverter: the Client and the Server run against each other in memory, with the
// timing convention of the cycle tables (each side answers what the other showed one step
// earlier). Thousands of random transactions checked against an independent parameter model, and
// transactions interrupted at every step by an inverter restart and by a master restart.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "ibs/vf1000_channel/client.hpp"
#include "ibs/devices/vf1000/channel.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/vf1000_channel/server.hpp"

namespace {

using namespace ibs::vf1000_channel;
using namespace ibs::drive;
using namespace ibs::devices::vf1000;
using ibs::Duration;
using ibs::Time;
using ibs::Word;
using namespace std::chrono_literals;

// Master and inverter on one in-memory channel. The inverter processes the channel every
// `inverter_every`-th master cycle (1: lockstep, as the tables; more: the VF1000's slower
// sampling), holding its word in between.
struct Channel {
  explicit Channel(const ClientConfig& cc, int inverter_every_cycles = 1,
                   ServerStart start = ServerStart::operational)
      : inverter(config(), start, Time{0}, parameters()),
        master(std::make_unique<Client>(cc)),
        inverter_every(inverter_every_cycles) {
    s2m = inverter.output();
  }
  static ServerConfig config() {
    ServerConfig c = server_config();
    c.init_duration = 200ms;  // shorter than the VF1000's 4 s: the behaviour is the same
    return c;
  }

  Server inverter;
  std::unique_ptr<Client> master;
  int inverter_every = 1;
  Duration cycle = 2ms;
  Time now{0};
  Word m2s = Client::initial_word();
  Word s2m = 0;
  bool power_stage_enabled = false;
  long cycles = 0;
  // Every value transfer the inverter committed, in order.
  std::vector<ServerEvent> writes;

  void step() {
    now += cycle;
    ++cycles;
    Word next_s2m = s2m;
    if (cycles % inverter_every == 0) {
      next_s2m = inverter.step(m2s, now, power_stage_enabled);
      if (inverter.last_event().kind == ServerEvent::Kind::value_written) {
        writes.push_back(inverter.last_event());
      }
    }
    const Word next_m2s = master->step(s2m, now);
    s2m = next_s2m;
    m2s = next_m2s;
  }
  // Steps until the request has an outcome (and a few more for the channel to come to rest).
  Outcome run(RequestId id, long max_cycles = 200000) {
    for (long i = 0; i < max_cycles; ++i) {
      const Poll p = master->poll(id);
      if (p.state == RequestState::done) return p.outcome;
      step();
    }
    ADD_FAILURE() << "request " << id << " has no outcome after " << max_cycles << " cycles";
    return {};
  }
  Outcome transact(const Request& r) {
    const Submitted s = master->submit(r);
    EXPECT_TRUE(s) << to_string(s.error);
    return run(s.id);
  }
};

ClientConfig lockstep_client() {
  ClientConfig c;
  c.start_synchronised = true;
  c.timeout = 2s;
  c.resync_hold = 20ms;
  return c;
}

// The parameter model the inverter must follow, written from the manuals independently of the
// server: values per number and 85-SIOF.
struct Model {
  explicit Model(std::span<const ParameterInfo> table) : params(table) { defaults(); }
  std::span<const ParameterInfo> params;
  std::map<std::uint16_t, Word> values;
  std::uint8_t siof = 0;

  void defaults() {
    for (const ParameterInfo& p : params) values[p.number] = p.default_value;
  }
  const ParameterInfo* find(std::uint16_t n) const {
    for (const ParameterInfo& p : params) {
      if (p.number == n) return &p;
    }
    return nullptr;
  }
  static bool fits(const ParameterInfo& p, Word v) {
    if (p.type == DataType::integer16) {
      const auto s = static_cast<std::int16_t>(v);
      return s >= static_cast<std::int16_t>(p.min) && s <= static_cast<std::int16_t>(p.max);
    }
    return v >= p.min && v <= p.max;
  }
  // The outcome a conforming master must report, and the model's state after it.
  Outcome expect(const Request& r, bool power_stage_enabled) {
    Outcome o;
    const ParameterInfo* p = find(r.number);
    switch (r.kind) {
      case RequestKind::value_inquiry:
        if (p == nullptr) {
          o.kind = OutcomeKind::nak;
          o.nak_cause = NakCause::no_parameter;
        } else if (r.number == 85) {
          o.kind = OutcomeKind::value;
          o.value = siof;
          siof = 0;  // reading clears (4.1.4)
        } else {
          o.kind = OutcomeKind::value;
          o.value = values[r.number];
        }
        return o;
      case RequestKind::description_scan:
        if (p == nullptr) {
          o.kind = OutcomeKind::nak;
          o.nak_cause = NakCause::no_parameter;
        } else {
          o.kind = OutcomeKind::description;
          o.description = make_description(*p);
        }
        return o;
      case RequestKind::value_transfer: {
        std::uint8_t bit = 0;
        if (siof != 0) {
          bit = 0;  // refused for the pending bits, no new one
        } else if (p == nullptr) {
          bit = 0x20;
        } else if (p->category == Category::ram_actual ||
                   p->category == Category::ram_actual_specific) {
          bit = 0x40;
        } else if (power_stage_enabled &&
                   (p->category == Category::eeprom || p->category == Category::eeprom_specific)) {
          bit = 0x40;
        } else if (!fits(*p, r.value)) {
          bit = 0x80;
        } else {
          o.kind = OutcomeKind::written;
          o.value = r.value;
          values[r.number] = r.value;
          if (r.number == 71 && r.value == 1) defaults();
          return o;
        }
        o.kind = OutcomeKind::nak;
        o.nak_cause = NakCause::siof;
        o.siof = static_cast<std::uint8_t>(siof | bit);
        siof = 0;  // the master reads 85-SIOF right after the NAK
        return o;
      }
    }
    return o;
  }
};

void expect_same_outcome(const Outcome& actual, const Outcome& expected, const std::string& what) {
  EXPECT_EQ(actual.kind, expected.kind)
      << what << ": got " << describe(actual) << ", expected " << describe(expected);
  switch (expected.kind) {
    case OutcomeKind::value:
    case OutcomeKind::written:
      EXPECT_EQ(actual.value, expected.value) << what;
      break;
    case OutcomeKind::description:
      EXPECT_EQ(actual.description, expected.description) << what;
      break;
    case OutcomeKind::nak:
      EXPECT_EQ(actual.nak_cause, expected.nak_cause) << what;
      EXPECT_EQ(actual.siof, expected.siof) << what;
      break;
    default:
      break;
  }
}

void expect_store_matches(const Server& s, const Model& m, const std::string& what) {
  for (const ParameterInfo& p : m.params) {
    const Word expected = p.number == 85 ? m.siof : m.values.at(p.number);
    ASSERT_EQ(s.value(p.number), expected) << what << ": parameter " << p.number << "-" << p.name;
  }
}

Request random_request(std::mt19937& rng, std::span<const ParameterInfo> table) {
  std::uniform_int_distribution<int> pct(0, 99);
  Request r;
  const int kind = pct(rng);
  r.kind = kind < 40   ? RequestKind::value_inquiry
           : kind < 85 ? RequestKind::value_transfer
                       : RequestKind::description_scan;
  if (pct(rng) < 85) {
    std::uniform_int_distribution<std::size_t> pick(0, table.size() - 1);
    r.number = table[pick(rng)].number;
  } else {
    std::uniform_int_distribution<int> any(0, ibs::vf1000_channel::kMaxParameterNumber);
    r.number = static_cast<std::uint16_t>(any(rng));
  }
  if (r.kind == RequestKind::value_transfer) {
    const ParameterInfo* p = nullptr;
    for (const ParameterInfo& q : table) {
      if (q.number == r.number) p = &q;
    }
    const int how = pct(rng);
    std::uniform_int_distribution<int> word(0, 0xFFFF);
    if (p != nullptr && how < 55) {  // in range (as the type's numbers)
      const std::int32_t lo = raw_as_number(p->type, p->min);
      const std::int32_t hi = raw_as_number(p->type, p->max);
      std::uniform_int_distribution<std::int32_t> in(lo, hi);
      r.value = static_cast<Word>(static_cast<std::uint32_t>(in(rng)) & 0xFFFFU);
    } else if (p != nullptr && how < 75) {  // at or just beyond a limit
      const int d = pct(rng) % 4;
      r.value = d == 0   ? p->min
                : d == 1 ? p->max
                : d == 2 ? static_cast<Word>(p->max + 1U)
                         : static_cast<Word>(p->min - 1U);
    } else {
      r.value = static_cast<Word>(word(rng));
    }
  }
  return r;
}

void run_random_transactions(int count, int inverter_every, unsigned seed) {
  ClientConfig cc = lockstep_client();
  cc.resync_hold = 50ms;
  Channel ch(cc, inverter_every);
  Model model(parameters());
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pct(0, 99);
  int naks = 0;
  int written = 0;
  for (int i = 0; i < count; ++i) {
    ch.power_stage_enabled = pct(rng) < 30;
    if (pct(rng) < 2) {  // the device sets its watchdog bit now and then
      ch.inverter.raise_siof(siof_mask(SiofBit::watchdog));
      model.siof |= siof_mask(SiofBit::watchdog);
    }
    const Request r = random_request(rng, parameters());
    const Outcome expected = model.expect(r, ch.power_stage_enabled);
    const std::string what = "transaction " + std::to_string(i) + " (" +
                             std::string(to_string(r.kind)) + " " + std::to_string(r.number) +
                             " value " + std::to_string(r.value) + ")";
    expect_same_outcome(ch.transact(r), expected, what);
    expect_store_matches(ch.inverter, model, what);
    if (::testing::Test::HasFailure()) return;
    naks += expected.kind == OutcomeKind::nak ? 1 : 0;
    written += expected.kind == OutcomeKind::written ? 1 : 0;
  }
  // The mix really covered both answers.
  EXPECT_GT(naks, count / 10);
  EXPECT_GT(written, count / 10);
}

TEST(ChannelSideAgainstSide, TheManualsTransactionsEndToEnd) {
  Channel ch(lockstep_client());
  EXPECT_EQ(ch.transact(value_inquiry(pnr::kFmax1)).value, 0x03E8);
  EXPECT_EQ(ch.transact(value_transfer(pnr::kFmax1, 0x01F4)).kind, OutcomeKind::written);
  EXPECT_EQ(ch.inverter.value(pnr::kFmax1), 0x01F4);
  const Outcome d = ch.transact(description_scan(pnr::kVb2));
  EXPECT_EQ(d.description, make_description(*ch.inverter.table().find(pnr::kVb2)));
  EXPECT_EQ(ch.transact(value_inquiry(40)).nak_cause, NakCause::no_parameter);
}

TEST(ChannelSideAgainstSide, RandomTransactionsInLockstepMatchTheParameterModel) {
  run_random_transactions(4000, 1, 20261121U);
}

TEST(ChannelSideAgainstSide, RandomTransactionsWithTheInverterSamplingSlowerMatchTheModel) {
  run_random_transactions(1500, 4, 4711U);
}

TEST(ChannelSideAgainstSide, PowerOnRefusalIsReportedAndTheNextTransferSucceeds) {
  Channel ch(lockstep_client(), 1, ServerStart::initialised);
  const Outcome o = ch.transact(value_transfer(pnr::kIbWd, 500));
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.nak_cause, NakCause::siof);
  EXPECT_EQ(o.siof, siof_mask(SiofBit::power_on));
  EXPECT_EQ(ch.transact(value_transfer(pnr::kIbWd, 500)).kind, OutcomeKind::written);
}

TEST(ChannelSideAgainstSide, AfterAnInverterPowerOnTheMasterReads85BeforeTransferring) {
  Channel ch(lockstep_client(), 1, ServerStart::power_on);
  Request r = value_transfer(pnr::kIbWd, 500);
  r.timeout = 1s;
  const Outcome o = ch.transact(r);  // the master saw RESET distinction 0 during initialisation
  EXPECT_EQ(o.kind, OutcomeKind::written) << describe(o);
  EXPECT_EQ(ch.master->last_siof(), siof_mask(SiofBit::power_on));
  EXPECT_EQ(ch.inverter.siof(), 0);
}

// One transaction of each shape, interrupted after every cycle by `interrupt`; the value must be
// whole (old or new, and new exactly when the inverter committed it), the outcome reported, and the
// channel usable afterwards.
struct Shape {
  const char* name;
  Request request;
  bool power_stage_enabled;
};
const Shape kShapes[] = {
    {"inquiry", value_inquiry(pnr::kFmax1), false},
    {"eeprom transfer", value_transfer(pnr::kFmax1, 0x01F4), false},
    {"ram transfer", value_transfer(pnr::kIcntl, 0x000F), true},
    {"eeprom/ram transfer", value_transfer(pnr::kFssio, 463), true},
    {"refused transfer", value_transfer(pnr::kFmax1, 0x5000), false},
    {"high-number transfer", value_transfer(pnr::kIbWd, 0x1234), false},
    {"description", description_scan(pnr::kVb2), false},
};

long cycles_of(const Shape& s, int inverter_every) {
  Channel ch(lockstep_client(), inverter_every);
  ch.power_stage_enabled = s.power_stage_enabled;
  const RequestId id = ch.master->submit(s.request).id;
  ch.run(id);
  return ch.cycles + 2L * inverter_every;  // through the inverter's return to wait mode
}

enum class Interrupt { inverter_restart, master_restart, new_master };

void interrupt_everywhere(Interrupt how, int inverter_every) {
  for (const Shape& s : kShapes) {
    const long total = cycles_of(s, inverter_every);
    ASSERT_GT(total, 4) << s.name;
    int committed_points = 0;
    int dropped_points = 0;
    for (long at = 0; at <= total; ++at) {
      const std::string what = std::string(s.name) + ", interrupted after cycle " +
                               std::to_string(at) + " of " + std::to_string(total);
      ClientConfig cc = lockstep_client();
      Channel ch(cc, inverter_every);
      ch.power_stage_enabled = s.power_stage_enabled;
      const std::uint16_t n = s.request.number;
      const Word before = *ch.inverter.value(n);
      const RequestId id = ch.master->submit(s.request).id;
      for (long i = 0; i < at; ++i) ch.step();
      const bool done_before = ch.master->poll(id).state == RequestState::done;

      switch (how) {
        case Interrupt::inverter_restart:
          ch.inverter.power_on(ch.now);
          break;
        case Interrupt::master_restart:
          ch.master->restart(ch.now);
          break;
        case Interrupt::new_master: {
          ClientConfig fresh = cc;
          fresh.start_synchronised = false;  // a restarted master knows nothing
          ch.master = std::make_unique<Client>(fresh);
          ch.m2s = Client::initial_word();
          break;
        }
      }
      // The reported outcome (the old master's, where it still exists).
      if (how != Interrupt::new_master) {
        const Outcome o = ch.run(id);
        const OutcomeKind lost = how == Interrupt::inverter_restart
                                     ? OutcomeKind::inverter_restarted
                                     : OutcomeKind::aborted;
        if (!done_before) {
          EXPECT_TRUE(o.kind == lost || o.kind == OutcomeKind::nak ||
                      (how == Interrupt::inverter_restart && o.kind != OutcomeKind::timeout))
              << what << ": " << describe(o);
        }
        if (o.kind == OutcomeKind::written) {
          EXPECT_FALSE(ch.writes.empty()) << what;
        }
      }
      // Bring the channel to rest: a further transaction goes through whatever happened.
      // (A probe sent while the restart is still unseen is itself reported as interrupted.)
      Request probe = value_inquiry(n);
      probe.timeout = 2s;
      Outcome after = ch.transact(probe);
      if (after.kind == OutcomeKind::inverter_restarted) after = ch.transact(probe);
      ASSERT_EQ(after.kind, OutcomeKind::value) << what << ": " << describe(after);

      // Never half-written: the new value exactly when the inverter committed it whole.
      const bool committed = !ch.writes.empty();
      ASSERT_LE(ch.writes.size(), 1U) << what;
      (committed ? committed_points : dropped_points) += 1;
      const ParameterInfo& p = *ch.inverter.table().find(n);
      Word expected = committed ? s.request.value : before;
      if (how == Interrupt::inverter_restart) {
        // The restart came after everything above: RAM-only values fall back to their defaults
        // (`before`, as the channel starts factory-fresh); EEPROM keeps what was committed.
        const bool ram_only = storage(p.category) == Storage::ram_control ||
                              (storage(p.category) == Storage::eeprom_ram && s.power_stage_enabled);
        if (ram_only) expected = before;
      }
      EXPECT_EQ(after.value, expected) << what;
      if (committed) {
        EXPECT_EQ(ch.writes.front().value, s.request.value) << what;
      }

      // And a transfer goes through afterwards (85-SIOF read first after an inverter restart).
      Request w = value_transfer(pnr::kRstop, 0x0010);
      w.timeout = 2s;
      ch.power_stage_enabled = false;
      const Outcome wo = ch.transact(w);
      EXPECT_TRUE(wo.kind == OutcomeKind::written ||
                  (how != Interrupt::inverter_restart && wo.kind == OutcomeKind::nak))
          << what << ": " << describe(wo);
      if (::testing::Test::HasFailure()) return;
    }
    // The interruption points fell on both sides of the commit.
    const bool can_commit =
        s.request.kind == RequestKind::value_transfer && s.request.value != 0x5000;
    EXPECT_GT(dropped_points, 0) << s.name;
    if (can_commit) {
      EXPECT_GT(committed_points, 0) << s.name;
    } else {
      EXPECT_EQ(committed_points, 0) << s.name;
    }
  }
}

TEST(ChannelInterrupted, ByAnInverterRestartAtEveryStep) {
  interrupt_everywhere(Interrupt::inverter_restart, 1);
}

TEST(ChannelInterrupted, ByAnInverterRestartAtEveryStepWithSlowerSampling) {
  interrupt_everywhere(Interrupt::inverter_restart, 3);
}

TEST(ChannelInterrupted, ByAMasterRestartAtEveryStep) {
  interrupt_everywhere(Interrupt::master_restart, 1);
}

TEST(ChannelInterrupted, ByAMasterRestartAtEveryStepWithSlowerSampling) {
  interrupt_everywhere(Interrupt::master_restart, 3);
}

TEST(ChannelInterrupted, ByANewMasterInstanceAtEveryStepWithSlowerSampling) {
  interrupt_everywhere(Interrupt::new_master, 3);
}

// Why resync_hold exists: without it, a freshly started master can take the stale wait-mode look of
// an inverter waiting for DAT2 (8000) as rest, and its new start word completes the old transfer
// with a byte that was never meant as a value.
TEST(ChannelInterrupted, WithoutResyncHoldANewMasterCanCompleteAStaleTransfer) {
  ClientConfig cc = lockstep_client();
  Channel ch(cc, 3);
  const RequestId id = ch.master->submit(value_transfer(pnr::kIbWd, 0x0100)).id;
  // Run until the inverter has taken DAT1 and waits for DAT2.
  for (int i = 0; i < 1000 && ch.inverter.state() != ServerState::transfer_low; ++i) ch.step();
  ASSERT_EQ(ch.inverter.state(), ServerState::transfer_low);
  (void)id;
  ClientConfig careless = cc;
  careless.start_synchronised = false;
  careless.resync_hold = 0ms;
  ch.master = std::make_unique<Client>(careless);
  ch.m2s = Client::initial_word();
  // Place the master's restart right after an inverter sample, as the bus can.
  while (ch.cycles % ch.inverter_every != 0) ch.step();
  const RequestId next = ch.master->submit(value_transfer(pnr::kIbWd, 0x0200)).id;
  ch.run(next);
  ASSERT_FALSE(ch.writes.empty());
  // The committed value is DAT1 01H of the old transfer with the new start word's 8AH (906's low
  // byte): a value nobody sent. With the default resync_hold this cannot happen (tests above).
  EXPECT_EQ(ch.writes.front().value, 0x018A);
}

}  // namespace
