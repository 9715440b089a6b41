// The meaning of a scenario: ranges, names, device kinds and layouts, the INTERBUS limits and the
// timeline. One validator for both file formats and for scenarios built in code.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibs/interbus/bus_config.hpp"
#include "ibs/interbus/mc6000_layout.hpp"
#include "ibs/sim/scenario.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim::detail {

namespace {

namespace mc = interbus::mc6000;

constexpr Duration kMaxRunTime = 24h;
constexpr Duration kMaxBusTime = 1s;  // cycle and software time: more is a unit typo
constexpr int kMaxRecoveryCycles = 100;
constexpr std::size_t kMaxNameLength = 32;
constexpr int kMaxCorruptCount = 10'000;
constexpr double kMaxRatePerS = 1000.0;

// The VF1000's ID code: remote bus, profile device, 3 words, no PCP (seed 001, 3.1.2).
constexpr Word kVf1000IdCode = 0x33B;
// VF1000 parameter numbers: 10 bits, the low byte and bits 0-1 of the control byte (4.1.2.1).
constexpr int kVf1000MaxParameter = 0x3FF;
// MC6000 parameter numbers: 0..999 (seed 000, 2.4.2); PCP index = number + 5C00H (seed 001, 4.2).
constexpr int kMc6000MaxParameter = 999;
// 906-IB-WD 8..65535 ms, the maximum switching monitoring off (seed 001, 4.1.1); 409-BUTWD in ms,
// 0 = off (3.2.4), an Unsigned 16.
constexpr int kVf1000MinWatchdogMs = 8;
constexpr int kMaxWatchdogMs = 0xFFFF;
// 907-IBCOD 0..3 (4.1.1).
constexpr int kMaxWatchdogReaction = 3;
// The VF1000 reference word: 0.05 Hz per bit, an absolute value (5.2.3).
constexpr double kMaxFrequencyHz = 65535 * 0.05;
// The MC6000 reference: rpm, a signed 16-bit word or Q16 in 32 bits (3.2.3, 5.3.4).
constexpr double kMinSpeedRpm = -32768.0;
constexpr double kMaxSpeedRpm = 32767.0;

std::size_t pick(std::size_t line, std::size_t fallback) {
  return line != 0 ? line : fallback;
}

std::string action_text(const TimelineEntry& e) {
  const std::string_view fault = fault_name(e.action);
  if (!fault.empty()) return "fault = \"" + std::string(fault) + "\"";
  return "'" + std::string(to_string(e.action)) + "'";
}

bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

template <std::size_t N>
bool one_of(std::string_view v, const std::string_view (&names)[N]) {
  return std::find(std::begin(names), std::end(names), v) != std::end(names);
}

template <std::size_t N>
std::string list(const std::string_view (&names)[N]) {
  std::string out;
  for (const std::string_view n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

std::string kind_text(DeviceKind k) {
  return k == DeviceKind::vf1000 ? "VF1000" : "MC6000";
}
std::string a_kind(DeviceKind k) {
  return k == DeviceKind::vf1000 ? "a VF1000" : "an MC6000";
}

// Numbers in messages: integers without a fraction ("40000", not "40000.0").
std::string number_text(double v) {
  if (std::isfinite(v) && std::trunc(v) == v && std::abs(v) < 1e15) {
    return std::to_string(static_cast<std::int64_t>(v));
  }
  return format_number(v);
}

struct Known {
  const DeviceConfig* config = nullptr;
  std::size_t line = 0;
  std::optional<mc::Layout> layout;  // MC6000 only
};

class Validator {
 public:
  Validator(const Scenario& s, const SourceMap& m, const std::string& file)
      : s_(s), m_(m), file_(file) {}

  void run() {
    check_top();
    check_bus();
    check_devices();
    check_random();
    check_timeline();
  }

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& what) const {
    throw ScenarioError(file_, line, what);
  }

  DeviceLines device_lines(std::size_t i) const {
    return i < m_.devices.size() ? m_.devices[i] : DeviceLines{};
  }
  EntryLines entry_lines(std::size_t i) const {
    if (i < m_.entries.size()) return m_.entries[i];
    const std::size_t l = s_.timeline[i].source_line;
    return {l, l, l, l, l, l, l};
  }

  void check_top() const {
    if (s_.name.empty()) fail(pick(m_.name, m_.root), "'name' must not be empty");
    if (std::any_of(s_.name.begin(), s_.name.end(),
                    [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7F; })) {
      fail(pick(m_.name, m_.root), "'name' must not hold control characters");
    }
    if (s_.duration <= Duration::zero()) {
      fail(pick(m_.duration, m_.root), "'duration' must be longer than 0 s");
    }
    if (s_.duration > kMaxRunTime) {
      fail(pick(m_.duration, m_.root),
           "'duration' " + format_time(s_.duration) + " is longer than 24 h");
    }
  }

  void check_bus() const {
    const BusSettings& b = s_.bus;
    if (b.cycle_time) {
      const std::size_t line = pick(m_.cycle_time, m_.bus);
      if (*b.cycle_time <= Duration::zero()) fail(line, "'cycle_time' must be longer than 0 s");
      if (*b.cycle_time > kMaxBusTime) {
        fail(line, "'cycle_time' " + format_time(*b.cycle_time) +
                       " is longer than 1 s (INTERBUS cycles take milliseconds)");
      }
    }
    const std::size_t sw = pick(m_.software_time, m_.bus);
    if (b.software_time < Duration::zero()) fail(sw, "'software_time' must not be negative");
    if (b.software_time > kMaxBusTime) {
      fail(sw, "'software_time' " + format_time(b.software_time) + " is longer than 1 s");
    }
    if (b.recovery_cycles < 0 || b.recovery_cycles > kMaxRecoveryCycles) {
      fail(pick(m_.recovery_cycles, m_.bus),
           "'recovery_cycles' = " + std::to_string(b.recovery_cycles) + " is out of range (0.." +
               std::to_string(kMaxRecoveryCycles) + ")");
    }
  }

  void check_devices() {
    if (s_.devices.empty()) {
      fail(pick(m_.device_array, m_.root),
           "a scenario needs at least one device ([[device]] in TOML, \"device\": [...] in JSON)");
    }
    for (std::size_t i = 0; i < s_.devices.size(); ++i) check_device(i);
    check_bus_limits();
  }

  void check_device(std::size_t i) {
    const DeviceConfig& d = s_.devices[i];
    const DeviceLines l = device_lines(i);
    const std::size_t table = l.table;
    const std::size_t name_line = pick(l.name, table);
    if (d.name.empty()) fail(name_line, "a device name must not be empty");
    if (d.name.size() > kMaxNameLength ||
        !std::all_of(d.name.begin(), d.name.end(), is_name_char)) {
      fail(name_line, "device name '" + d.name + "' must be 1.." + std::to_string(kMaxNameLength) +
                          " letters, digits, '_' or '-'");
    }
    for (const Known& k : known_) {
      if (k.config->name == d.name) {
        fail(name_line,
             "device name '" + d.name + "' is already used (line " + std::to_string(k.line) + ")");
      }
    }
    Known known{&d, table, std::nullopt};
    const Duration period =
        d.kind == DeviceKind::vf1000 ? kVf1000SamplePeriod : kMc6000SamplePeriod;
    const std::string who = "device '" + d.name + "': ";
    if (d.kind == DeviceKind::vf1000) {
      if (d.bus == BusSide::local) {
        fail(pick(l.bus, table), who + "a VF1000 is always a remote bus device (seed 001, 1.3)");
      }
    } else {
      try {
        known.layout = mc::make_layout(
            d.supi, d.ibcnf, d.bus == BusSide::local ? mc::BusKind::local : mc::BusKind::remote);
      } catch (const mc::LayoutError& e) {
        const std::string msg = e.what();
        const bool about_supi = msg.rfind("405-SUPI", 0) == 0;
        const std::size_t first = about_supi ? l.supi : l.ibcnf;
        const std::size_t second = about_supi ? l.ibcnf : l.supi;
        fail(pick(first, pick(second, table)), who + msg);
      }
    }
    if (d.phase < Duration::zero() || d.phase >= period) {
      fail(pick(l.phase, table), who + "'phase' " + format_time(d.phase) +
                                     " must be at least 0 s and shorter than the " +
                                     kind_text(d.kind) + "'s sample period " + format_time(period));
    }
    if (d.jitter < Duration::zero() || d.jitter * 2 >= period) {
      fail(pick(l.jitter, table), who + "'jitter' " + format_time(d.jitter) +
                                      " must be at least 0 s and shorter than half the " +
                                      kind_text(d.kind) + "'s sample period (" +
                                      format_time(period / 2) + ")");
    }
    if (d.watchdog_ms) {
      const int min = d.kind == DeviceKind::vf1000 ? kVf1000MinWatchdogMs : 0;
      if (*d.watchdog_ms < min || *d.watchdog_ms > kMaxWatchdogMs) {
        fail(pick(l.watchdog_ms, table),
             who + "'watchdog_ms' = " + std::to_string(*d.watchdog_ms) + " is out of range (" +
                 std::to_string(min) + ".." + std::to_string(kMaxWatchdogMs) +
                 (d.kind == DeviceKind::vf1000 ? ", 906-IB-WD" : ", 409-BUTWD, 0 = off") + ")");
      }
    }
    if (d.watchdog_reaction) {
      const std::size_t line = pick(l.watchdog_reaction, table);
      if (d.kind != DeviceKind::vf1000) {
        fail(line, who +
                       "'watchdog_reaction' is a VF1000 setting (907-IBCOD); the MC6000 "
                       "always reports E-OP1 (seed 001, 3.2.4)");
      }
      if (*d.watchdog_reaction < 0 || *d.watchdog_reaction > kMaxWatchdogReaction) {
        fail(line, who + "'watchdog_reaction' = " + std::to_string(*d.watchdog_reaction) +
                       " is out of range (0..3, 907-IBCOD)");
      }
    }
    known_.push_back(known);
  }

  // The INTERBUS limits (devices, remote bus devices, local bus segments, PCP devices, process
  // data words) are make_bus_config's; to name the line, find the first device that breaks one.
  // Every limit only grows with the ring, so the shortest refused prefix ends at that device.
  void check_bus_limits() const {
    std::vector<interbus::DeviceSpec> ring;
    ring.reserve(s_.devices.size());
    for (const Known& k : known_) {
      const bool vf = k.config->kind == DeviceKind::vf1000;
      ring.push_back(
          {k.config->name, interbus::IdCode{vf ? kVf1000IdCode : k.layout->id_code},
           k.config->bus == BusSide::local ? interbus::BusKind::local : interbus::BusKind::remote});
    }
    const auto refused = [&](std::size_t n) -> std::optional<std::string> {
      try {
        (void)interbus::make_bus_config(std::span(ring).first(n));
        return std::nullopt;
      } catch (const interbus::ConfigError& e) {
        return std::string(e.what());
      }
    };
    if (!refused(ring.size())) return;
    std::size_t lo = 1;
    std::size_t hi = ring.size();
    while (lo < hi) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (refused(mid)) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
    fail(known_[lo - 1].line, *refused(lo));
  }

  void check_random() const {
    const RandomFaults& r = s_.random;
    if (r.seed > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      fail(pick(m_.seed, m_.random), "'seed' must be 0..2^63-1 (a TOML integer)");
    }
    const std::pair<double, std::string_view> rates[] = {
        {r.corrupt_per_s, "corrupt_per_s"},
        {r.power_cycle_per_s, "power_cycle_per_s"},
        {r.device_fault_per_s, "device_fault_per_s"},
        {r.lost_per_s, "lost_per_s"},
        {r.master_restart_per_s, "master_restart_per_s"}};
    for (std::size_t i = 0; i < std::size(rates); ++i) {
      const auto [rate, key] = rates[i];
      if (!std::isfinite(rate) || rate < 0.0 || rate > kMaxRatePerS) {
        fail(pick(m_.rates[i], m_.random), "'" + std::string(key) + "' = " + number_text(rate) +
                                               " is out of range (0..1000 per second)");
      }
    }
  }

  const Known* find(std::string_view name) const {
    const auto it = std::find_if(known_.begin(), known_.end(),
                                 [&](const Known& k) { return k.config->name == name; });
    return it == known_.end() ? nullptr : &*it;
  }

  std::string device_list() const {
    std::string out;
    for (const Known& k : known_) out += (out.empty() ? "" : ", ") + k.config->name;
    return out;
  }

  void check_timeline() const {
    for (std::size_t i = 0; i < s_.timeline.size(); ++i) {
      const TimelineEntry& e = s_.timeline[i];
      const EntryLines l = entry_lines(i);
      const std::size_t at_line = pick(l.at, l.table);
      if (e.at < Duration::zero()) fail(at_line, "'at' must not be negative");
      if (e.at > s_.duration) {
        fail(at_line, "'at' = " + format_time(e.at) + " is after the end of the run ('duration' " +
                          format_time(s_.duration) + ")");
      }
      if (i > 0 && e.at < s_.timeline[i - 1].at) {
        fail(at_line, "'at' = " + format_time(e.at) + " is earlier than the entry before it (" +
                          format_time(s_.timeline[i - 1].at) + ", line " +
                          std::to_string(entry_lines(i - 1).table) +
                          "): the timeline is written in time order");
      }
      check_entry(e, l);
    }
  }

  void check_entry(const TimelineEntry& e, const EntryLines& l) const {
    const std::size_t action_line = pick(l.action, l.table);
    const std::string what = action_text(e);
    const bool bus_wide = e.action == Action::fault_corrupt || e.action == Action::master_restart;
    if (bus_wide) {
      if (!e.device.empty()) {
        fail(pick(l.device, l.table), what + " is bus-wide: it takes no 'device'");
      }
    } else if (e.device.empty()) {
      fail(l.table, what + " needs a 'device'");
    }
    const Known* k = bus_wide ? nullptr : find(e.device);
    if (!bus_wide && k == nullptr) {
      fail(pick(l.device, l.table),
           "unknown device '" + e.device + "' (devices: " + device_list() + ")");
    }
    const DeviceKind kind = k != nullptr ? k->config->kind : DeviceKind::mc6000;
    const std::string who = "device '" + e.device + "'";
    const auto& layout = k != nullptr ? k->layout : std::optional<mc::Layout>{};
    const std::string supi_text = layout ? " (405-SUPI " + std::to_string(layout->supi) : "";

    const auto need_control_word = [&] {
      if (layout && (!layout->exchanges_data || layout->pd_words < 1)) {
        fail(action_line, who + " has no control word" + supi_text +
                              (layout->exchanges_data ? ": PCP only)" : ": no data exchange)") +
                              ", so " + what + " cannot reach it");
      }
    };
    const auto need_parameter_channel = [&] {
      if (layout && layout->pcp_words == 0) {
        fail(action_line,
             who + " has no PCP channel" + supi_text + "), so " + what + " cannot reach it");
      }
      const int max = kind == DeviceKind::vf1000 ? kVf1000MaxParameter : kMc6000MaxParameter;
      if (e.parameter > max) {
        fail(pick(l.parameter, action_line),
             "parameter " + std::to_string(e.parameter) + " is out of range for the " +
                 kind_text(kind) + " " + who + " (0.." + std::to_string(max) +
                 (kind == DeviceKind::vf1000 ? ", 10-bit PNR, seed 001 4.1.2.1)"
                                             : ", seed 000 2.4.2)"));
      }
    };
    const auto only_for = [&](DeviceKind wanted, std::string_view instead) {
      if (kind != wanted) {
        fail(action_line, what + " is " + a_kind(wanted) + " action, but " + who + " is " +
                              a_kind(kind) + " (use '" + std::string(instead) + "')");
      }
    };
    const auto finite = [&](double v, std::size_t line) {
      if (!std::isfinite(v)) fail(line, what + " needs a finite number");
    };

    switch (e.action) {
      case Action::state:
        need_control_word();
        if (!one_of(e.value, kTargetStates)) {
          fail(action_line,
               "'state' = \"" + e.value + "\" is not a target state (" + list(kTargetStates) + ")");
        }
        break;
      case Action::wait_state:
        need_control_word();
        if (!one_of(e.value, kWaitStates)) {
          fail(action_line, "'wait_state' = \"" + e.value + "\" is not a DRIVECOM state (" +
                                list(kWaitStates) + ")");
        }
        if (e.duration < Duration::zero()) {
          fail(pick(l.modifier, action_line), "'timeout' must not be negative");
        }
        break;
      case Action::emergency_stop:
      case Action::block_power:
        need_control_word();
        break;
      case Action::speed:
        only_for(DeviceKind::mc6000, "frequency");
        finite(e.number, action_line);
        if (layout && (!layout->exchanges_data || layout->reference_words == 0)) {
          fail(action_line, who + " carries no speed reference (406-IBCNF " +
                                std::to_string(static_cast<int>(layout->ibcnf)) + ", 405-SUPI " +
                                std::to_string(layout->supi) + ")");
        }
        if (e.number < kMinSpeedRpm || e.number > kMaxSpeedRpm) {
          fail(action_line,
               "'speed' = " + number_text(e.number) + " rpm is out of range (-32768..32767 rpm)");
        }
        break;
      case Action::frequency:
        only_for(DeviceKind::vf1000, "speed");
        finite(e.number, action_line);
        if (std::abs(e.number) > kMaxFrequencyHz) {
          fail(action_line, "'frequency' = " + number_text(e.number) +
                                " Hz is out of range (-3276.75..3276.75 Hz, 0.05 Hz per bit)");
        }
        break;
      case Action::read:
      case Action::describe:
        need_parameter_channel();
        break;
      case Action::write: {
        need_parameter_channel();
        const std::size_t value_line = pick(l.value, action_line);
        finite(e.number, value_line);
        const bool vf = kind == DeviceKind::vf1000;
        const double min = vf ? -32768.0 : -2147483648.0;
        const double max = vf ? 65535.0 : 4294967295.0;
        if (e.number != std::trunc(e.number)) {
          fail(value_line, "write's 'value' = " + number_text(e.number) +
                               " must be an integer (the raw value)");
        }
        if (e.number < min || e.number > max) {
          fail(value_line, "write's 'value' = " + number_text(e.number) +
                               " is out of range for the " + kind_text(kind) +
                               (vf ? " (-32768..65535, 16 bits)" : " (-2^31..2^32-1, 32 bits)"));
        }
        break;
      }
      case Action::fault_corrupt:
        if (e.count < 1 || e.count > kMaxCorruptCount) {
          fail(pick(l.modifier, action_line), "'count' = " + std::to_string(e.count) +
                                                  " is out of range (1.." +
                                                  std::to_string(kMaxCorruptCount) + ")");
        }
        break;
      case Action::fault_device:
        if (e.duration < Duration::zero()) {
          fail(pick(l.modifier, action_line), "'duration' must not be negative");
        }
        break;
      case Action::fault_lost:
        if (e.duration <= Duration::zero()) {
          fail(pick(l.modifier, action_line),
               "fault = \"lost\" needs a 'duration' longer than 0 s");
        }
        break;
      case Action::fault_power_cycle:
      case Action::master_restart:
        break;
    }
  }

  const Scenario& s_;
  const SourceMap& m_;
  const std::string& file_;
  std::vector<Known> known_;
};

}  // namespace

void validate(const Scenario& s, const SourceMap& lines, const std::string& file) {
  Validator(s, lines, file).run();
}

}  // namespace ibs::sim::detail
