// `ibs timing`: the cycle time of a ring of drives with every term of the formula, and the
// worst-case reaction and recovery times that follow from it (docs/bus.md, "Cycle time").
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "bus_commands.hpp"
#include "commands.hpp"
#include "ibs/interbus/bus_config.hpp"
#include "ibs/interbus/cycle_time.hpp"
#include "ibs/interbus/id_code.hpp"
#include "ibs/devices/registry.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::cli {

namespace {

using Json = nlohmann::ordered_json;


// A device argument that does not parse; the message names it.
class SpecError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct RingEntry {
  std::string spec;  // as given
  interbus::DeviceSpec device;
  devices::RingEntry entry;  // the drive's settings and note
};

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  for (;;) {
    const auto pos = s.find(sep);
    parts.push_back(s.substr(0, pos));
    if (pos == std::string_view::npos) return parts;
    s.remove_prefix(pos + 1);
  }
}

// NAME[:FIELD...], the fields as the drive kind takes them (DriveFacts::timing_syntax).
RingEntry parse_device(const std::string& spec) {
  const auto fail = [&spec](const std::string& why) {
    return SpecError("ibs timing: device '" + spec + "': " + why);
  };
  const std::vector<std::string_view> f = split(spec, ':');
  const devices::DriveKind* kind = devices::find_drive_kind(f[0]);
  if (kind == nullptr) {
    std::string syntaxes;
    const auto kinds = devices::drive_kinds();
    for (std::size_t i = 0; i < kinds.size(); ++i) {
      if (i > 0) syntaxes += i + 1 == kinds.size() ? " or " : ", ";
      syntaxes += std::string(kinds[i]->facts().timing_syntax);
    }
    throw fail("unknown device, expected " + syntaxes);
  }
  RingEntry e;
  e.spec = spec;
  try {
    e.entry = (*kind)->ring_entry(std::span(f).subspan(1));
  } catch (const devices::SettingsError& x) {
    throw fail(x.what());
  }
  e.device = {std::string((*kind)->name()), e.entry.id_code, e.entry.bus};
  return e;
}

std::vector<RingEntry> parse_ring(const std::vector<std::string>& specs) {
  std::vector<RingEntry> ring;
  std::map<std::string, int> seen;
  for (const std::string& s : specs.empty() ? default_timing_ring() : specs) {
    RingEntry e = parse_device(s);
    // Unique names in ring order: mc6000, mc6000_2, ...
    const int n = ++seen[e.device.name];
    if (n > 1) e.device.name += "_" + std::to_string(n);
    ring.push_back(std::move(e));
  }
  return ring;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string words(std::size_t n) {
  return std::to_string(n) + (n == 1 ? " word" : " words");
}

struct Timing {
  std::vector<RingEntry> ring;
  interbus::BusConfig config;
  interbus::CycleTimeParams params;
  std::string baud;  // "500k", "2M"
  double line_bits = 0.0;
  Duration line_time{0};
  Duration cycle{0};
  Duration reaction{0};
  Duration recovery{0};
};

void print_text(const Timing& t, std::ostream& out) {
  const interbus::CycleTimeParams& p = t.params;
  const std::size_t n = t.config.ring_bytes();
  const std::size_t m = t.config.remote_devices;
  std::size_t spec_width = 4;
  std::size_t name_width = 4;
  for (const RingEntry& e : t.ring) {
    spec_width = std::max(spec_width, e.spec.size());
    name_width = std::max(name_width, e.device.name.size());
  }
  out << "ring (position 0 = the first device after the master):\n";
  for (std::size_t i = 0; i < t.ring.size(); ++i) {
    const interbus::Device& d = t.config.devices[i];
    out << "  " << i << "  " << std::left << std::setw(static_cast<int>(name_width)) << d.name
        << "  " << std::setw(static_cast<int>(spec_width)) << t.ring[i].spec << std::right << "  "
        << interbus::to_hex(d.id) << "  " << interbus::to_string(d.bus) << "  "
        << words(d.ring_words) << " (" << d.ring_words - d.pcp_words << " process data + "
        << d.pcp_words << " PCP)";
    if (!t.ring[i].entry.note.empty()) out << ", " << t.ring[i].entry.note;
    out << "\n";
  }
  out << "T_cycle = SW + (" << format_number(p.line_bits_per_byte) << " * ("
      << format_number(p.overhead_bytes) << " + N) + " << format_number(p.bits_per_remote_device)
      << " * M) * T_bit\n";
  out << "  N       = " << n << " bytes (" << words(t.config.ring_words)
      << " on the ring, PCP included)\n";
  out << "  M       = " << m << " remote bus " << (m == 1 ? "device" : "devices") << "\n";
  out << "  T_bit   = " << format_us(p.bit_time) << " us ("
      << (t.baud == "2M" ? "2 Mbit/s" : "500 kbit/s") << ")\n";
  out << "  SW      = " << format_us(p.software_time) << " us\n";
  out << "  line    = " << format_number(p.line_bits_per_byte) << " * ("
      << format_number(p.overhead_bytes) << " + " << n << ") + "
      << format_number(p.bits_per_remote_device) << " * " << m << " = "
      << format_number(t.line_bits) << " bit times = " << format_us(t.line_time) << " us\n";
  out << "  T_cycle = " << format_us(p.software_time) << " us + " << format_us(t.line_time)
      << " us = " << format_ms(t.cycle) << " ms\n";
  out << "worst-case reaction time: " << interbus::kReactionCycles
      << " cycles = " << format_ms(t.reaction) << " ms\n";
  out << "recovery after a transmission error: " << interbus::kRecoveryCycles
      << " cycles = " << format_ms(t.recovery) << " ms\n";
}

void print_json(const Timing& t, std::ostream& out) {
  Json devices = Json::array();
  for (std::size_t i = 0; i < t.ring.size(); ++i) {
    const interbus::Device& d = t.config.devices[i];
    Json j{{"position", d.ring_position},
           {"name", d.name},
           {"spec", t.ring[i].spec},
           {"id_code", interbus::to_hex(d.id)},
           {"id_code_value", d.id.raw},
           {"bus", d.bus == interbus::BusKind::local ? "local" : "remote"},
           {"ring_words", d.ring_words},
           {"pd_words", d.ring_words - d.pcp_words},
           {"pcp_words", d.pcp_words}};
    for (const devices::ReportedSetting& r : t.ring[i].entry.settings) {
      if (r.number) {
        j[r.key] = *r.number;
      } else {
        j[r.key] = r.text;
      }
    }
    devices.push_back(j);
  }
  const Json j{
      {"devices", devices},
      {"baud", t.baud},
      {"data_bytes", t.config.ring_bytes()},
      {"ring_words", t.config.ring_words},
      {"remote_devices", t.config.remote_devices},
      {"bit_time_ns", t.params.bit_time.count()},
      {"software_time_ns", t.params.software_time.count()},
      {"line_bits", t.line_bits},
      {"line_time_ns", t.line_time.count()},
      {"cycle_time_ns", t.cycle.count()},
      {"cycle_time_ms", to_ms(t.cycle)},
      {"reaction_cycles", interbus::kReactionCycles},
      {"reaction_time_ns", t.reaction.count()},
      {"reaction_time_ms", to_ms(t.reaction)},
      {"recovery_cycles", interbus::kRecoveryCycles},
      {"recovery_time_ns", t.recovery.count()},
      {"recovery_time_ms", to_ms(t.recovery)},
  };
  out << j.dump(2) << "\n";
}

}  // namespace

// docs/bus.md's worked example, `mc6000:11 vf1000`.
std::vector<std::string> default_timing_ring() {
  std::vector<std::string> ring;
  for (const sim::DeviceConfig& d : sim::default_scenario().devices) {
    ring.push_back((*devices::find_drive_kind(d.kind))->ring_spec(sim::device_settings(d)));
  }
  return ring;
}

int timing_command(const TimingOptions& o, std::ostream& out, std::ostream& err) {
  Timing t;
  const std::string baud = lower(o.baud);
  if (baud == "500k") {
    t.baud = "500k";
    t.params = interbus::params_for(interbus::BaudRate::kbit500);
  } else if (baud == "2m") {
    t.baud = "2M";
    t.params = interbus::params_for(interbus::BaudRate::mbit2);
  } else {
    err << "ibs timing: --baud '" << o.baud << "' is neither 500k nor 2M\n";
    return kExitBadInput;
  }
  if (o.software_time_us) {
    const double us = *o.software_time_us;
    if (!std::isfinite(us) || us < 0.0 || us > 1e9) {
      err << "ibs timing: --sw-us " << format_number(us)
          << " is not a software time in microseconds (0 .. 1e9)\n";
      return kExitBadInput;
    }
    t.params.software_time = Duration{std::llround(us * 1000.0)};
  }
  try {
    t.ring = parse_ring(o.devices);
    std::vector<interbus::DeviceSpec> specs;
    specs.reserve(t.ring.size());
    for (const RingEntry& e : t.ring) specs.push_back(e.device);
    t.config = interbus::make_bus_config(specs);
  } catch (const SpecError& e) {
    err << e.what() << "\n";
    return kExitBadInput;
  } catch (const interbus::ConfigError& e) {
    err << "ibs timing: " << e.what() << "\n";
    return kExitBadInput;
  }
  const interbus::RingLoad load = interbus::ring_load(t.config);
  t.line_bits = t.params.line_bits_per_byte *
                    (t.params.overhead_bytes + static_cast<double>(load.data_bytes)) +
                t.params.bits_per_remote_device * static_cast<double>(load.remote_devices);
  t.cycle = interbus::cycle_time(load, t.params);
  t.line_time = t.cycle - t.params.software_time;
  t.reaction = interbus::worst_case_reaction_time(t.cycle);
  t.recovery = interbus::recovery_time(t.cycle);
  if (o.json) {
    print_json(t, out);
  } else {
    print_text(t, out);
  }
  return kExitOk;
}

int timing_command(const TimingOptions& options) {
  return timing_command(options, std::cout, std::cerr);
}

}  // namespace ibs::cli
