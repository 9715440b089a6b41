// Client against server over 1, 2 and 4 words: thousands of random requests under random
// faults (corrupted, lost, repeated cycles) and restarts of either side. An oracle keeps, per
// parameter, the set of values the servo may hold given everything the master knows; every
// result must be consistent with it. A wrong value, a confirmation for another request, a
// duplicated execution or a second result for one request fails the test.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "pcp_harness.hpp"
#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"

namespace ibs::pcp {
namespace {

using namespace ibs::devices::mc6000;

using test::Bus;
using test::FaultRates;

enum class Latch { clear, set, unknown };

struct Oracle {
  explicit Oracle(const ParameterStore& store) {
    for (const ParameterInfo& p : store.table()) {
      ram[p.number] = {ParameterStore::default_raw(p)};
      if (p.category == Category::eeprom) eeprom[p.number] = {ParameterStore::default_raw(p)};
    }
  }

  std::map<std::uint16_t, std::set<std::uint32_t>> ram;
  std::map<std::uint16_t, std::set<std::uint32_t>> eeprom;
  // EEPROM saves that are certain once the time has come: number -> (value, time).
  std::map<std::uint16_t, std::pair<std::uint32_t, Time>> pending_save;
  Latch latch = Latch::clear;
  Time eeprom_maybe_busy_until{};

  void settle_saves(Time now) {
    for (auto it = pending_save.begin(); it != pending_save.end();) {
      if (it->second.second <= now) {
        eeprom[it->first] = {it->second.first};
        it = pending_save.erase(it);
      } else {
        ++it;
      }
    }
  }
  void servo_restart(const ParameterStore& store, Time now) {
    settle_saves(now);
    for (const ParameterInfo& p : store.table()) {
      ram[p.number] = p.category == Category::eeprom
                          ? eeprom[p.number]
                          : std::set<std::uint32_t>{ParameterStore::default_raw(p)};
    }
    pending_save.clear();
    latch = Latch::set;  // power-on bit
    eeprom_maybe_busy_until = Time{};
  }
  void latch_maybe() {
    if (latch == Latch::clear) latch = Latch::unknown;
  }
};

struct Op {
  enum class Kind { read, write, get_ov, identify, status } kind = Kind::read;
  std::uint16_t number = 0;
  std::vector<std::uint8_t> data;  // write
};

struct Stats {
  int ops = 0;
  int ok = 0;
  int negative = 0;
  int not_now = 0;
  int unknown = 0;
  int restarts_servo = 0;
  int restarts_master = 0;
  int across_restart = 0;  // results completed across a servo restart
};

class Campaign {
 public:
  Campaign(int words, std::uint32_t seed, Duration cycle, FaultRates faults, double restart_rate,
           test::Interface interface = test::Interface::at_sample)
      : words_(words),
        rng_(seed),
        client_(test::client_config(words)),
        parameters_(StartMode::power_on),
        server_([&] {
          ServerConfig c = ibs::devices::mc6000::server_config(1);
          c.channel_words = words;
          c.start = StartMode::power_on;
          return c;
        }(), parameters_.served),
        bus_(client_, server_, cycle, 1ms, interface),
        oracle_(parameters_.drive.parameters().store()),
        restart_rate_(restart_rate) {
    bus_.set_faults(faults, seed * 7919U + 1U);
    oracle_.latch = Latch::set;
    parameters_.drive.parameters().set_reading(kIbsta, 0x0231);
    oracle_.ram[kIbsta] = {0x0231};
  }

  void run(int ops) {
    while (stats_.ops < ops && !::testing::Test::HasFatalFailure()) one();
  }
  [[nodiscard]] const Stats& stats() const { return stats_; }
  [[nodiscard]] std::string summary() const {
    // Built with a stream: GCC 12's -Wrestrict misfires on long `literal + std::string` chains at
    // -O2.
    const auto& f = bus_.fault_counts();
    std::ostringstream o;
    o << "width " << words_ << ": " << stats_.ops << " requests, " << stats_.ok << " writes ok, "
      << stats_.negative << " refused statically, " << stats_.not_now << " not now, "
      << stats_.unknown << " unknown, " << stats_.across_restart
      << " across a restart; servo/master restarts " << stats_.restarts_servo << "/"
      << stats_.restarts_master << "; faults corrupted/lost/repeated " << f.corrupted << "/"
      << f.lost << "/" << f.repeated << "; stale frames seen "
      << client_.link().stats().frames_repeated + server_.link().stats().frames_repeated;
    return o.str();
  }
  [[nodiscard]] const Client& client() const { return client_; }
  [[nodiscard]] const Server& server() const { return server_; }
  [[nodiscard]] const Bus& bus() const { return bus_; }
  [[nodiscard]] int protocol_errors() const { return protocol_errors_; }
  [[nodiscard]] std::uint32_t dropped() const {
    return dropped_ + server_.link().stats().messages_dropped +
           client_.link().stats().messages_dropped;
  }

 private:
  template <class T>
  T pick(std::initializer_list<T> xs) {
    std::uniform_int_distribution<std::size_t> d(0, xs.size() - 1);
    return *(xs.begin() + static_cast<std::ptrdiff_t>(d(rng_)));
  }
  double uniform() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }
  std::uint32_t bits(unsigned n) {
    return static_cast<std::uint32_t>(rng_() & ((n >= 32U ? 0U : (1U << n)) - 1U));
  }

  Op random_op() {
    Op op;
    const double x = uniform();
    const std::uint16_t number = pick<std::uint16_t>(
        {83, 416, 428, 108, 407, 84, 409, 82, 406, 81, 408, 91, 85, 999, 500, 85, 83, 84});
    if (x < 0.40) {
      op.kind = Op::Kind::read;
      op.number = number;
    } else if (x < 0.90) {
      op.kind = Op::Kind::write;
      op.number = number;
      const ParameterInfo* p = parameters_.drive.parameters().store().info(number);
      std::size_t len = p ? size_of(p->type) : 2;
      if (uniform() < 0.05) len = len == 2 ? 4 : 2;  // a wrong length now and then
      std::uint32_t v = bits(static_cast<unsigned>(8 * len));
      if (p && uniform() < 0.7) {  // mostly in range
        const auto lo = p->min;
        const auto hi = p->max;
        v = ParameterStore::to_raw(*p, std::uniform_int_distribution<std::int64_t>(lo, hi)(rng_));
      }
      op.data.resize(len);
      for (std::size_t i = 0; i < len; ++i)
        op.data[i] = static_cast<std::uint8_t>((v >> (8U * (len - 1U - i))) & 0xFFU);
    } else if (x < 0.95) {
      op.kind = Op::Kind::get_ov;
      op.number = number;
    } else {
      op.kind = uniform() < 0.5 ? Op::Kind::identify : Op::Kind::status;
    }
    return op;
  }

  SubmitStatus submit(const Op& op) {
    const Time t = bus_.now();
    const ParameterRef p = ParameterRef::number(op.number);
    switch (op.kind) {
      case Op::Kind::read:
        return client_.read(t, p);
      case Op::Kind::write:
        return client_.write_bytes(t, p, op.data);
      case Op::Kind::get_ov:
        return client_.get_ov(t, p);
      case Op::Kind::identify:
        return client_.identify(t);
      case Op::Kind::status:
        return client_.status(t);
    }
    return SubmitStatus::invalid_argument;
  }

  // Runs the bus until the client's result, injecting at most one restart on the way.
  std::optional<Result> await(bool& master_restarted) {
    const int restart_at = uniform() < restart_rate_ ? static_cast<int>(rng_() % 80U) : -1;
    const bool servo = uniform() < 0.5;
    master_restarted = false;
    for (int cycle = 0; cycle < 20000; ++cycle) {
      if (cycle == restart_at) {
        if (servo) {
          // A confirmation already complete on the wire still arrives: it tells what the servo
          // did before the restart, so it is judged against the state before it.
          restart_in_op_ = true;
          ram_before_ = oracle_.ram;
          parameters_.drive.parameters().power_on(bus_.now());
          server_.power_on(bus_.now());
          parameters_.drive.parameters().set_reading(kIbsta, 0x0231);
          oracle_.servo_restart(parameters_.drive.parameters().store(), bus_.now());
          oracle_.ram[kIbsta] = {0x0231};  // the device model's status word, set again
          ++stats_.restarts_servo;
          note("servo restart");
        } else {
          client_ = Client(test::client_config(words_));
          ++stats_.restarts_master;
          master_restarted = true;
          return std::nullopt;  // the old request's result dies with the old master
        }
      }
      bus_.cycle();
      if (auto r = client_.take_result()) return r;
    }
    ADD_FAILURE() << "no result within 20000 cycles";
    return std::nullopt;
  }

  void initiate() {
    ASSERT_EQ(client_.initiate(bus_.now()), SubmitStatus::accepted);
    bool restarted = false;
    const auto r = await(restarted);
    note(r ? std::string(to_string(r->kind)).insert(0, "initiate -> ")
           : std::string("initiate -> none"));
    if (r) {
      ASSERT_EQ(r->service, ServiceCode::initiate);
      ASSERT_TRUE(r->ok() || r->kind == ResultKind::link_reset || r->kind == ResultKind::timeout ||
                  r->kind == ResultKind::aborted)
          << to_string(r->kind);
    }
  }

  static bool unknown_outcome(ResultKind k) {
    return k == ResultKind::link_reset || k == ResultKind::timeout || k == ResultKind::aborted;
  }

  void one() {
    ASSERT_FALSE(client_.take_result().has_value()) << "a result nobody asked for";
    if (!client_.associated()) {
      initiate();
      return;
    }
    // After a refused write the master reads 85-SERR, as the LUSTBUS manual (6, 9.2) tells it to.
    Op op = random_op();
    if (oracle_.latch != Latch::clear && uniform() < 0.8) op = Op{Op::Kind::read, kSerr, {}};
    ASSERT_EQ(submit(op), SubmitStatus::accepted);
    ++stats_.ops;
    const Time submitted = bus_.now();
    bool master_restarted = false;
    restart_in_op_ = false;
    const std::optional<Result> r = await(master_restarted);
    {
      std::ostringstream o;
      o << "op " << static_cast<int>(op.kind) << " #" << op.number << " -> ";
      if (r) {
        o << to_string(r->kind) << " " << to_string(r->error);
      } else {
        o << "master restart";
      }
      o << " latch " << static_cast<int>(oracle_.latch);
      note(o.str());
    }
    oracle_.settle_saves(bus_.now());
    const ParameterInfo* p = parameters_.drive.parameters().store().info(op.number);
    if (!r) {
      ASSERT_TRUE(master_restarted);
      unknown(op, p, submitted);
      return;
    }
    ASSERT_EQ(r->index, op.kind == Op::Kind::identify || op.kind == Op::Kind::status
                            ? 0
                            : index_of(op.number));
    if (r->kind == ResultKind::protocol_error) ++protocol_errors_;
    if (unknown_outcome(r->kind)) {
      ASSERT_GT(stats_.restarts_servo + stats_.restarts_master, 0)
          << "without restarts every request is confirmed: " << to_string(r->kind);
      unknown(op, p, submitted);
      return;
    }
    ASSERT_TRUE(r->kind == ResultKind::ok || r->kind == ResultKind::negative) << to_string(r->kind);
    if (restart_in_op_) {
      judge_across_restart(op, p, *r, submitted);
      return;
    }
    switch (op.kind) {
      case Op::Kind::read:
        check_read(op, p, *r);
        break;
      case Op::Kind::write:
        check_write(op, p, *r, submitted);
        break;
      case Op::Kind::get_ov:
        if (p == nullptr) {
          ASSERT_EQ(r->error, errors::kObjectDoesNotExist);
        } else {
          ASSERT_TRUE(r->ok());
          ASSERT_EQ(r->description, describe(*p));
        }
        break;
      case Op::Kind::identify:
        ASSERT_TRUE(r->ok());
        ASSERT_EQ(r->identity, server_.config().identity);
        break;
      case Op::Kind::status:
        ASSERT_TRUE(r->ok());
        if (oracle_.latch == Latch::clear) {
          ASSERT_EQ(r->status.local_detail, 0);
        }
        if (oracle_.latch == Latch::set) {
          ASSERT_NE(r->status.local_detail, 0);
        }
        break;
    }
  }

  void unknown(const Op& op, const ParameterInfo* p, Time submitted) {
    ++stats_.unknown;
    if (op.kind == Op::Kind::read && op.number == kSerr) {
      if (oracle_.latch == Latch::set) oracle_.latch = Latch::unknown;
    }
    if (op.kind != Op::Kind::write) return;
    oracle_.latch_maybe();
    const auto v = p ? decode(p->type, op.data) : std::nullopt;
    if (p == nullptr || !v || !p->writable()) return;
    oracle_.ram[p->number].insert(v->raw);
    if (p->category == Category::eeprom) {
      oracle_.eeprom[p->number].insert(v->raw);
      oracle_.pending_save.erase(p->number);
      oracle_.eeprom_maybe_busy_until =
          bus_.now() + 15ms * static_cast<Duration::rep>(size_of(p->type));
    }
    (void)submitted;
  }

  static std::string list(const std::set<std::uint32_t>& s) {
    std::ostringstream o;
    for (const std::uint32_t v : s) o << " " << v;
    return o.str();
  }

  std::string history() const {
    std::ostringstream o;
    for (const auto& h : log_) o << "\n  " << h;
    return o.str();
  }
  void note(const std::string& s) {
    std::ostringstream o;
    o << to_ms(bus_.now()) << " " << s;
    log_.push_back(o.str());
    if (log_.size() > 12) log_.erase(log_.begin());
  }

  void judge_across_restart(const Op& op, const ParameterInfo* p, const Result& r, Time submitted) {
    ++stats_.across_restart;
    if (op.kind == Op::Kind::read && p != nullptr && op.number != kSerr && r.ok()) {
      const auto v = decode(p->type, r.data.view());
      ASSERT_TRUE(v.has_value());
      ASSERT_EQ(ram_before_[op.number].count(v->raw), 1U)
          << "read " << op.number << " across a restart";
      return;
    }
    if (op.kind == Op::Kind::read && p == nullptr) {
      ASSERT_EQ(r.error, errors::kObjectDoesNotExist);
      return;
    }
    if (op.kind == Op::Kind::write) unknown(op, p, submitted);
  }

  void check_read(const Op& op, const ParameterInfo* p, const Result& r) {
    if (p == nullptr) {
      ASSERT_EQ(r.error, errors::kObjectDoesNotExist);
      return;
    }
    ASSERT_TRUE(r.ok()) << to_string(r.error);
    const auto v = decode(p->type, r.data.view());
    ASSERT_TRUE(v.has_value()) << "length " << r.data.size << " for " << op.number;
    if (op.number == kSerr) {
      if (oracle_.latch == Latch::clear) {
        ASSERT_EQ(v->raw, 0U) << "SERR should be clear";
      }
      if (oracle_.latch == Latch::set) {
        ASSERT_NE(v->raw, 0U) << "SERR should be set";
      }
      oracle_.latch = Latch::clear;
      return;
    }
    auto& possible = oracle_.ram[op.number];
    ASSERT_TRUE(possible.count(v->raw) == 1)
        << "parameter " << op.number << " read " << v->raw
        << ", which the servo cannot hold; possible:" << list(possible) << " at "
        << to_ms(bus_.now()) << " ms";
    possible = {v->raw};
  }

  void check_write(const Op& op, const ParameterInfo* p, const Result& r, Time submitted) {
    std::optional<PcpError> static_error;
    const auto v = p ? decode(p->type, op.data) : std::nullopt;
    if (p == nullptr) {
      static_error = errors::kObjectDoesNotExist;
    } else if (!p->writable()) {
      static_error = errors::kNoAccess;
    } else if (!v) {
      static_error = errors::kDataLength;
    } else if (compare(p->type, v->raw, ParameterStore::to_raw(*p, p->max)) > 0) {
      static_error = errors::kValueTooHigh;
    } else if (compare(p->type, v->raw, ParameterStore::to_raw(*p, p->min)) < 0) {
      static_error = errors::kValueTooLow;
    } else if (op.number == ibs::devices::mc6000::kParamSbaud &&
               !ibs::drive::is_baud_step(v->raw, ibs::devices::mc6000::kHighestBaud)) {
      static_error = errors::kValueTooHigh;  // LUSTBUS manual 4: the rates in steps (LB-E18)
    }
    if (static_error) {
      ASSERT_EQ(r.kind, ResultKind::negative) << "write " << op.number;
      // LUSTBUS manual 9.2 (docs/errata.md MC-D3): while 85-SERR holds a bit every write is refused
      // before it is looked at, and enters nothing.
      if (oracle_.latch != Latch::clear && r.error == errors::kNotExecutableNow) {
        ++stats_.negative;
        oracle_.latch = Latch::set;
        return;
      }
      ASSERT_NE(oracle_.latch, Latch::set) << "write " << op.number << " looked at despite 85-SERR";
      ASSERT_EQ(r.error, *static_error) << "write " << op.number;
      ++stats_.negative;
      oracle_.latch = Latch::set;
      return;
    }
    const bool eeprom = p->category == Category::eeprom;
    const bool may_be_busy = eeprom && submitted < oracle_.eeprom_maybe_busy_until;
    if (r.kind == ResultKind::negative) {
      ASSERT_EQ(r.error, errors::kNotExecutableNow) << "write " << op.number;
      ASSERT_TRUE(oracle_.latch != Latch::clear || may_be_busy)
          << "write " << op.number << " refused although SERR is clear and the EEPROM idle";
      ++stats_.not_now;
      oracle_.latch = Latch::set;
      return;
    }
    ASSERT_NE(oracle_.latch, Latch::set)
        << "write " << op.number << " accepted although SERR is set" << history();
    ++stats_.ok;
    oracle_.ram[p->number] = {v->raw};
    if (eeprom) {
      oracle_.eeprom[p->number].insert(v->raw);
      const Time done = r.completed_at + 15ms * static_cast<Duration::rep>(size_of(p->type));
      oracle_.pending_save[p->number] = {v->raw, done};
      oracle_.eeprom_maybe_busy_until = done;
    }
  }

  int words_;
  std::mt19937 rng_;
  Client client_;
  test::Served parameters_;
  Server server_;
  Bus bus_;
  Oracle oracle_;
  double restart_rate_;
  Stats stats_;
  int protocol_errors_ = 0;
  std::uint32_t dropped_ = 0;
  std::vector<std::string> log_;
  bool restart_in_op_ = false;
  std::map<std::uint16_t, std::set<std::uint32_t>> ram_before_;
};

constexpr FaultRates kFaults{0.03, 0.03, 0.03, 0.03, 0.03};

class Faults : public ::testing::TestWithParam<int> {};

TEST_P(Faults, RandomRequestsUnderLostRepeatedAndCorruptedCycles) {
  const int words = GetParam();
  // Seed 11 with the servo's link in its 1 ms samples, seed 12 with it on the INTERBUS CPU at the
  // bus cycle (the simulator's timing): the guarantees hold at either rate.
  for (const std::uint32_t seed : {11U, 12U}) {
    Campaign c(words, seed + static_cast<std::uint32_t>(words) * 100U, 567us, kFaults, 0.0,
               seed == 12U ? test::Interface::at_cycle : test::Interface::at_sample);
    c.run(1500);
    RecordProperty("campaign_" + std::to_string(seed), c.summary());
    SCOPED_TRACE("width " + std::to_string(words) + " seed " + std::to_string(seed));
    EXPECT_EQ(c.protocol_errors(), 0);
    EXPECT_EQ(c.dropped(), 0U) << "a stale cycle never makes a bad message";
    EXPECT_EQ(c.stats().unknown, 0);
    EXPECT_GT(c.stats().ok, 200);
    EXPECT_GT(c.stats().negative, 100);
    EXPECT_GT(c.bus().fault_counts().corrupted, 100U);
    EXPECT_GT(c.bus().fault_counts().lost, 100U);
    EXPECT_GT(c.bus().fault_counts().repeated, 100U);
    EXPECT_GT(c.client().link().stats().frames_repeated + c.server().link().stats().frames_repeated,
              1000U);
  }
}

TEST_P(Faults, RandomRequestsInLockStepWithoutFaults) {
  const int words = GetParam();
  Campaign c(words, 77U + static_cast<std::uint32_t>(words), 1ms, FaultRates{}, 0.0);
  c.run(600);
  RecordProperty("campaign", c.summary());
  EXPECT_EQ(c.protocol_errors(), 0);
  EXPECT_EQ(c.dropped(), 0U);
  EXPECT_EQ(c.stats().unknown, 0);
}

TEST_P(Faults, RandomRequestsWithServoAndMasterRestarts) {
  const int words = GetParam();
  Campaign c(words, 31U + static_cast<std::uint32_t>(words), 567us, kFaults, 0.08,
             test::Interface::at_cycle);
  c.run(2000);
  RecordProperty("campaign", c.summary());
  EXPECT_EQ(c.protocol_errors(), 0);
  EXPECT_EQ(c.dropped(), 0U);
  EXPECT_GT(c.stats().restarts_servo, 10);
  EXPECT_GT(c.stats().restarts_master, 10);
  EXPECT_GT(c.stats().unknown, 10);
  EXPECT_GT(c.stats().ok, 200);
}

INSTANTIATE_TEST_SUITE_P(Widths, Faults, ::testing::Values(1, 2, 4),
                         [](const ::testing::TestParamInfo<int>& i) {
                           return std::to_string(i.param) + "Words";
                         });

}  // namespace
}  // namespace ibs::pcp
