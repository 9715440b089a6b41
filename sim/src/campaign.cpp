#include "ibs/sim/campaign.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <unordered_map>

#include "ibs/devices/emulator.hpp"
#include "ibs/devices/registry.hpp"
#include "ibs/drive/parameters.hpp"
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
      if (c.spec.role == ParamRole::download) d.download_open = false;
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
      if (o.value == drive::kLoadDefaults) factory_reset(d, certain);
      break;
    case ParamRole::download:
      if (o.value == drive::kDownloadBegin) {
        if (certain) {
          c->ram = {drive::kDownloadBegin};
          c->settle_at.reset();
          d.download_open = true;
          d.lock_may_end.reset();
        } else {
          add(c->ram, drive::kDownloadBegin);
        }
      } else if (o.value == drive::kDownloadEnd) {
        if (certain) {
          // The dataset is checked (SLOAD reads kDownloadBegin), then SLOAD reads 0 (docs/errata.md
          // MC-D2).
          c->ram = {drive::kDownloadBegin, 0};
          c->settle_at = now + d.spec.download_check + 2 * d.spec.period + 2 * d.spec.jitter;
          c->settle = 0;
          c->settle_ram = true;
          d.lock_may_end = o.submitted + d.spec.download_check;
        } else {
          add(c->ram, drive::kDownloadBegin);
          add(c->ram, 0);
          d.download_open = false;  // not known any more
        }
      }
      break;
    case ParamRole::normal:
      if (d.download_open) {
        // LUSTBUS manual 11.4 (MC-D2): during a download only the CardWriteable parameters take the
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
  if (wc->spec.role == ParamRole::command && w.value == drive::kLoadDefaults && c.spec.role != ParamRole::command &&
      c.spec.role != ParamRole::device_owned) {
    add(v, c.spec.factory);
  }
  if (w.number == c.spec.number) {
    if (c.spec.role == ParamRole::normal) {
      add(v, w.value);
    } else if (c.spec.role == ParamRole::download && w.value < 0 && !eeprom) {
      add(v, drive::kDownloadBegin);
      if (w.value == drive::kDownloadEnd) add(v, 0);
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
  // A reset from FAULT that boots the drive (RESET FAULT, INTERBUS manual 5.2.1): its store
  // as after a power cycle, and its bus watchdog as after one too: monitoring again from the first valid cycle after the
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
  // Nor can it tell a drive switched off and on in FAULT RESPONSE ACTIVE or FAULT that comes back
  // in FAULT (its cause still there) from one that stayed in FAULT, when the self-test's NOT READY
  // falls between two of its samples: a request made in the fault covers the reset of that fault
  // too. A drive that comes back without the fault has restarted, which the master can see (it
  // left FAULT without a reset edge) and must not enable: the first state after NOT READY decides
  // (observe()).
  if (state_then && (*state_then == State::fault || *state_then == State::fault_response_active)) {
    d.boot_from_fault = now;
    return;
  }
  d.boot_from_fault.reset();
  withdraw(d, now, "power cycle", false);
}

void CampaignChecker::reboot_store(Dev& d, Time now) {
  settle(d, now);
  for (auto& c : d.cells) {
    switch (c.spec.role) {
      case ParamRole::device_owned: break;
      case ParamRole::command:
      case ParamRole::download: c.ram = {c.spec.factory}; c.settle_at.reset(); break;
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
    d.boot_from_fault.reset();  // asked after the power cycle: nothing of it is left to withdraw
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
    const std::int64_t t = d.spec.watchdog_parameter != 0 && d.spec.watchdog_ms ? d.spec.watchdog_ms(v) : v;
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
  if (d.boot_from_fault && state != State::not_ready) {
    if (state != State::fault && state != State::fault_response_active) withdraw(d, *d.boot_from_fault, "power cycle", false);
    d.boot_from_fault.reset();
  }
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
    violation(d, t, "download-lock",
              "ENABLED during an open " + d.spec.download_label + " download (" + d.spec.download_source + ")");
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
// The campaign: the ring, the traffic, the faults. Every drive kind's part comes from its profile
// (devices/campaign_profile.hpp), found through the registry.

namespace {

constexpr int kMarginCycles = 5;             // see docs/robustness.md
constexpr Duration kOutage = 550ms;          // longer than every watchdog time the ring uses

struct Step {
  ParamOp op = ParamOp::read;
  std::uint16_t number = 0;
  std::int64_t value = 0;
  Duration pause_before{0};
  std::string special;  // counted under this name when it ends
};

struct Node {
  std::size_t index = 0;
  const devices::CampaignProfile* profile = nullptr;
  devices::CampaignRingDevice ring;  // as the ring configured it
  bool pcp = false;                  // a parameter channel
  bool pd = false;
  std::vector<devices::CampaignWrites> pools;
  std::vector<std::uint16_t> readable;
  std::vector<devices::CampaignLayoutParameter> layout;
  std::optional<devices::CampaignDownload> download;
  std::optional<devices::CampaignFactoryDefaults> factory_defaults;
  std::optional<std::uint16_t> error_register;
  double describe_share = 0.0;
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
  std::uint32_t software_resets = 0;  // boots from a reset seen so far
  // The layout parameters and the technician.
  std::optional<Time> power_cycle_at;
  bool check_layout = false;
  bool layout_expected_mismatch = false;

  [[nodiscard]] bool is_download(std::uint16_t number) const { return download && download->parameter == number; }
  // "405/406"
  [[nodiscard]] std::string layout_numbers() const {
    std::string s;
    for (const auto& l : layout) s += (s.empty() ? "" : "/") + std::to_string(l.number);
    return s;
  }
};

std::string kind_name(ParamKind k) { return std::string(devices::to_string(k)); }

DeviceConfig device_config(const devices::DriveKind& kind, const devices::CampaignRingDevice& r) {
  DeviceConfig c;
  c.name = r.name;
  c.kind = std::string(kind->name());
  set_device_settings(c, r.settings);
  c.phase = r.phase;
  c.jitter = r.jitter;
  c.initialised = r.initialised;
  return c;
}

struct Runner {
  const CampaignOptions& opt;
  CampaignResult& res;
  devices::CampaignRandom rng;
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

  std::int64_t uniform(std::int64_t lo, std::int64_t hi) { return rng.uniform(lo, hi); }
  bool chance(double p) { return rng.chance(p); }
  template <typename T>
  const T& pick(const std::vector<T>& v) { return rng.pick(v); }
  Duration between(Duration lo, Duration hi) { return rng.between(lo, hi); }

  void build() {
    // Every kind's share of the ring, in the registry's order.
    std::vector<std::pair<const devices::DriveKind*, devices::CampaignRingDevice>> ring;
    for (const devices::DriveKind& k : devices::drive_kinds()) {
      if (k.campaign == nullptr) continue;
      for (devices::CampaignRingDevice& r : k.campaign->ring(rng)) {
        scenario.devices.push_back(device_config(k, r));
        ring.emplace_back(&k, std::move(r));
      }
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
      const devices::CampaignProfile& profile = *ring[i].first->campaign;
      Node n;
      n.index = i;
      n.profile = &profile;
      n.ring = std::move(ring[i].second);
      devices::CampaignDevice dev = profile.device(n.ring, sim->emulator(i), rng);
      n.pcp = dev.has_channel;
      n.pd = dev.has_pd;
      n.pools = std::move(dev.writes);
      n.readable = std::move(dev.readable);
      n.layout = std::move(dev.layout);
      n.download = profile.download();
      n.factory_defaults = profile.factory_defaults();
      n.error_register = profile.write_error_register();
      n.describe_share = profile.describe_share();
      CheckerDeviceSpec spec;
      spec.name = c.name;
      spec.period = dev.period;
      spec.jitter = c.jitter;
      spec.has_pd = dev.has_pd;
      spec.params = std::move(dev.params);
      spec.watchdog_parameter = dev.watchdog_parameter;
      spec.watchdog_ms = [&profile](std::int64_t raw) { return profile.watchdog_ms(raw); };
      spec.watchdog_fixed_ms = dev.watchdog_fixed_ms;
      if (n.download) {
        spec.download_check = n.download->check;
        spec.download_label = std::string(n.download->label);
        spec.download_source = std::string(n.download->source);
      }
      res.devices.push_back(c.name + ": " + dev.description + ", phase " + fmt_time(c.phase) + ", jitter " +
                            fmt_time(c.jitter) + (c.initialised ? "" : ", switched on at the start"));
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

  // --- traffic ---------------------------------------------------------------------------------

  Step next_step(Node& n) {
    if (!n.script.empty()) {
      Step s = n.script.front();
      n.script.pop_front();
      return s;
    }
    if (n.download && chance(1.0 / 3000)) start_download(n);
    if (!n.layout.empty() && chance(1.0 / 3000)) change_layout(n);
    if (n.factory_defaults && chance(1.0 / 6000)) {
      // The PROG command: kLoadDefaults loads the factory defaults (LUSTBUS manual 10); now and then
      // another of its values.
      const devices::CampaignFactoryDefaults& f = *n.factory_defaults;
      const std::int64_t v = !f.other_values.empty() && chance(f.other_chance) ? pick(f.other_values)
                                                                             : std::int64_t{drive::kLoadDefaults};
      n.script.push_back({ParamOp::write, f.parameter, v, Duration{0}, std::string(f.label) + " writes"});
    }
    if (!n.script.empty()) return next_step(n);
    const double r = rng.real();
    if (r < 0.02) {
      // A parameter the device does not have.
      const std::uint16_t missing = pick(std::vector<std::uint16_t>{40, 400, 999});
      const ParamOp op = pick(std::vector<ParamOp>{ParamOp::read, ParamOp::write, ParamOp::describe});
      return {op, missing, 1, Duration{0}, ""};
    }
    if (r < 0.02 + n.describe_share) return {ParamOp::describe, pick(n.readable), 0, Duration{0}, ""};
    if (r < 0.5) return {ParamOp::read, pick(n.readable), 0, Duration{0}, ""};
    const devices::CampaignWrites& p = pick(n.pools);
    const bool bad = !p.out_of_range.empty() && chance(0.12);
    return {ParamOp::write, p.number, bad ? pick(p.out_of_range) : pick(p.in_range), Duration{0}, ""};
  }

  void change_layout(Node& n) {
    // One of the layout parameters, each as likely: the drive evaluates it only at the next
    // power-on. Half the time the ring's value, half another.
    std::size_t k = 0;
    while (k + 1 < n.layout.size() && !chance(1.0 / static_cast<double>(n.layout.size() - k))) ++k;
    const devices::CampaignLayoutParameter& l = n.layout[k];
    std::int64_t v = l.configured;
    if (chance(0.5)) {
      while (v == l.configured) v = uniform(l.min, l.max);
    }
    n.script.push_back({ParamOp::write, l.number, v, Duration{0}, std::string(l.label) + " writes"});
  }

  void start_download(Node& n) {
    // LUSTBUS manual 11.4: SLOAD = -1 (only at standstill), the dataset, SLOAD = -2, then poll SLOAD.
    const devices::CampaignDownload& dl = *n.download;
    const std::string label(dl.label);
    ++res.special[label + " downloads started"];
    n.sload_end_retries = 0;
    if (n.pd) command(n, StateCommand::block_power, sim->now());
    n.script.push_back({ParamOp::write, dl.parameter, drive::kDownloadBegin, 30ms, label + " = -1"});
    for (int k = 0; k < 3; ++k) {
      const devices::CampaignWrites& p = pick(n.pools);
      n.script.push_back({ParamOp::write, p.number, pick(p.in_range), Duration{0}, "writes during a download"});
    }
    n.script.push_back({ParamOp::write, dl.parameter, drive::kDownloadEnd, Duration{0}, label + " = -2"});
    n.script.push_back({ParamOp::read, dl.parameter, 0, 600ms, label + " polls"});
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
    const Duration limit = n.profile->request_timeout(s.op, s.number, s.value) + kMarginCycles * sim->cycle_time();
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
    const Step& cur = n.current;
    if (n.error_register && cur.op == ParamOp::write && st.kind != ParamKind::written && st.kind != ParamKind::refused) {
      // The refused write latched the error register, which refuses every further write until
      // it is read.
      const std::uint16_t reg = *n.error_register;
      n.script.push_front({ParamOp::read, reg, 0, Duration{0}, ""});
      // A download whose start was refused is given up (or its end repeated). A start whose
      // outcome is unknown (timed out, or cut by a restart) may have opened the download: the
      // drive then keeps it open -- it knows no connection (docs/errata.md MC-D2) -- and would
      // take every later value untested or drop it. Its dataset is dropped, but its end is sent
      // at once: it closes a download that did open and is refused where none did.
      if (n.is_download(cur.number) && cur.value == drive::kDownloadBegin) {
        const bool maybe_open = st.kind == ParamKind::timeout || st.kind == ParamKind::aborted;
        std::erase_if(n.script, [&](const Step& x) {
          if (x.special.empty()) return false;
          return !maybe_open || !n.is_download(x.number);
        });
      }
      if (n.is_download(cur.number) && cur.value == drive::kDownloadEnd && n.sload_end_retries < 3) {
        ++n.sload_end_retries;
        n.script.push_back({ParamOp::write, cur.number, drive::kDownloadEnd, 100ms, std::string(n.download->label) + " = -2"});
      }
    }
    if (n.is_download(cur.number) && cur.op == ParamOp::read && st.kind == ParamKind::value && !cur.special.empty()) {
      const std::string label(n.download->label);
      ++res.special[st.value == 0 ? label + " downloads completed (reads 0)" : label + " polls still -1"];
      if (st.value == drive::kDownloadBegin && checker.download_open(n.index)) {
        n.script.push_back({ParamOp::read, cur.number, 0, 100ms, label + " polls"});
      }
    }
    if (cur.op == ParamOp::write && st.kind == ParamKind::written) {
      for (const auto& l : n.layout) {
        // Switch the drive off and on once the EEPROM has the value: it must come back with a
        // module error (its layout no longer fits the ring).
        if (cur.number == l.number && cur.value != l.configured) n.power_cycle_at = now + 40ms;
      }
    }
  }

  void check_store(Node& n, Time now) {
    store.clear();
    if (!n.pcp) return;
    n.profile->read_store(sim->emulator(n.index), store);
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
    if (!n.download) return false;
    if (checker.download_open(n.index) || (n.busy && n.is_download(n.current.number))) return true;
    return std::any_of(n.script.begin(), n.script.end(), [&n](const Step& s) { return n.is_download(s.number); });
  }

  void random_command(Node& n, Time now) {
    const double r = rng.real();
    StateCommand c = r < 0.5    ? StateCommand::enable
                     : r < 0.75 ? StateCommand::other_target
                     : r < 0.875 ? StateCommand::emergency_stop
                                 : StateCommand::block_power;
    if (c == StateCommand::enable && !opt.enable_during_download && in_download(n)) c = StateCommand::other_target;
    command(n, c, now);
    if (chance(0.2)) {
      const auto [lo, hi] = n.profile->reference_range();
      sim->driver(n.index).set_reference(static_cast<double>(uniform(lo, hi)));
    }
    // Mostly every few cycles; now and then a long pause, in which a request runs its whole
    // course through whatever faults come.
    n.next_command = now + (chance(0.03) ? between(300ms, 3s) : between(10ms, 120ms));
  }

  // --- the technician ---------------------------------------------------------------------------

  void recommission(Node& n) {
    // The layout parameters back to the ring's configuration at the drive, then switched off
    // and on.
    n.profile->restore_layout(sim->emulator(n.index), n.ring);
    for (const auto& l : n.layout) checker.set_value(n.index, l.number, l.configured);
    sim->inject_fault(Action::fault_power_cycle, n.index);
    ++res.special["recommissioned (" + n.layout_numbers() + " restored, power cycle)"];
  }

  void check_layouts(Time t) {
    for (Node& n : nodes) {
      if (n.layout.empty() || !n.pcp) continue;
      if (n.check_layout) {
        n.check_layout = false;
        if (n.profile->layout_mismatch(sim->emulator(n.index)) != n.layout_expected_mismatch) {
          std::string values;
          for (const auto& l : n.layout) {
            values += (values.empty() ? "" : " / ") + show(checker.possible(n.index, l.number, true));
          }
          checker.report(n.index, t, "layout",
                         "after a power-on with " + n.layout_numbers() + " = " + values + " the device " +
                             (n.layout_expected_mismatch ? "does not show" : "shows") + " a module error");
        }
        ++res.special["layout checks after a power-on with changed " + n.layout_numbers()];
      }
      if (n.power_cycle_at && t >= *n.power_cycle_at && !n.busy) {
        n.power_cycle_at.reset();
        // Known EEPROM values only: then the layout after the power-on is known too.
        bool known = true;
        bool mismatch = false;
        for (const auto& l : n.layout) {
          const auto v = checker.possible(n.index, l.number, true);
          known = known && v.size() == 1;
          if (v.size() == 1 && v[0] != l.configured) mismatch = true;
        }
        if (known) {
          n.check_layout = true;
          n.layout_expected_mismatch = mismatch;
        }
        sim->inject_fault(Action::fault_power_cycle, n.index);
        ++res.special["power cycles after changing " + n.layout_numbers()];
        continue;
      }
      if (n.profile->layout_mismatch(sim->emulator(n.index)) && !n.check_layout) recommission(n);
    }
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
        // The power-on latched in the error register.
        if (n.error_register && n.pcp) n.script.push_front({ParamOp::read, *n.error_register, 0, Duration{0}, ""});
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
      // A drive that booted from a reset during this stretch: the model's store follows before
      // any outcome of this cycle is checked against the device's.
      for (Node& n : nodes) {
        if (const std::uint32_t r = n.profile->software_resets(sim->emulator(n.index)); r != n.software_resets) {
          n.software_resets = r;
          checker.software_reset(n.index, t);
        }
      }
      const std::uint64_t valid_now = sim->summary().valid_cycles;
      const bool valid = valid_now > valid_before;
      valid_before = valid_now;
      process_faults();
      for (Node& n : nodes) {
        const devices::DeviceEmulator& e = sim->emulator(n.index);
        const bool me = sim->module_error(n.index, t);
        bool lost = me;
        if (e.takes_words_in_module_error() && e.module_error(t)) lost = false;  // initialising
        if (n.profile->layout_mismatch(e)) lost = true;
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
        const devices::DeviceEmulator& e = sim->emulator(n.index);
        const bool tripped = e.watchdog_tripped();
        checker.observe(n.index, t, s, tripped, e.error_number().has_value());
        if (traced && *traced == n.index && (s != n.last_state || tripped != n.tripped_trace)) {
          n.tripped_trace = tripped;
          trace(n, t, "state " + std::string(drivecom::to_string(s)) + (tripped ? " (watchdog tripped)" : ""));
        }
        n.last_state = s;
      }
      checker.check_overdue(t);
      if (!more || res.transactions >= opt.transactions) break;
      check_layouts(t);
      // Traffic and commands.
      for (Node& n : nodes) {
        if (!n.busy && t >= n.pause_until && !n.power_cycle_at && n.pcp && !sim->driver(n.index).parameters().closing()) {
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
