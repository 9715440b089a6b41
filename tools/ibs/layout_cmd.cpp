// `ibs layout`: a drive's ID code and the meaning of each of its process-data words, as the drive
// kind's descriptor gives them (devices/descriptor.hpp): the MC6000's by 405-SUPI / 406-IBCNF,
// the VF1000's three words.
#include <array>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bus_commands.hpp"
#include "commands.hpp"
#include "ibs/interbus/bus_config.hpp"
#include "ibs/interbus/cycle_time.hpp"
#include "ibs/interbus/id_code.hpp"
#include "ibs/devices/registry.hpp"

namespace ibs::cli {

namespace {

using Json = nlohmann::ordered_json;

// What one device adds to T_cycle: its bytes to N, 1 to M on the remote bus, and the line time
// of those bits at each baud rate.
struct CycleShare {
  std::size_t data_bytes = 0;
  std::size_t remote_devices = 0;
  double line_bits = 0.0;
  Duration at_500k{0};
  Duration at_2m{0};
};

struct LayoutReport {
  std::string device;  // the drive kind's name
  devices::LayoutDescription layout;  // the drive's words (its descriptor)
  interbus::Device placed;  // the device as a one-device bus configuration places it
  CycleShare share;
};

const char* bus_name(interbus::BusKind b) {
  return b == interbus::BusKind::local ? "local" : "remote";
}

CycleShare cycle_share(const interbus::BusConfig& c) {
  CycleShare s;
  const interbus::RingLoad load = interbus::ring_load(c);
  const interbus::CycleTimeParams p500 = interbus::params_for(interbus::BaudRate::kbit500);
  const interbus::CycleTimeParams p2m = interbus::params_for(interbus::BaudRate::mbit2);
  s.data_bytes = load.data_bytes;
  s.remote_devices = load.remote_devices;
  s.line_bits = p500.line_bits_per_byte * static_cast<double>(load.data_bytes) +
                p500.bits_per_remote_device * static_cast<double>(load.remote_devices);
  // The difference to an empty ring: the formula's own rounding, SW and overhead cancel.
  s.at_500k = interbus::cycle_time(load, p500) - interbus::cycle_time(interbus::RingLoad{}, p500);
  s.at_2m = interbus::cycle_time(load, p2m) - interbus::cycle_time(interbus::RingLoad{}, p2m);
  return s;
}

void place(LayoutReport& r, const std::string& name, interbus::IdCode id, interbus::BusKind bus) {
  const std::array<interbus::DeviceSpec, 1> ring{{{name, id, bus}}};
  const interbus::BusConfig c = interbus::make_bus_config(ring);
  r.placed = c.devices.front();
  r.share = cycle_share(c);
}

Json words_json(const std::vector<devices::WordMeaning>& words) {
  Json a = Json::array();
  for (const devices::WordMeaning& w : words) {
    a.push_back(Json{{"word", w.word}, {"role", w.role}, {"meaning", w.meaning}});
  }
  return a;
}

void print_json(const LayoutReport& r, std::ostream& out) {
  Json j;
  j["device"] = r.device;
  for (const devices::ReportedSetting& x : r.layout.settings) {
    if (x.number) {
      j[x.key] = *x.number;
    } else {
      j[x.key] = x.text;
    }
  }
  j["bus"] = bus_name(r.placed.bus);
  j["id_code"] = interbus::to_hex(r.placed.id);
  j["id_code_value"] = r.placed.id.raw;
  j["id_code_description"] = interbus::describe(r.placed.id);
  j["exchanges_data"] = r.layout.exchanges_data;
  j["ring_words"] = r.placed.ring_words;
  j["pd_words"] = r.placed.ring_words - r.placed.pcp_words;
  j["pcp_words"] = r.placed.pcp_words;
  j["output_words"] = words_json(r.layout.out_words);
  j["input_words"] = words_json(r.layout.in_words);
  j["pcp"] = r.layout.pcp;
  j["cycle_time_contribution"] = Json{
      {"data_bytes", r.share.data_bytes},    {"remote_devices", r.share.remote_devices},
      {"line_bits", r.share.line_bits},      {"time_ns_500k", r.share.at_500k.count()},
      {"time_ns_2m", r.share.at_2m.count()},
  };
  out << j.dump(2) << "\n";
}

void print_words(const std::vector<devices::WordMeaning>& words, std::ostream& out) {
  if (words.empty()) out << "  no process data (every word is PCP)\n";
  for (const devices::WordMeaning& w : words) {
    out << "  word " << w.word << "  " << w.meaning << "\n";
  }
}

void print_text(const LayoutReport& r, std::ostream& out) {
  const interbus::Device& d = r.placed;
  out << r.layout.title << "\n";
  out << "ID code " << interbus::describe(d.id) << "\n";
  out << "on the ring: " << d.ring_words << (d.ring_words == 1 ? " word" : " words") << " ("
      << d.ring_words - d.pcp_words << " process data + " << d.pcp_words << " PCP), "
      << bus_name(d.bus) << " bus\n";
  out << "master -> device (output image):\n";
  print_words(r.layout.out_words, out);
  out << "device -> master (input image):\n";
  print_words(r.layout.in_words, out);
  out << "PCP channel: " << r.layout.pcp << "\n";
  const interbus::CycleTimeParams p;
  out << "cycle time contribution: N += " << r.share.data_bytes
      << " bytes, M += " << r.share.remote_devices << ": " << format_number(p.line_bits_per_byte)
      << " * " << r.share.data_bytes << " + " << format_number(p.bits_per_remote_device) << " * "
      << r.share.remote_devices << " = " << format_number(r.share.line_bits)
      << " bit times = " << format_us(r.share.at_500k) << " us at 500 kbit/s, "
      << format_us(r.share.at_2m) << " us at 2 Mbit/s\n";
}

}  // namespace

int layout_command(const LayoutOptions& o, std::ostream& out, std::ostream& err) {
  const devices::DriveKind* kind = devices::find_drive_kind(o.device);
  if (kind == nullptr) {
    err << "ibs layout: unknown device '" << o.device << "' (" << devices::drive_kind_names(", ", " or ") << ")\n";
    return kExitBadInput;
  }
  const devices::DriveDescriptor& d = **kind;
  if (const auto refusal = d.check_layout_options(o.settings, o.bus.has_value())) {
    err << "ibs layout: " << *refusal << "\n";
    return kExitBadInput;
  }
  devices::DeviceSettings settings;
  settings.drive = o.settings;
  if (o.bus) {
    if (*o.bus == "local") {
      settings.bus = interbus::BusKind::local;
    } else if (*o.bus != "remote") {
      err << "ibs layout: --bus '" << *o.bus << "' is neither local nor remote\n";
      return kExitBadInput;
    }
  }
  try {
    const devices::Configuration c = d.configure(settings);
    LayoutReport r;
    r.device = std::string(d.name());
    r.layout = d.layout(c);
    place(r, r.device, c.id_code, c.bus);
    if (o.json) {
      print_json(r, out);
    } else {
      print_text(r, out);
    }
    return kExitOk;
  } catch (const devices::SettingsError& e) {
    err << "ibs layout: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const interbus::ConfigError& e) {
    err << "ibs layout: " << e.what() << "\n";
    return kExitBadInput;
  }
}

int layout_command(const LayoutOptions& options) {
  return layout_command(options, std::cout, std::cerr);
}

}  // namespace ibs::cli
