#include "ibs/sim/campaign.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <random>
#include <unordered_map>

#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/service.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/devices/vf1000/device.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/pcp/data_types.hpp"
#include "ibs/pcp/parameter_store.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::sim {

namespace {

using devices::ParamKind;
using devices::ParamOp;
using drivecom::State;

bool contains(const std::vector<std::int64_t>& set, std::int64_t v) {
  return std::find(set.begin(), set.end(), v) != set.end();
}
void add(std::vector<std::int64_t>& set, std::int64_t v) {
  if (!contains(set, v)) set.push_back(v);
}
void add_all(std::vector<std::int64_t>& set, const std::vector<std::int64_t>& from) {
  for (const auto v : from) add(set, v);
}
std::string show(const std::vector<std::int64_t>& set) {
  std::string s = "{";
  for (std::size_t i = 0; i < set.size(); ++i) s += (i ? ", " : "") + std::to_string(set[i]);
  return s + "}";
}
// "8.2 ms", "550 ms", "100 us", "0 s"
std::string fmt_time(Duration d) {
  char b[32];
  if (d.count() == 0) return "0 s";
  if (d.count() % 1000000 == 0 || d >= 1ms) {
    std::snprintf(b, sizeof b, "%g ms", to_ms(d));
  } else {
    std::snprintf(b, sizeof b, "%g us", static_cast<double>(d.count()) / 1e3);
  }
  return b;
}
std::string ms(Duration d) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f ms", to_ms(d));
  return b;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The oracle.

std::size_t CampaignChecker::add_device(CheckerDeviceSpec spec) {
  Dev d;
  for (const auto& p : spec.params) {
    Cell c;
    c.spec = p;
    c.ram = {p.initial};
    if (p.eeprom) c.eeprom = {p.initial};
    d.cells.push_back(std::move(c));
  }
  d.spec = std::move(spec);
  devices_.push_back(std::move(d));
  return devices_.size() - 1;
}

CampaignChecker::Cell* CampaignChecker::cell(Dev& d, std::uint16_t number) {
  for (auto& c : d.cells) {
    if (c.spec.number == number) return &c;
  }
  return nullptr;
}

void CampaignChecker::violation(const Dev& d, Time at, std::string check, std::string what) {
  ++violation_count_;
  if (violations_.size() < max_violations_kept) violations_.push_back({at, d.spec.name, std::move(check), std::move(what)});
}

void CampaignChecker::submitted(std::size_t dev, ParamOp op, std::uint16_t number, std::int64_t value, Time now,
                                Duration limit) {
  Dev& d = devices_[dev];
  Outstanding o;
  o.op = op;
  o.number = number;
  o.value = value;
  o.submitted = now;
  o.deadline = now + limit;
  if (op == ParamOp::read) {
    if (Cell* c = cell(d, number)) o.allowed = c->ram;
  }
  d.out = std::move(o);
}

void CampaignChecker::factory_reset(Dev& d, bool certain) {
  for (auto& c : d.cells) {
    if (c.spec.role == ParamRole::device_owned || c.spec.role == ParamRole::command) continue;
    if (certain) {
      c.ram = {c.spec.factory};
      if (c.spec.eeprom) c.eeprom = {c.spec.factory};
      c.settle_at.reset();
    } else {
      add(c.ram, c.spec.factory);
      if (c.spec.eeprom) add(c.eeprom, c.spec.factory);
      if (!c.settle_ram) c.settle_at.reset();  // a pending save may have been dropped by the reset
    }
  }
}

void CampaignChecker::settle(Dev& d, Time now) {
  for (auto& c : d.cells) {
    if (!c.settle_at || *c.settle_at > now) continue;
    if (c.settle_ram) {
      c.ram = {c.settle};
      if (c.spec.role == ParamRole::sload) d.download_open = false;
    } else {
      c.eeprom = {c.settle};
    }
    c.settle_at.reset();
  }
}

void CampaignChecker::ended(std::size_t dev, ParamKind kind, std::int64_t value, Time now) {
  Dev& d = devices_[dev];
  if (!d.out) return;
  const Outstanding o = std::move(*d.out);
  d.out.reset();
  settle(d, now);
  ++counts_.outcome_checks;
  ++counts_.deadline_checks;
  const std::string what = std::string(devices::to_string(o.op)) + " of " + std::to_string(o.number) +
                           (o.op == ParamOp::write ? " = " + std::to_string(o.value) : "");
  if (now > o.deadline && !o.overdue_reported) {
    violation(d, now, "overdue", what + " ended " + ms(now - o.submitted) + " after submission, limit " +
                                     ms(o.deadline - o.submitted));
  }
  bool documented = false;
  switch (o.op) {
    case ParamOp::read:
      documented = kind == ParamKind::value || kind == ParamKind::nak || kind == ParamKind::timeout ||
                   kind == ParamKind::aborted;
      break;
    case ParamOp::write:
      documented = kind == ParamKind::written || kind == ParamKind::nak || kind == ParamKind::timeout ||
                   kind == ParamKind::aborted || kind == ParamKind::refused;
      break;
    case ParamOp::describe:
      documented = kind == ParamKind::description || kind == ParamKind::nak || kind == ParamKind::timeout ||
                   kind == ParamKind::aborted;
      break;
  }
  if (!documented) {
    violation(d, now, "outcome", what + " ended '" + std::string(devices::to_string(kind)) + "', not an outcome of a " +
                                     std::string(devices::to_string(o.op)));
    return;
  }
  Cell* c = cell(d, o.number);
  if (c == nullptr && (kind == ParamKind::value || kind == ParamKind::written || kind == ParamKind::description)) {
    violation(d, now, "outcome", what + " ended '" + std::string(devices::to_string(kind)) +
                                     "' although the device has no such parameter");
    return;
  }
  if (o.op == ParamOp::read && kind == ParamKind::value && c != nullptr && c->spec.role != ParamRole::device_owned) {
    ++counts_.read_checks;
    if (!contains(o.allowed, value)) {
      violation(d, now, "read", what + " returned " + std::to_string(value) + "; the model allows " + show(o.allowed));
    }
  }
  if (o.op != ParamOp::write || c == nullptr) return;
  const bool out_of_range = o.value < c->spec.min || o.value > c->spec.max;
  if (kind == ParamKind::written && (out_of_range || c->spec.role == ParamRole::device_owned)) {
    violation(d, now, "outcome", what + " was confirmed although " +
                                     (out_of_range ? "the value is outside " + std::to_string(c->spec.min) + ".." +
                                                         std::to_string(c->spec.max)
                                                   : std::string("the parameter is not the master's to write")));
    return;
  }
  if (c->spec.role == ParamRole::device_owned) return;
  const bool landed = kind == ParamKind::written;
  const bool maybe = kind == ParamKind::timeout || kind == ParamKind::aborted;
  if (!landed && !maybe) return;  // nak, refused: nothing changed
  const bool certain = landed && !o.disturbed;
  switch (c->spec.role) {
    case ParamRole::command:
      if (o.value == 1) factory_reset(d, certain);
      break;
    case ParamRole::sload:
      if (o.value == -1) {
        if (certain) {
          c->ram = {-1};
          c->settle_at.reset();
          d.download_open = true;
          d.lock_may_end.reset();
        } else {
          add(c->ram, -1);
        }
      } else if (o.value == -2) {
        if (certain) {
          // The dataset is checked (SLOAD -1), then SLOAD reads 0 (docs/errata.md MC-D2).
          c->ram = {-1, 0};
          c->settle_at = now + d.spec.download_check + 2 * d.spec.period + 2 * d.spec.jitter;
          c->settle = 0;
          c->settle_ram = true;
          d.lock_may_end = o.submitted + d.spec.download_check;
        } else {
          add(c->ram, -1);
          add(c->ram, 0);
          d.download_open = false;  // not known any more
        }
      }
      break;
    case ParamRole::normal:
      if (d.download_open) {
        // Seed 000 11.4 (MC-D2): during a download only the CardWriteable parameters take the
        // value, into RAM; their EEPROM copy follows when the dataset is accepted.
        if (!c->spec.card_writeable) break;
        if (certain) {
          c->ram = {o.value};
        } else {
          add(c->ram, o.value);
        }
        if (c->spec.eeprom) add(c->eeprom, o.value);
        c->settle_at.reset();
        break;
      }
      if (certain) {
        c->ram = {o.value};
        c->settle_at.reset();
        if (c->spec.eeprom) {
          add(c->eeprom, o.value);
          if (!c->spec.eeprom_ram) {
            c->settle_at = now + c->spec.eeprom_save;
            c->settle = o.value;
            c->settle_ram = false;
            settle(d, now);
          }
        }
      } else {
        add(c->ram, o.value);
        if (c->spec.eeprom) add(c->eeprom, o.value);
        c->settle_at.reset();  // the earlier value's save no longer decides the EEPROM
      }
      break;
    case ParamRole::device_owned: break;
  }
}

void CampaignChecker::check_overdue(Time now) {
  for (auto& d : devices_) {
    if (!d.out || d.out->overdue_reported || now <= d.out->deadline) continue;
    d.out->overdue_reported = true;
    violation(d, now, "overdue", std::string(devices::to_string(d.out->op)) + " of " + std::to_string(d.out->number) +
                                     " still pending " + ms(now - d.out->submitted) + " after submission, limit " +
                                     ms(d.out->deadline - d.out->submitted));
  }
}

void CampaignChecker::check_store(std::size_t dev, Time now, const std::vector<StoreEntry>& store) {
  Dev& d = devices_[dev];
  settle(d, now);
  for (const StoreEntry& e : store) {
    Cell* c = cell(d, e.number);
    if (c == nullptr || c->spec.role == ParamRole::device_owned) continue;
    ++counts_.store_checks;
    const std::vector<std::int64_t> ram = allowed_now(d, *c, false);
    const std::vector<std::int64_t> eeprom = c->spec.eeprom ? allowed_now(d, *c, true) : std::vector<std::int64_t>{};
    if (!contains(ram, e.ram) && c->reported_ram != e.ram) {
      c->reported_ram = e.ram;  // once per wrong value
      violation(d, now, "store", "parameter " + std::to_string(e.number) + " holds " + std::to_string(e.ram) +
                                     " in RAM; the model allows " + show(ram));
    }
    if (c->spec.eeprom && e.eeprom && !contains(eeprom, *e.eeprom) && c->reported_eeprom != *e.eeprom) {
      c->reported_eeprom = *e.eeprom;
      violation(d, now, "store", "parameter " + std::to_string(e.number) + " holds " + std::to_string(*e.eeprom) +
                                     " in EEPROM; the model allows " + show(eeprom));
    }
  }
}

std::vector<std::int64_t> CampaignChecker::allowed_now(const Dev& d, const Cell& c, bool eeprom) const {
  // The model's values plus what the outstanding write (if any) may have done already.
  std::vector<std::int64_t> v = eeprom ? c.eeprom : c.ram;
  if (!d.out || d.out->op != ParamOp::write) return v;
  const Outstanding& w = *d.out;
  const Cell* wc = nullptr;
  for (const auto& x : d.cells) {
    if (x.spec.number == w.number) wc = &x;
  }
  if (wc == nullptr || w.value < wc->spec.min || w.value > wc->spec.max) return v;
  if (wc->spec.role == ParamRole::command && w.value == 1 && c.spec.role != ParamRole::command &&
      c.spec.role != ParamRole::device_owned) {
    add(v, c.spec.factory);
  }
  if (w.number == c.spec.number) {
    if (c.spec.role == ParamRole::normal) {
      add(v, w.value);
    } else if (c.spec.role == ParamRole::sload && w.value < 0 && !eeprom) {
      add(v, -1);
      if (w.value == -2) add(v, 0);
    }
  }
  return v;
}

void CampaignChecker::set_value(std::size_t dev, std::uint16_t number, std::int64_t value) {
  Dev& d = devices_[dev];
  if (Cell* c = cell(d, number)) {
    c->ram = {value};
    if (c->spec.eeprom) c->eeprom = {value};
    c->settle_at.reset();
  }
}

void CampaignChecker::withdraw(Dev& d, Time t, const std::string& why, bool via_master) {
  d.permitted = false;
  if (via_master) {
    if (!d.written_after && !d.word_out) d.written_after = t;
    if (d.leave_why.empty() || !d.leave_by) d.leave_why = why;
    return;
  }
  if (!d.leave_by || t < *d.leave_by) {
    d.leave_by = t;
    d.leave_why = why;
  }
}

void CampaignChecker::software_reset(std::size_t dev, Time now) {
  // The VF1000's RESET FAULT (seed 001, 5.2.1): it boots, its store as after a power cycle, and
  // its bus watchdog as after one too: monitoring again from the first valid cycle after the
  // self-test. The master asked for it, so its request is not touched.
  Dev& d = devices_[dev];
  reboot_store(d, now);
  d.armed = false;
  d.tripped = false;
  d.last_fed.reset();
  d.fed_before_slice.reset();
}

void CampaignChecker::power_cycle(std::size_t dev, Time now, std::optional<State> state_then) {
  software_reset(dev, now);  // the drive boots the same way; what differs is the master's request
  Dev& d = devices_[dev];
  // A drive switched off and on while it still initialises (NOT READY) looks the same to the
  // master before and after: a request made then covers it (as a fault joins a latched one).
  if (state_then && *state_then == State::not_ready) return;
  withdraw(d, now, "power cycle", false);
}

void CampaignChecker::reboot_store(Dev& d, Time now) {
  settle(d, now);
  for (auto& c : d.cells) {
    switch (c.spec.role) {
      case ParamRole::device_owned: break;
      case ParamRole::command:
      case ParamRole::sload: c.ram = {c.spec.factory}; c.settle_at.reset(); break;
      case ParamRole::normal:
        c.ram = c.spec.eeprom ? c.eeprom : std::vector<std::int64_t>{c.spec.factory};
        c.settle_at.reset();  // a save not yet done may be lost: the EEPROM set keeps both
        break;
    }
  }
  d.download_open = false;
  if (d.out) {
    d.out->disturbed = true;
    if (d.out->op == ParamOp::read) {
      if (Cell* c = cell(d, d.out->number)) add_all(d.out->allowed, c->ram);
    }
  }
}

void CampaignChecker::device_fault(std::size_t dev, Time now, std::optional<State> state_then) {
  Dev& d = devices_[dev];
  // A fault while the drive is in FAULT already joins the latched one, which a request made
  // then covers (the master cannot tell them apart).
  if (state_then && (*state_then == State::fault || *state_then == State::fault_response_active)) return;
  withdraw(d, now + d.spec.period + 2 * d.spec.jitter, "device fault", false);
}

void CampaignChecker::master_restart(Time now) {
  for (auto& d : devices_) {
    d.permitted = false;
    d.written_after = now;
    d.word_out.reset();
    d.leave_why = "master restart";
  }
}

void CampaignChecker::state_command(std::size_t dev, StateCommand c, Time now) {
  Dev& d = devices_[dev];
  if (c == StateCommand::enable) {
    d.permitted = true;
    d.written_after.reset();
    d.word_out.reset();
    d.leave_by.reset();
    d.leave_why.clear();
    d.enabled_reported = false;
    return;
  }
  withdraw(d, now,
           c == StateCommand::emergency_stop ? "EMERGENCY STOP"
           : c == StateCommand::block_power  ? "BLOCK POWER"
                                             : "request of another target",
           true);
}

void CampaignChecker::master_cycle(Time t) {
  for (auto& d : devices_) {
    if (d.written_after && t > *d.written_after) {
      d.word_out = t;
      d.written_after.reset();
    }
  }
}

void CampaignChecker::exchange(std::size_t dev, Time t, bool words_delivered, bool watchdog_fed) {
  Dev& d = devices_[dev];
  if (d.word_out && words_delivered && t > *d.word_out) {
    // The device acts on the word at its first sample from t on: within one period (+ jitter
    // both ways).
    const Time by = t + d.spec.period + 2 * d.spec.jitter;
    if (!d.leave_by || by < *d.leave_by) d.leave_by = by;
    d.word_out.reset();
  }
  d.fed_before_slice = d.last_fed;
  if (watchdog_fed) {
    d.last_fed = t;
    d.armed = true;
    d.late_reported = false;
  }
}

std::pair<std::int64_t, std::int64_t> CampaignChecker::watchdog_window(const Dev& d) const {
  // The monitoring times the device may be using, in ms (-1: may be off).
  std::vector<std::int64_t> values;
  if (d.spec.watchdog_parameter == 0) {
    values = {d.spec.watchdog_fixed_ms};
  } else {
    for (const auto& c : d.cells) {
      if (c.spec.number == d.spec.watchdog_parameter) values = allowed_now(d, c, false);
    }
  }
  std::int64_t lo = -1;
  std::int64_t hi = -1;
  bool off = false;
  for (std::int64_t v : values) {
    std::int64_t t = v;
    if (d.spec.kind == devices::vf1000::kName) {
      const auto m = devices::vf1000::ib_wd_monitoring_time(static_cast<Word>(v));
      t = m ? m->count() : 0;
    }
    if (t <= 0) {
      off = true;
      continue;
    }
    lo = lo < 0 ? t : std::min(lo, t);
    hi = std::max(hi, t);
  }
  return {lo, off ? -1 : hi};
}

void CampaignChecker::observe(std::size_t dev, Time t, State state, bool watchdog_tripped, bool watchdog_fault) {
  Dev& d = devices_[dev];
  // Watchdog: a new trip must come after its time; an outage longer than its time plus a sample
  // must have tripped it.
  if (d.spec.watchdog_parameter != 0 || d.spec.watchdog_fixed_ms != 0) {
    const auto [lo, hi] = watchdog_window(d);
    if (watchdog_tripped && !d.tripped) {
      ++counts_.watchdog_trips;
      if (lo < 0) {
        violation(d, t, "watchdog-early", "the bus watchdog tripped although it is off");
      } else if (!d.armed || !d.fed_before_slice) {
        violation(d, t, "watchdog-early", "the bus watchdog tripped before any valid cycle reached the device");
      } else if (t - *d.fed_before_slice <= std::chrono::milliseconds(lo)) {
        violation(d, t, "watchdog-early", "the bus watchdog tripped " + ms(t - *d.fed_before_slice) +
                                              " after the last valid cycle (or earlier); its time is " +
                                              std::to_string(lo) + " ms");
      }
    }
    if (d.armed && d.last_fed && hi > 0 && !d.late_reported &&
        t - *d.last_fed > std::chrono::milliseconds(hi) + d.spec.period + 2 * d.spec.jitter) {
      ++counts_.watchdog_late_checks;
      d.late_reported = true;  // one check per outage
      if (!watchdog_tripped) {
        violation(d, t, "watchdog-late", "no valid cycle for " + ms(t - *d.last_fed) + " and the watchdog (" +
                                             std::to_string(hi) + " ms) has not tripped");
      }
    }
    d.tripped = watchdog_tripped;
  }
  // A watchdog fault is a fault like any other -- unless the drive was in a fault state already,
  // as for device faults (device_fault()).
  const bool in_fault = d.last_state && (*d.last_state == State::fault || *d.last_state == State::fault_response_active);
  if (watchdog_fault && !d.watchdog_fault && !in_fault) withdraw(d, t, "watchdog fault", false);
  d.watchdog_fault = watchdog_fault;
  d.last_state = state;
  // ENABLED only with permission, or while a withdrawal is on its way to the device.
  if (d.leave_by && t >= *d.leave_by) {
    ++counts_.stop_checks;
    if (state == State::enabled && !d.permitted) {
      violation(d, t, "stop", "still ENABLED " + ms(t - *d.leave_by) + " after the deadline of the " + d.leave_why);
      d.enabled_reported = true;
    }
    d.leave_by.reset();
  }
  if (state != State::enabled) {
    d.enabled_reported = false;
    d.lock_reported = false;
    return;
  }
  ++counts_.state_checks;
  if (d.download_open && !(d.lock_may_end && t >= *d.lock_may_end) && !d.lock_reported) {
    d.lock_reported = true;
    violation(d, t, "download-lock", "ENABLED during an open 80-SLOAD download (seed 000 11.4: secured until it ends)");
  }
  const bool in_flight = d.written_after || d.word_out || d.leave_by;
  if (!d.permitted && !in_flight && !d.enabled_reported) {
    d.enabled_reported = true;
    violation(d, t, "enabled", "ENABLED without a request for ENABLED since the last " +
                                   (d.leave_why.empty() ? std::string("start") : d.leave_why));
  }
}

}  // namespace ibs::sim

namespace ibs::sim {

void CampaignChecker::report(std::size_t dev, Time at, std::string check, std::string what) {
  violation(devices_[dev], at, std::move(check), std::move(what));
}

std::vector<std::int64_t> CampaignChecker::possible(std::size_t dev, std::uint16_t number, bool eeprom) const {
  for (const auto& c : devices_[dev].cells) {
    if (c.spec.number == number) return eeprom ? c.eeprom : c.ram;
  }
  return {};
}

// ---------------------------------------------------------------------------------------------
// The campaign: the ring, the traffic, the faults.

namespace {

// The campaign's oracle knows both drives it runs; the simulator hands out their emulators.
devices::Mc6000Device& mc6000_of(Simulator& sim, std::size_t i) {
  return dynamic_cast<devices::Mc6000Device&>(sim.emulator(i));
}
devices::Vf1000Device& vf1000_of(Simulator& sim, std::size_t i) {
  return dynamic_cast<devices::Vf1000Device&>(sim.emulator(i));
}


constexpr Duration kPcpTimeout = 500ms;      // pcp::ClientConfig::request_timeout (docs/pcp.md)
constexpr Duration kVfTimeout = 2s;          // vf1000_channel::ClientConfig::timeout
constexpr int kMarginCycles = 5;             // see docs/robustness.md
constexpr Duration kOutage = 550ms;          // longer than every watchdog time the ring uses

struct Pool {
  std::uint16_t number = 0;
  std::vector<std::int64_t> in_range;
  std::vector<std::int64_t> out_of_range;
};

struct Step {
  ParamOp op = ParamOp::read;
  std::uint16_t number = 0;
  std::int64_t value = 0;
  Duration pause_before{0};
  std::string special;  // counted under this name when it ends
};

struct Node {
  std::size_t index = 0;
  std::string kind;  // the drive kind's name
  int supi = 0;
  int ibcnf = 0;
  bool pcp = false;
  bool pd = false;
  std::vector<Pool> pools;
  std::vector<std::uint16_t> readable;
  // Traffic.
  bool busy = false;
  devices::ParamId id = 0;
  Step current;
  std::deque<Step> script;
  Time pause_until{0};
  int sload_end_retries = 0;
  bool fed_trace = true;
  bool tripped_trace = false;
  // State commands.
  Time next_command{0};
  std::optional<State> last_state;
  std::uint32_t software_resets = 0;  // VF1000 boots from RESET FAULT seen so far
  // 405/406 and the technician.
  std::optional<Time> power_cycle_at;
  bool check_layout = false;
  bool layout_expected_mismatch = false;
};

std::string kind_name(ParamKind k) { return std::string(devices::to_string(k)); }

struct Runner {
  const CampaignOptions& opt;
  CampaignResult& res;
  std::mt19937_64 rng;
  Scenario scenario;
  std::unique_ptr<Simulator> sim;
  CampaignChecker checker;
  std::vector<Node> nodes;
  std::unordered_map<std::string, std::size_t> by_name;
  std::size_t faults_seen = 0;
  Time next_outage{0};
  std::vector<StoreEntry> store;  // reused
  // IBS_CAMPAIGN_TRACE=NAME prints what happens to one device (for finding a violation's cause).
  std::optional<std::size_t> traced;
  void trace(const Node& n, Time t, const std::string& what) const {
    if (traced && *traced == n.index) std::fprintf(stderr, "%.3f ms %s\n", to_ms(t), what.c_str());
  }

  Runner(const CampaignOptions& o, CampaignResult& r) : opt(o), res(r), rng(o.seed * 0x9E3779B97F4A7C15ULL + 7) {}

  std::int64_t uniform(std::int64_t lo, std::int64_t hi) { return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng); }
  bool chance(double p) { return std::uniform_real_distribution<double>(0.0, 1.0)(rng) < p; }
  template <typename T>
  const T& pick(const std::vector<T>& v) { return v[static_cast<std::size_t>(uniform(0, static_cast<std::int64_t>(v.size()) - 1))]; }
  Duration between(Duration lo, Duration hi) { return Duration{uniform(lo.count(), hi.count())}; }

  void build() {
    struct Mc {
      const char* name;
      int supi, ibcnf;
      std::vector<int> butwd;
    };
    // PCP over 4 words (SUPI 3), 2 words (SUPI 2, 6, 9), 1 word (SUPI 5, 8, 11); two servos
    // without PCP (SUPI 10, 12), one of them stepped a cycle at a time (no jitter).
    const std::vector<Mc> mcs = {
        {"mc4a", 3, 0, {0, 50, 120}},   {"mc4b", 3, 0, {0, 80}},       {"mc4c", 3, 0, {40, 150}},
        {"mc2a", 9, 1, {30, 60, 100}},  {"mc2b", 6, 0, {0, 100}},      {"mc2c", 9, 0, {50, 200}},
        {"mc2d", 2, 0, {0, 60}},        {"mc1a", 11, 2, {30, 50}},     {"mc1b", 11, 3, {0, 200}},
        {"mc1c", 8, 1, {40, 120}},      {"mc1d", 5, 0, {0, 80}},       {"mcpd", 12, 2, {25, 40, 250}},
        {"mcpd2", 10, 3, {20, 100}},
    };
    for (const auto& m : mcs) {
      DeviceConfig c;
      c.name = m.name;
      c.kind = devices::mc6000::kName;
      c.supi = m.supi;
      c.ibcnf = m.ibcnf;
      c.bus = chance(0.3) ? interbus::BusKind::local : interbus::BusKind::remote;
      c.phase = between(Duration{0}, ibs::devices::mc6000::kSamplePeriod - Duration{1});
      c.jitter = std::string(m.name) == "mcpd" ? Duration{0} : pick(std::vector<Duration>{0us, 20us, 50us, 100us});
      c.initialised = !chance(0.2);
      c.watchdog_ms = pick(m.butwd);
      scenario.devices.push_back(c);
    }
    const std::vector<int> ibwd = {100, 200, 400, 65535};
    for (int v = 0; v < 4; ++v) {
      DeviceConfig c;
      c.name = "vf" + std::to_string(v + 1);
      c.kind = devices::vf1000::kName;
      c.phase = between(Duration{0}, ibs::devices::vf1000::kSamplePeriod - Duration{1});
      c.jitter = pick(std::vector<Duration>{0us, 100us, 400us});
      c.initialised = !chance(0.25);
      c.watchdog_ms = ibwd[static_cast<std::size_t>(v)] == 65535 ? 65535 : static_cast<int>(uniform(8, ibwd[static_cast<std::size_t>(v)]));
      c.watchdog_reaction = v % 4;  // 0 none, 1 E-IBS, 2 BLOCK POWER, 3 EMERGENCY STOP
      scenario.devices.push_back(c);
    }
    scenario.name = "campaign";
    scenario.bus.baud_2mbit = true;
    // Long enough for the transactions (about 500 per simulated second); the run stops earlier.
    scenario.duration = std::chrono::seconds(120 + static_cast<std::int64_t>(opt.transactions / 150));
    scenario.random.seed = opt.seed;
    scenario.random.corrupt_per_s = 2.0;
    scenario.random.power_cycle_per_s = 0.3;
    scenario.random.device_fault_per_s = 0.6;
    scenario.random.lost_per_s = 0.3;
    scenario.random.master_restart_per_s = 0.05;
    sim = std::make_unique<Simulator>(scenario);
    res.cycle_time = sim->cycle_time();

    for (std::size_t i = 0; i < scenario.devices.size(); ++i) {
      const DeviceConfig& c = scenario.devices[i];
      Node n;
      n.index = i;
      n.kind = c.kind;
      CheckerDeviceSpec spec;
      spec.name = c.name;
      spec.kind = c.kind;
      spec.jitter = c.jitter;
      std::string desc = c.name + ": ";
      if (c.kind == devices::mc6000::kName) {
        const auto& l = mc6000_of(*sim, i).layout();
        n.supi = c.supi;
        n.ibcnf = c.ibcnf;
        n.pcp = l.pcp_words > 0;
        n.pd = l.pd_words > 0;
        spec.period = ibs::devices::mc6000::kSamplePeriod;
        spec.download_check = ibs::devices::mc6000::DriveTiming{}.download_check;
        spec.has_pd = n.pd;
        desc += "MC6000 SUPI " + std::to_string(c.supi) + " / IBCNF " + std::to_string(c.ibcnf) + ", " +
                std::to_string(l.pd_words) + " process-data word(s), " +
                (n.pcp ? "PCP " + std::to_string(l.pcp_words) + " word(s)" : std::string("no PCP")) + ", " +
                (c.bus == interbus::BusKind::local ? "local" : "remote") + std::string(" bus, 409-BUTWD ") + std::to_string(*c.watchdog_ms) + " ms";
        if (n.pcp) {
          spec.watchdog_parameter = 409;
          build_mc_params(n, spec, c);
        } else {
          spec.watchdog_fixed_ms = *c.watchdog_ms;
        }
      } else {
        n.pcp = true;  // the communication word
        n.pd = true;
        spec.period = ibs::devices::vf1000::kSamplePeriod;
        spec.watchdog_parameter = 906;
        desc += "VF1000, 906-IB-WD " + std::to_string(*c.watchdog_ms) + " ms, 907-IBCOD " +
                std::to_string(*c.watchdog_reaction);
        build_vf_params(n, spec, c);
      }
      desc += ", phase " + fmt_time(c.phase) + ", jitter " + fmt_time(c.jitter) +
              (c.initialised ? "" : ", switched on at the start");
      res.devices.push_back(desc);
      checker.add_device(std::move(spec));
      n.next_command = Time{0} + between(1ms, 50ms);
      by_name[c.name] = i;
      nodes.push_back(std::move(n));
    }
    next_outage = Time{0} + between(3s, 8s);
    if (const char* e = std::getenv("IBS_CAMPAIGN_TRACE")) {
      const auto it = by_name.find(e);
      if (it != by_name.end()) traced = it->second;
    }
  }

  void build_mc_params(Node& n, CheckerDeviceSpec& spec, const DeviceConfig& c) {
    for (const pcp::ParameterInfo& p : devices::mc6000::kParameters) {
      ParamModelSpec m;
      m.number = p.number;
      m.eeprom = p.category == pcp::Category::eeprom;
      m.factory = p.default_value;
      m.initial = p.number == devices::mc6000::kSupi ? c.supi : p.number == devices::mc6000::kIbcnf ? c.ibcnf
                  : p.number == 409        ? *c.watchdog_ms
                                           : p.default_value;
      m.min = p.min;
      m.max = p.max;
      m.eeprom_save = std::chrono::milliseconds(15) * static_cast<std::int64_t>(pcp::size_of(p.type)) +
                      ibs::devices::mc6000::kSamplePeriod + 2 * c.jitter;
      m.card_writeable = devices::mc6000::card_writeable(p.number);
      m.role = !p.writable() ? ParamRole::device_owned
               : p.number == devices::mc6000::kProg  ? ParamRole::command
               : p.number == devices::mc6000::kSload ? ParamRole::sload
                                         : ParamRole::normal;
      spec.params.push_back(m);
      n.readable.push_back(p.number);
      if (m.role != ParamRole::normal || p.number == devices::mc6000::kSupi || p.number == devices::mc6000::kIbcnf) continue;
      Pool pool;
      pool.number = p.number;
      pool.in_range = {p.default_value, p.min, p.max};
      for (int k = 0; k < 3; ++k) add(pool.in_range, uniform(p.min, p.max));
      if (p.number == 409) pool.in_range = {0, 40, 100, 250, m.initial};
      for (const std::int64_t v : {p.min - 1, p.max + 1}) pool.out_of_range.push_back(v);
      n.pools.push_back(std::move(pool));
    }
  }

  void build_vf_params(Node& n, CheckerDeviceSpec& spec, const DeviceConfig& c) {
    for (const drive::ParameterInfo& p : devices::vf1000::parameters()) {
      ParamModelSpec m;
      m.number = p.number;
      const drive::Storage s = drive::storage(p.category);
      m.eeprom = s == drive::Storage::eeprom || s == drive::Storage::eeprom_ram;
      m.eeprom_ram = s == drive::Storage::eeprom_ram;
      m.factory = p.default_value;
      m.initial = p.number == devices::vf1000::pnr::kIbWd ? *c.watchdog_ms : p.number == devices::vf1000::pnr::kIbcod ? *c.watchdog_reaction
                                                                                           : p.default_value;
      m.min = p.min;
      m.max = p.max;
      m.eeprom_save = Duration{0};  // the inverter's store takes the EEPROM copy with the value
      // 901/905 mirror the process data; 11-STAT reads the drive's status and takes only the reset
      // 000FH (seed 000, 8.1.1), over the communication word too (VF-E14).
      const bool mirrored = p.number == devices::vf1000::pnr::kIcntl || p.number == devices::vf1000::pnr::kFdriv ||
                            p.number == devices::vf1000::pnr::kStat;
      m.role = (!drive::writable(p.category) || mirrored) ? ParamRole::device_owned
               : p.number == devices::vf1000::pnr::kProg           ? ParamRole::command
                                                      : ParamRole::normal;
      spec.params.push_back(m);
      n.readable.push_back(p.number);
      if (m.role != ParamRole::normal) continue;
      Pool pool;
      pool.number = p.number;
      pool.in_range = {p.default_value, p.min, p.max};
      for (int k = 0; k < 2; ++k) add(pool.in_range, uniform(p.min, p.max));
      if (p.number == devices::vf1000::pnr::kIbWd) pool.in_range = {100, 200, 400, 65535, m.initial};
      if (p.max < 0xFFFF) pool.out_of_range.push_back(p.max + 1);
      if (p.type == drive::DataType::usign8 || p.type == drive::DataType::binary8) pool.out_of_range.push_back(0x1FF);
      if (p.min > 0) pool.out_of_range.push_back(p.min - 1);
      n.pools.push_back(std::move(pool));
    }
  }

  // --- traffic ---------------------------------------------------------------------------------

  Step next_step(Node& n) {
    if (!n.script.empty()) {
      Step s = n.script.front();
      n.script.pop_front();
      return s;
    }
    const bool mc = n.kind == devices::mc6000::kName;
    if (mc && chance(1.0 / 3000)) start_download(n);
    if (mc && chance(1.0 / 3000)) {
      // 405-SUPI / 406-IBCNF: evaluated only at the next power-on (seed 001 3.2.2).
      const bool supi = chance(0.5);
      const std::uint16_t number = supi ? devices::mc6000::kSupi : devices::mc6000::kIbcnf;
      const int configured = supi ? n.supi : n.ibcnf;
      std::int64_t v = configured;
      if (chance(0.5)) {
        while (v == configured) v = supi ? uniform(0, 12) : uniform(0, 3);
      }
      n.script.push_back({ParamOp::write, number, v, Duration{0}, supi ? "405-SUPI writes" : "406-IBCNF writes"});
    }
    if (chance(1.0 / 6000)) {
      // 4-PROG / 71-PROG: 1 loads the factory defaults (seed 000 10); 111 (MC6000) a baud rate.
      const std::int64_t v = mc && chance(0.3) ? pick(std::vector<std::int64_t>{0, 111}) : 1;
      n.script.push_back({ParamOp::write, static_cast<std::uint16_t>(mc ? devices::mc6000::kProg : devices::vf1000::pnr::kProg), v,
                          Duration{0}, mc ? "4-PROG writes" : "71-PROG writes"});
    }
    if (!n.script.empty()) return next_step(n);
    const double r = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    const double describe = mc ? 0.06 : 0.02;
    if (r < 0.02) {
      // A parameter the device does not have.
      const std::uint16_t missing = pick(std::vector<std::uint16_t>{40, 400, 999});
      const ParamOp op = pick(std::vector<ParamOp>{ParamOp::read, ParamOp::write, ParamOp::describe});
      return {op, missing, 1, Duration{0}, ""};
    }
    if (r < 0.02 + describe) return {ParamOp::describe, pick(n.readable), 0, Duration{0}, ""};
    if (r < 0.5) return {ParamOp::read, pick(n.readable), 0, Duration{0}, ""};
    const Pool& p = pick(n.pools);
    const bool bad = !p.out_of_range.empty() && chance(0.12);
    return {ParamOp::write, p.number, bad ? pick(p.out_of_range) : pick(p.in_range), Duration{0}, ""};
  }

  void start_download(Node& n) {
    // Seed 000 11.4: SLOAD = -1 (only at standstill), the dataset, SLOAD = -2, then poll SLOAD.
    ++res.special["80-SLOAD downloads started"];
    n.sload_end_retries = 0;
    if (n.pd) command(n, StateCommand::block_power, sim->now());
    n.script.push_back({ParamOp::write, devices::mc6000::kSload, -1, 30ms, "80-SLOAD = -1"});
    for (int k = 0; k < 3; ++k) {
      const Pool& p = pick(n.pools);
      n.script.push_back({ParamOp::write, p.number, pick(p.in_range), Duration{0}, "writes during a download"});
    }
    n.script.push_back({ParamOp::write, devices::mc6000::kSload, -2, Duration{0}, "80-SLOAD = -2"});
    n.script.push_back({ParamOp::read, devices::mc6000::kSload, 0, 600ms, "80-SLOAD polls"});
  }

  void submit(Node& n, Time now) {
    Step s = next_step(n);
    if (s.pause_before > Duration{0} && n.pause_until <= now) {
      n.pause_until = now + s.pause_before;
      s.pause_before = Duration{0};
      n.script.push_front(s);
      return;
    }
    devices::DeviceDriver& drv = sim->driver(n.index);
    // An MC6000 request: an Initiate and the request itself, each with the PCP client's timeout;
    // a write of 4-PROG = 1 waits for the factory defaults (seed 000, 10: up to 10 s).
    const bool factory_defaults = n.kind == devices::mc6000::kName && s.op == devices::ParamOp::write &&
                                  s.number == devices::mc6000::kProg && s.value == devices::mc6000::kProgFactoryDefaults;
    const Duration mc_limit =
        kPcpTimeout + (factory_defaults ? devices::Mc6000Driver::kFactoryDefaultsTimeout : kPcpTimeout);
    const Duration limit = (n.kind == devices::mc6000::kName ? mc_limit : kVfTimeout) + kMarginCycles * sim->cycle_time();
    n.current = s;
    trace(n, now, "submit " + std::string(devices::to_string(s.op)) + " " + std::to_string(s.number) + " " + std::to_string(s.value));
    checker.submitted(n.index, s.op, s.number, s.value, now, limit);
    n.id = drv.parameters().submit(s.op, s.number, s.value);
    n.busy = true;
    if (n.id == 0) finish(n, {ParamKind::refused, 0}, now);
  }

  void finish(Node& n, devices::ParamStatus st, Time now) {
    n.busy = false;
    trace(n, now, "end " + kind_name(st.kind) + " " + std::to_string(st.value));
    checker.ended(n.index, st.kind, st.value, now);
    ++res.transactions;
    ++res.transactions_by[std::string(devices::to_string(n.current.op)) + " " + kind_name(st.kind)];
    if (!n.current.special.empty()) ++res.special[n.current.special + " (" + kind_name(st.kind) + ")"];
    check_store(n, now);
    const bool mc = n.kind == devices::mc6000::kName;
    if (mc && n.current.op == ParamOp::write && st.kind != ParamKind::written && st.kind != ParamKind::refused) {
      // A refused PCP write sets 85-SERR, which refuses every further write until it is read.
      n.script.push_front({ParamOp::read, devices::mc6000::kSerr, 0, Duration{0}, ""});
      // A download whose start or end was refused is given up (or its end repeated).
      if (n.current.number == devices::mc6000::kSload && n.current.value == -1) {
        while (!n.script.empty() && !n.script.front().special.empty() && n.script.front().number != devices::mc6000::kSerr) n.script.pop_front();
        std::erase_if(n.script, [](const Step& x) { return !x.special.empty(); });
      }
      if (n.current.number == devices::mc6000::kSload && n.current.value == -2 && n.sload_end_retries < 3) {
        ++n.sload_end_retries;
        n.script.push_back({ParamOp::write, devices::mc6000::kSload, -2, 100ms, "80-SLOAD = -2"});
      }
    }
    if (mc && n.current.op == ParamOp::read && n.current.number == devices::mc6000::kSload && st.kind == ParamKind::value &&
        !n.current.special.empty()) {
      ++res.special[st.value == 0 ? "80-SLOAD downloads completed (reads 0)" : "80-SLOAD polls still -1"];
      if (st.value == -1 && checker.download_open(n.index)) {
        n.script.push_back({ParamOp::read, devices::mc6000::kSload, 0, 100ms, "80-SLOAD polls"});
      }
    }
    if (mc && n.current.op == ParamOp::write && st.kind == ParamKind::written &&
        (n.current.number == devices::mc6000::kSupi || n.current.number == devices::mc6000::kIbcnf) &&
        n.current.value != (n.current.number == devices::mc6000::kSupi ? n.supi : n.ibcnf)) {
      // Switch the servo off and on once the EEPROM has the value: it must come back with a
      // module error (its layout no longer fits the ring).
      n.power_cycle_at = now + 40ms;
    }
  }

  void check_store(Node& n, Time now) {
    store.clear();
    if (n.kind == devices::mc6000::kName) {
      const auto& servo = mc6000_of(*sim, n.index);
      if (servo.pcp() == nullptr) return;
      const pcp::ParameterStore& ps = servo.drive().store();
      for (const pcp::ParameterInfo& p : devices::mc6000::kParameters) {
        const auto v = ps.get(p.number);
        const auto e = ps.eeprom(p.number);
        StoreEntry entry{p.number, v ? pcp::signed_raw(*v) : 0, std::nullopt};
        if (e) entry.eeprom = pcp::signed_raw(*e);
        store.push_back(entry);
      }
    } else {
      const devices::vf1000::Drive& d = vf1000_of(*sim, n.index).drive();
      for (const drive::ParameterInfo& p : devices::vf1000::parameters()) {
        const int slot = d.table().slot(p.number);
        if (slot < 0) continue;
        store.push_back({p.number, d.store().value(static_cast<std::size_t>(slot)),
                         std::optional<std::int64_t>(d.store().eeprom_value(static_cast<std::size_t>(slot)))});
      }
    }
    checker.check_store(n.index, now, store);
  }

  // --- state commands --------------------------------------------------------------------------

  void command(Node& n, StateCommand c, Time now) {
    drivecom::Sequencer& seq = sim->driver(n.index).sequencer();
    std::string name;
    switch (c) {
      case StateCommand::enable: seq.request(drivecom::Target::enabled, now); name = "request ENABLED"; break;
      case StateCommand::other_target: {
        const auto t = pick(std::vector<drivecom::Target>{drivecom::Target::start_up_inhibit, drivecom::Target::ready,
                                                          drivecom::Target::on});
        seq.request(t, now);
        name = "request " + std::string(drivecom::to_string(t));
        break;
      }
      case StateCommand::emergency_stop: seq.request_emergency_stop(now); name = "EMERGENCY STOP"; break;
      case StateCommand::block_power: seq.request_block_power(now); name = "BLOCK POWER"; break;
    }
    checker.state_command(n.index, c, now);
    trace(n, now, "command " + name);
    ++res.state_commands;
    ++res.state_commands_by[name];
  }

  [[nodiscard]] bool in_download(const Node& n) const {
    if (n.kind != devices::mc6000::kName) return false;
    if (checker.download_open(n.index) || (n.busy && n.current.number == devices::mc6000::kSload)) return true;
    return std::any_of(n.script.begin(), n.script.end(), [](const Step& s) { return s.number == devices::mc6000::kSload; });
  }

  void random_command(Node& n, Time now) {
    const double r = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    StateCommand c = r < 0.5    ? StateCommand::enable
                     : r < 0.75 ? StateCommand::other_target
                     : r < 0.875 ? StateCommand::emergency_stop
                                 : StateCommand::block_power;
    if (c == StateCommand::enable && !opt.enable_during_download && in_download(n)) c = StateCommand::other_target;
    command(n, c, now);
    if (chance(0.2)) {
      devices::DeviceDriver& drv = sim->driver(n.index);
      drv.set_reference(n.kind == devices::mc6000::kName ? static_cast<double>(uniform(-3000, 3000))
                                                     : static_cast<double>(uniform(-60, 60)));
    }
    // Mostly every few cycles; now and then a long pause, in which a request runs its whole
    // course through whatever faults come.
    n.next_command = now + (chance(0.03) ? between(300ms, 3s) : between(10ms, 120ms));
  }

  // --- the technician ---------------------------------------------------------------------------

  void recommission(Node& n, Time now) {
    // 405/406 back to the ring's configuration (keypad), then switched off and on.
    devices::mc6000::DriveParameters& ps = mc6000_of(*sim, n.index).drive().parameters();
    for (const auto& [number, v] : {std::pair<std::uint16_t, int>{devices::mc6000::kSupi, n.supi}, {devices::mc6000::kIbcnf, n.ibcnf}}) {
      ps.preset(number, v);
      checker.set_value(n.index, number, v);
    }
    sim->inject_fault(Action::fault_power_cycle, n.index);
    ++res.special["recommissioned (405/406 restored, power cycle)"];
    static_cast<void>(now);
  }

  // --- the loop ----------------------------------------------------------------------------------

  void process_faults() {
    const auto& faults = sim->summary().faults;
    for (; faults_seen < faults.size(); ++faults_seen) {
      const FaultRecord& f = faults[faults_seen];
      ++res.faults[f.kind];
      if (traced && (f.device.empty() || f.device == scenario.devices[*traced].name)) {
        trace(nodes[*traced], f.at, "fault " + f.kind + " " + f.detail);
      }
      if (f.kind == "master-restart") {
        // At a cycle end: the master's cycle right after it already sends BLOCK POWER.
        checker.master_restart(f.at - Duration{1});
        continue;
      }
      const auto it = by_name.find(f.device);
      if (it == by_name.end()) continue;
      Node& n = nodes[it->second];
      if (f.kind == "power-cycle") {
        checker.power_cycle(n.index, f.at, n.last_state);
        if (n.kind == devices::mc6000::kName && n.pcp) n.script.push_front({ParamOp::read, devices::mc6000::kSerr, 0, Duration{0}, ""});
      } else if (f.kind == "device-fault") {
        checker.device_fault(n.index, f.at, n.last_state);
      }
    }
  }

  void run() {
    build();
    const Duration ct = sim->cycle_time();
    SimOptions so;
    so.measure_master_time = false;
    const auto wall0 = std::chrono::steady_clock::now();
    Time last_progress{0};
    std::uint64_t valid_before = 0;
    for (std::int64_t k = 1;; ++k) {
      const Time t = Time{0} + k * ct;
      const bool more = sim->run_until(t, so);
      // A VF1000 that booted from RESET FAULT during this stretch: the model's store follows before
      // any outcome of this cycle is checked against the device's.
      for (Node& n : nodes) {
        if (n.kind != devices::vf1000::kName) continue;
        if (const std::uint32_t r = vf1000_of(*sim, n.index).software_resets(); r != n.software_resets) {
          n.software_resets = r;
          checker.software_reset(n.index, t);
        }
      }
      const std::uint64_t valid_now = sim->summary().valid_cycles;
      const bool valid = valid_now > valid_before;
      valid_before = valid_now;
      process_faults();
      for (Node& n : nodes) {
        const bool me = sim->module_error(n.index, t);
        bool lost = me;
        if (n.kind == devices::vf1000::kName && vf1000_of(*sim, n.index).module_error(t)) lost = false;  // initialising
        if (n.kind == devices::mc6000::kName && mc6000_of(*sim, n.index).configuration_mismatch()) lost = true;
        checker.exchange(n.index, t, valid && !lost, valid && !me);
        if (traced && *traced == n.index && (valid && !me) != n.fed_trace) {
          n.fed_trace = valid && !me;
          trace(n, t, n.fed_trace ? "data flows" : "no data");
        }
      }
      checker.master_cycle(t);
      for (Node& n : nodes) {
        if (!n.busy) continue;
        const devices::ParamStatus st = sim->driver(n.index).parameters().status(n.id);
        if (st.done()) finish(n, st, t);
      }
      for (Node& n : nodes) {
        const State s = sim->device_state(n.index);
        bool tripped = false;
        bool wd_fault = false;
        if (n.kind == devices::vf1000::kName) {
          tripped = vf1000_of(*sim, n.index).watchdog_tripped();
          wd_fault = vf1000_of(*sim, n.index).error_number().has_value();
        } else {
          tripped = wd_fault = mc6000_of(*sim, n.index).watchdog_tripped();
        }
        checker.observe(n.index, t, s, tripped, wd_fault);
        if (traced && *traced == n.index && (s != n.last_state || tripped != n.tripped_trace)) {
          n.tripped_trace = tripped;
          trace(n, t, "state " + std::string(drivecom::to_string(s)) + (tripped ? " (watchdog tripped)" : ""));
        }
        n.last_state = s;
      }
      checker.check_overdue(t);
      if (!more || res.transactions >= opt.transactions) break;
      // Layout checks and the technician.
      for (Node& n : nodes) {
        if (n.kind != devices::mc6000::kName || !n.pcp) continue;
        devices::Mc6000Device* mc = &mc6000_of(*sim, n.index);
        if (n.check_layout) {
          n.check_layout = false;
          if (mc->configuration_mismatch() != n.layout_expected_mismatch) {
            checker.report(n.index, t, "layout",
                           std::string("after a power-on with 405/406 = ") + show(checker.possible(n.index, devices::mc6000::kSupi, true)) +
                               " / " + show(checker.possible(n.index, devices::mc6000::kIbcnf, true)) + " the device " +
                               (n.layout_expected_mismatch ? "does not show" : "shows") + " a module error");
          }
          ++res.special["layout checks after a power-on with changed 405/406"];
        }
        if (n.power_cycle_at && t >= *n.power_cycle_at && !n.busy) {
          n.power_cycle_at.reset();
          const auto supi = checker.possible(n.index, devices::mc6000::kSupi, true);
          const auto ibcnf = checker.possible(n.index, devices::mc6000::kIbcnf, true);
          if (supi.size() == 1 && ibcnf.size() == 1) {
            n.check_layout = true;
            n.layout_expected_mismatch = supi[0] != n.supi || ibcnf[0] != n.ibcnf;
          }
          sim->inject_fault(Action::fault_power_cycle, n.index);
          ++res.special["power cycles after changing 405/406"];
          continue;
        }
        if (mc->configuration_mismatch() && !n.check_layout) recommission(n, t);
      }
      // Traffic and commands.
      for (Node& n : nodes) {
        if (!n.busy && t >= n.pause_until && !n.power_cycle_at && n.pcp &&
            !(n.kind == devices::vf1000::kName && sim->driver(n.index).parameters().closing())) {
          submit(n, t);
        }
        if (n.pd && t >= n.next_command) random_command(n, t);
      }
      if (t >= next_outage) {
        // The master's data stops (a run of corrupted cycles): every watchdog must trip.
        const int count = static_cast<int>(kOutage / ct) + 1;
        sim->inject_fault(Action::fault_corrupt, 0, Duration{0}, count);
        ++res.special["watchdog outages (" + fmt_time(kOutage) + " of corrupted cycles)"];
        next_outage = t + between(5s, 15s);
      }
      if (opt.progress && t - last_progress >= 10s) {
        opt.progress(res.transactions, t);
        last_progress = t;
      }
    }
    const Time end = sim->now();
    for (Node& n : nodes) {
      if (n.pcp) check_store(n, end);
    }
    res.simulated = end - Time{0};
    res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  }
};

}  // namespace

CampaignResult run_campaign(const CampaignOptions& options) {
  CampaignResult res;
  res.seed = options.seed;
  Runner r(options, res);
  r.run();
  res.checks = r.checker.counts();
  res.violation_count = r.checker.violation_count();
  res.violations = r.checker.violations();
  return res;
}

}  // namespace ibs::sim
