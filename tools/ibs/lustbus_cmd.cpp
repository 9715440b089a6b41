// The CLI11 wiring of `ibs lustbus ...` (the emulator serves with serial::serve, the host commands
// ask through serial::transact) and the file side of `ibs decode` for a byte log
// (lustbus::read_byte_log).
#include "lustbus_cmd.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <fstream>
#include <filesystem>
#include <stdexcept>

#include "line_outputs.hpp"
#include "watched_line_device.hpp"
#include "ibs/control/channel.hpp"
#include "ibs/base/text_file.hpp"
#include "ibs/base/time_text.hpp"
#include "ibs/devices/plant_event.hpp"
#include "ibs/devices/drives.hpp"
#include "ibs/lustbus/byte_log.hpp"
#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/served_receiver.hpp"
#include "ibs/lustbus/value.hpp"
#include "ibs/lustbus/siof.hpp"
#include "ibs/lustbus/telegram.hpp"
#include "ibs/serial/byte_log.hpp"
#include "ibs/serial/lustbus_host.hpp"
#include "ibs/serial/pty.hpp"
#include "ibs/serial/serve.hpp"
#include "ibs/tool/format.hpp"
#include "stop_signals.hpp"

namespace ibs::cli {

namespace lb = ::ibs::lustbus;

namespace {

// 2.1: 7 data bits, even parity, one stop bit; RS-485 direction by the driver where it can.
serial::PortOptions port_options(const LustbusPortOptions& o) {
  serial::PortOptions p;
  p.baud = o.baud;
  p.framing = serial::k7E1;
  p.rs485 = true;
  return p;
}

struct BadInput : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// A parameter as the command line needs it: the drive's table (its LUSTBUS face in the registry)
// and the protocol family it is asked in.
struct Param : devices::LustbusParameter {
  lb::Family family = lb::Family::standard;
};

std::int64_t number_of(lb::DataType t, std::uint32_t bits) {
  switch (t) {
    case lb::DataType::integer16:
      return static_cast<std::int16_t>(bits);
    case lb::DataType::int32q16:
    case lb::DataType::float_ieee:
    case lb::DataType::mc_error:
      return static_cast<std::int32_t>(bits);
    default:
      return bits;
  }
}

std::uint32_t bits_of(lb::DataType t, std::int64_t n) {
  const unsigned w = lb::width_bits(t);
  const auto u = static_cast<std::uint64_t>(n);
  return static_cast<std::uint32_t>(w == 32 ? (u & 0xFFFFFFFFULL) : (u & ((1ULL << w) - 1ULL)));
}

// The drive a name gives, from the registry's LUSTBUS faces.
const devices::LustbusFace& parse_face(const std::string& s) {
  const devices::Drive* d = devices::find_drive(s, devices::Bus::lustbus);
  if (d == nullptr) {
    throw BadInput("--device '" + s + "': expected " + devices::drive_names(devices::Bus::lustbus, ", ", " or "));
  }
  return *d->lustbus;
}

bool parse_uint(const std::string& s, unsigned& v) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return !s.empty() && r.ec == std::errc{} && r.ptr == s.data() + s.size();
}

// The registered drive whose LUSTBUS face offers a dataset download (11.4); a build without one is
// a broken registry.
const devices::Drive& download_drive() {
  for (const devices::Drive* d : devices::drives_on(devices::Bus::lustbus)) {
    if (d->lustbus->procedures != nullptr && d->lustbus->procedures->download) return *d;
  }
  throw std::logic_error("no LUSTBUS drive offers a dataset download (LUSTBUS manual 11.4)");
}

// PARAM by number or by name (case-sensitive, as the tables spell it), from the drive's face.
Param find_param(const devices::LustbusFace& face, const std::string& text) {
  if (auto p = face.find_parameter(text)) {
    Param r;
    static_cast<devices::LustbusParameter&>(r) = std::move(*p);
    r.family = face.family;
    return r;
  }
  throw BadInput("parameter '" + text + "': the " + std::string(lb::to_string(face.family)) +
                 " has no such parameter" + std::string(face.parameter_numbers));
}

std::string label(const Param& p) { return std::to_string(p.number) + "-" + p.name; }

using lb::engineering_text;

lb::Code value_code(const Param& p, bool description) {
  const auto c = lb::parameter_code(p.family, p.number, description);
  if (!c) throw BadInput("parameter " + label(p) + " has no CODE");
  return *c;
}

// VALUE text -> the type's bit pattern, checked against the parameter's limits.
std::uint32_t parse_value(const Param& p, const std::string& text, bool check_limits = true) {
  std::uint32_t bits = 0;
  if (text.rfind("0x", 0) == 0 || text.rfind("0X", 0) == 0) {
    const std::string hex = text.substr(2);
    std::uint64_t v = 0;
    const auto r = std::from_chars(hex.data(), hex.data() + hex.size(), v, 16);
    if (hex.empty() || r.ec != std::errc{} || r.ptr != hex.data() + hex.size() ||
        v >> lb::width_bits(p.type) != 0) {
      throw BadInput(label(p) + ": raw value '" + text + "' is not a " +
                     std::to_string(lb::width_bits(p.type)) + "-bit hex number");
    }
    bits = static_cast<std::uint32_t>(v);
  } else {
    double v = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || r.ec != std::errc{} || r.ptr != text.data() + text.size()) {
      throw BadInput(label(p) + ": value '" + text + "' is not a number (raw values take 0x)");
    }
    const auto b = lb::from_engineering(p.type, v);
    if (!b.ok()) {
      throw BadInput(label(p) + ": value " + text + " does not fit " +
                     std::string(lb::to_string(p.type)) + " (" +
                     std::string(lb::to_string(b.error)) + ")");
    }
    bits = b.value;
  }
  if (check_limits && p.type != lb::DataType::float_ieee) {
    const std::int64_t n = number_of(p.type, bits);
    if (n < p.min) {
      throw BadInput(label(p) + ": value " + text + " is below the minimum " +
                     engineering_text(p.type, bits_of(p.type, p.min)));
    }
    if (n > p.max) {
      throw BadInput(label(p) + ": value " + text + " is above the maximum " +
                     engineering_text(p.type, bits_of(p.type, p.max)));
    }
  }
  return bits;
}

lb::Value format_value(const Param& p, std::uint32_t bits) {
  const auto v = lb::format_typed(p.family, p.type, bits);
  if (!v.ok()) throw BadInput(label(p) + ": the value cannot be sent as a VALUE");
  return v.value;
}

// One request through the host loop on the port (serial/lustbus_host.hpp); a request the host
// refuses is bad input.
lb::Outcome ask(serial::SerialPort& port, lb::Host& host, const lb::Request& request) {
  try {
    return serial::transact(port, host, request);
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
}

// "vf1000@ADDR or mc6000@ADDR": the registry's LUSTBUS drives.
std::string device_forms() { return devices::drive_names(devices::Bus::lustbus, ", ", " or ", "@ADDR"); }

// "vf1000@3" -> (the drive's face, 3); throws naming the text.
std::pair<const devices::LustbusFace*, lb::Address> parse_device(const std::string& spec) {
  const auto at = spec.find('@');
  const auto bad = [&]() { return BadInput("device '" + spec + "': expected " + device_forms() + ", ADDR 1..30"); };
  if (at == std::string::npos) throw bad();
  const devices::Drive* d = devices::find_drive(spec.substr(0, at), devices::Bus::lustbus);
  unsigned a = 0;
  if (d == nullptr || !parse_uint(spec.substr(at + 1), a) || a < 1 || a > 30) throw bad();
  return {d->lustbus, static_cast<lb::Address>(a)};
}

// One served drive as the control channel names it: `NAME@ADDR` as given, or the address.
struct ControlledDrive {
  std::string spec;
  lb::Address address = 0;
  const devices::DriveFacts* facts = nullptr;  // its descriptor's facts (EventFacts), if any
  devices::LustbusEmulated* drive = nullptr;
};

// A control line's event for one drive, and when a device fault's cause goes (duration).
struct ControlEvent {
  std::size_t drive = 0;
  devices::PlantEvent event;
  std::optional<Duration> clear_after;
  std::string text;  // what happened, for the one line on stderr
};

// Reads one line of `emulate --control`: the timeline's keys for the events that make sense
// without a master (device fault with cause and duration, power cycle, mains, load, input), the
// same words as the scenario files (docs/scenarios.md). Throws std::invalid_argument with what
// is wrong.
ControlEvent parse_emulate_control(std::string_view text, std::span<const ControlledDrive> drives) {
  using nlohmann::json;
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    // A syntax error, or a number no double holds (out_of_range.406, "1e400"): the line is bad,
    // the emulator goes on. nlohmann's text begins "[json.exception....] ".
    std::string what = e.what();
    if (const auto at = what.find("] "); !what.empty() && what.front() == '[' && at != std::string::npos) {
      what.erase(0, at + 2);
    }
    throw std::invalid_argument("not a JSON object: " + what);
  }
  if (!j.is_object()) throw std::invalid_argument("a control line must be a JSON object");
  const auto string_of = [&](const char* key) {
    if (!j[key].is_string()) throw std::invalid_argument(std::string("'") + key + "' must be a string");
    return j[key].get<std::string>();
  };
  ControlEvent c;
  std::string action;
  for (const auto& item : j.items()) {
    const std::string& key = item.key();
    if (key == "at") throw std::invalid_argument("control entries apply at once: no 'at'");
    if (key == "fault" || key == "mains" || key == "load" || key == "input" || key == "smartcard" ||
        key == "option_card") {
      if (!action.empty()) {
        throw std::invalid_argument("a control line holds one action: '" + action + "' and '" + key + "'");
      }
      action = key;
    } else if (key != "device" && key != "cause" && key != "duration" && key != "level") {
      throw std::invalid_argument("unknown key '" + key +
                                  "' (the emulator takes: device, fault, cause, duration, mains, load, input, level, "
                                  "smartcard, option_card)");
    }
  }
  if (action.empty()) {
    throw std::invalid_argument("a control line needs an action: fault, mains, load, input, smartcard or option_card");
  }
  // Which drive: its address, or NAME@ADDR as given on the command line; alone, it may go unsaid.
  if (!j.contains("device")) {
    if (drives.size() != 1) throw std::invalid_argument("give 'device' (the drive's address or NAME@ADDR)");
  } else {
    const json& d = j["device"];
    bool found = false;
    for (std::size_t i = 0; i < drives.size() && !found; ++i) {
      if ((d.is_number_unsigned() && d.get<unsigned>() == drives[i].address) ||
          (d.is_string() && d.get<std::string>() == drives[i].spec)) {
        c.drive = i;
        found = true;
      }
    }
    if (!found) {
      std::string known;
      for (const ControlledDrive& x : drives) known += (known.empty() ? "" : ", ") + x.spec;
      throw std::invalid_argument("unknown device " + d.dump() + " (served: " + known + ")");
    }
  }
  const ControlledDrive& who = drives[c.drive];
  const devices::EventFacts none{};
  const devices::EventFacts& facts = who.facts != nullptr ? who.facts->events : none;
  const std::string title = who.facts != nullptr ? std::string(who.facts->title) : who.spec;
  const auto only_with = [&](const char* key, const char* with) {
    if (j.contains(key)) throw std::invalid_argument(std::string("'") + key + "' goes with " + with + " only");
  };
  if (action != "fault") only_with("cause", "fault = \"device\"");
  if (action != "fault" && action != "smartcard") only_with("duration", "fault = \"device\" and 'smartcard'");
  if (action != "input") only_with("level", "'input'");
  if (action == "fault") {
    const std::string fault = string_of("fault");
    if (fault == "power-cycle") {
      only_with("cause", "fault = \"device\"");
      only_with("duration", "fault = \"device\"");
      c.event.kind = devices::PlantEvent::Kind::power_cycle;
      c.text = "power cycle";
    } else if (fault == "device") {
      c.event.kind = devices::PlantEvent::Kind::fault;
      c.text = "device fault";
      if (j.contains("cause")) {
        const json& v = j["cause"];
        const std::string given = v.is_string() ? v.get<std::string>() : v.is_number_integer() ? v.dump() : "";
        if (given.empty()) throw std::invalid_argument("'cause' must be the drive's error number or name");
        const devices::CauseCheck check = devices::check_cause(facts, title, given);
        if (!check.number) throw std::invalid_argument("'cause': " + check.error);
        c.event.cause = check.number;
        c.text += ", error " + devices::cause_text(facts, *check.number);
      }
      if (j.contains("duration")) {
        try {
          c.clear_after = parse_time(string_of("duration"));
        } catch (const std::invalid_argument& e) {
          throw std::invalid_argument(std::string("'duration': ") + e.what());
        }
        c.text += " for " + format_time(*c.clear_after);
      }
    } else {
      throw std::invalid_argument("fault = \"" + fault +
                                  "\" is not for an emulated drive on its own: it takes \"device\" or "
                                  "\"power-cycle\" (\"corrupt\" and \"lost\" are INTERBUS faults of `ibs run`)");
    }
  } else if (action == "mains") {
    const std::string m = string_of("mains");
    if (m != "off" && m != "on") throw std::invalid_argument("'mains' must be \"off\" or \"on\", not \"" + m + "\"");
    c.event.kind = m == "off" ? devices::PlantEvent::Kind::mains_off : devices::PlantEvent::Kind::mains_on;
    c.text = "mains " + m;
  } else if (action == "smartcard") {
    // The drive's SMARTCARD (LUSTBUS manual 10 exception 2): read or written for 'duration'.
    if (facts.card_max_s <= 0.0) {
      throw std::invalid_argument("'smartcard' is not for the " + title + ": " +
                                  std::string(facts.no_card.empty() ? "its manuals name no SMARTCARD operation"
                                                                    : facts.no_card));
    }
    const std::string op = string_of("smartcard");
    if (op != "read" && op != "write") {
      throw std::invalid_argument("'smartcard' must be \"read\" or \"write\", not \"" + op + "\"");
    }
    if (!j.contains("duration")) throw std::invalid_argument("'smartcard' needs 'duration': how long the card is busy");
    Duration d{};
    try {
      d = parse_time(string_of("duration"));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("'duration': ") + e.what());
    }
    const double s = std::chrono::duration<double>(d).count();
    if (!(s > 0.0) || s > facts.card_max_s) {
      throw std::invalid_argument("'duration' of a SMARTCARD operation must be above 0 s and at most " +
                                  format_time(std::chrono::duration_cast<Duration>(
                                      std::chrono::duration<double>(facts.card_max_s))) +
                                  " (" + std::string(facts.card_source) + ")");
    }
    c.event.kind = op == "write" ? devices::PlantEvent::Kind::card_write : devices::PlantEvent::Kind::card_read;
    c.event.value = s;
    c.text = "SMARTCARD " + std::string(op == "write" ? "written" : "read") + " for " + format_time(d);
  } else if (action == "option_card") {
    // The drive's option card, detected at its next power-on (INTERBUS manual 3.2.1 for the MC6000).
    if (facts.option_card.empty()) {
      throw std::invalid_argument("'option_card' is not for the " + title + ": " +
                                  std::string(facts.no_option.empty() ? "its manuals give no option card an effect"
                                                                      : facts.no_option));
    }
    const std::string op = string_of("option_card");
    if (op != "withdrawn" && op != "inserted") {
      throw std::invalid_argument("'option_card' must be \"withdrawn\" or \"inserted\", not \"" + op + "\"");
    }
    c.event.kind = op == "withdrawn" ? devices::PlantEvent::Kind::option_withdrawn
                                     : devices::PlantEvent::Kind::option_inserted;
    c.text = std::string(facts.option_card) + " " + op;
  } else if (action == "load") {
    if (facts.load_unit.empty()) {
      throw std::invalid_argument("'load' is not for the " + title + ": " +
                                  std::string(facts.no_load.empty() ? "its manuals give it no load" : facts.no_load));
    }
    if (!j["load"].is_number() || !std::isfinite(j["load"].get<double>())) {
      throw std::invalid_argument("'load' must be a number (" + std::string(facts.load_unit) + ")");
    }
    c.event.kind = devices::PlantEvent::Kind::load;
    c.event.value = j["load"].get<double>();
    c.text = "load " + j["load"].dump() + " " + std::string(facts.load_unit);
  } else {
    if (facts.inputs.empty()) {
      throw std::invalid_argument("'input' is not for the " + title + ": " +
                                  std::string(facts.no_inputs.empty() ? "its manuals name no input" : facts.no_inputs));
    }
    const std::string name = string_of("input");
    const auto input = devices::find_input(facts, name);
    if (!input) {
      throw std::invalid_argument("'input' = \"" + name + "\" is not an input of the " + title + " (" +
                                  devices::input_names(facts) + ")");
    }
    if (!j.contains("level")) throw std::invalid_argument("'input' needs 'level' (\"high\" or \"low\")");
    const std::string level = string_of("level");
    if (level != "high" && level != "low") {
      throw std::invalid_argument("'level' must be \"high\" or \"low\", not \"" + level + "\"");
    }
    c.event.kind = devices::PlantEvent::Kind::input;
    c.event.input = *input;
    c.event.level = level == "high";
    c.text = "input " + name + " " + level;
  }
  return c;
}

int emulate(const LustbusEmulateOptions& o, std::ostream& out, std::ostream& err) {
  const auto bad = [&](const std::string& what) {
    err << "ibs lustbus emulate: " << what << "\n";
    return kExitLustbusBadInput;
  };
  const bool pty = o.pty || !o.pty_link.empty();  // --pty-link implies --pty
  if (pty == !o.port.port.empty()) return bad("give either --port PATH or --pty (or --pty-link PATH)");
  if (o.devices.empty()) return bad("no device: give " + device_forms() + " (one or more)");
  std::vector<ServedLustbusDrive> specs;
  std::vector<lb::Address> addresses;
  std::vector<devices::LustbusEmulated> drives;
  std::vector<std::unique_ptr<lb::Receiver>> receivers;
  std::vector<lb::ServedReceiver> served;
  std::set<lb::Address> used;
  try {
    for (const std::string& spec : o.devices) {
      const auto [face, addr] = parse_device(spec);
      if (!used.insert(addr).second) {
        throw BadInput("device '" + spec + "': address " + std::to_string(addr) +
                       " is given twice (9.1: both would answer at once)");
      }
      specs.push_back({spec, face});
      addresses.push_back(addr);
    }
    std::vector<devices::SettingValues> settings;
    try {
      settings = lustbus_drive_settings(o.settings, specs);
    } catch (const std::invalid_argument& e) {
      throw BadInput(e.what());
    }
    for (std::size_t i = 0; i < specs.size(); ++i) {
      devices::LustbusFaceOptions options;
      options.settings = std::move(settings[i]);
      options.seed = o.seed + addresses[i];
      options.reaction_ms = o.reaction_ms;
      options.baud = o.port.baud;
      try {
        drives.push_back(specs[i].face->make(options));
      } catch (const std::invalid_argument& e) {
        throw BadInput("device '" + specs[i].spec + "': " + e.what());
      }
      const devices::LustbusEmulated& d = drives.back();
      receivers.push_back(std::make_unique<lb::Receiver>(*d.responder, addresses[i]));
      served.emplace_back(receivers.back().get(), d.advance, d.line_baud);
    }
  } catch (const BadInput& e) {
    return bad(e.what());
  }
  // The control channel, opened before the port so that a bad spec serves nothing.
  std::unique_ptr<control::Channel> control;
  std::vector<ControlledDrive> controlled;
  if (!o.control.empty()) {
    std::string error;
    control = control::Channel::open(o.control, error);
    if (!control) return bad("--control " + o.control + ": " + error);
    for (std::size_t i = 0; i < specs.size(); ++i) {
      const std::string name = specs[i].spec.substr(0, specs[i].spec.find('@'));
      const devices::Drive* d = devices::find_drive(name, devices::Bus::lustbus);
      const devices::DriveFacts* facts = d != nullptr && d->interbus != nullptr ? &(*d->interbus)->facts() : nullptr;
      controlled.push_back({specs[i].spec, addresses[i], facts, &drives[i]});
    }
  }

  // Blocked before `pty: PATH` is printed: whoever reads that line may signal at once.
  StopSignals signals;
  std::optional<serial::PtyPair> pair;
  std::optional<serial::PtyLink> link;
  std::optional<serial::SerialPort> opened;
  std::unique_ptr<serial::ByteLog> log;
  try {
    if (pty) {
      pair.emplace(serial::PtyPair::open(port_options(o.port)));
      if (!o.pty_link.empty()) link.emplace(o.pty_link, pair->slave_path());
    } else {
      opened.emplace(serial::SerialPort::open(o.port.port, port_options(o.port)));
    }
    log = open_byte_log(o.port.log, o.port.log_stream);
  } catch (const std::exception& e) {
    return bad(e.what());
  }
  serial::SerialPort& port = pair ? pair->master() : *opened;
  EmulateEvents events(out);
  // The first line says where it serves: the new pty, or the port it opened.
  events.serving(o.json, pair ? "pty" : "port", pair ? pair->slave_path() : o.port.port,
                 link ? link->path() : std::string());
  for (const std::string& n : port.notes()) err << "ibs lustbus emulate: " << n << "\n";
  port.set_log(log.get());
  port.set_tap(o.port.tap);
  // With --json each drive's line is watched: what its receiver took or threw away after each
  // byte (3, LB-D23) and the answers it gave.
  std::vector<std::vector<std::uint8_t>> telegrams(specs.size());
  std::vector<lb::ReceiverCounters> seen(specs.size());
  std::vector<std::unique_ptr<WatchedLineDevice>> watched;
  const auto drive_event = [&](std::size_t i, Time at, std::string_view what) {
    return EmulateEvents::event(at, what, specs[i].spec, receivers[i]->address());
  };
  const auto watch_byte = [&](std::size_t i, std::uint8_t b, Time now) {
    constexpr std::size_t kMaxTelegram = 128;  // longer than any telegram (6): what a host sent unended
    std::vector<std::uint8_t>& bytes = telegrams[i];
    const lb::Receiver& r = *receivers[i];
    const lb::ReceiverCounters& n = r.counters();
    const auto with_bytes = [&](nlohmann::ordered_json j) {
      j["bytes"] = serial::format_bytes(bytes);
      events.print(j);
      bytes.clear();
    };
    if (n.fragments != seen[i].fragments) {  // this byte came after a silence: the fragment before it went
      nlohmann::ordered_json j = drive_event(i, now, "corrupt");
      j["what"] = "fragment";
      with_bytes(std::move(j));
    }
    if (n.cut_answers != seen[i].cut_answers) events.print(drive_event(i, now, "answer-cut"));
    if (r.last_event() == lb::ReceiverEvent::reset) bytes.clear();  // EOT begins every telegram (3)
    if (bytes.size() < kMaxTelegram) bytes.push_back(b);
    switch (r.last_event()) {
      case lb::ReceiverEvent::enquiry:
      case lb::ReceiverEvent::select:
      case lb::ReceiverEvent::broadcast: {
        nlohmann::ordered_json j = drive_event(i, now, "telegram");
        j["kind"] = std::string(lb::to_string(r.last_event()));
        with_bytes(std::move(j));
        break;
      }
      case lb::ReceiverEvent::checksum_error:
      case lb::ReceiverEvent::dropped: {
        nlohmann::ordered_json j = drive_event(i, now, "corrupt");
        j["what"] = r.last_event() == lb::ReceiverEvent::checksum_error ? "checksum" : "improper";
        with_bytes(std::move(j));
        break;
      }
      case lb::ReceiverEvent::none:
      case lb::ReceiverEvent::reset: break;
    }
    seen[i] = n;
  };
  std::vector<base::LineDevice*> lines;
  for (std::size_t i = 0; i < served.size(); ++i) {
    if (!o.json) {
      lines.push_back(&served[i]);
      continue;
    }
    watched.push_back(std::make_unique<WatchedLineDevice>(
        served[i], events, specs[i].spec, [&receivers, i] { return unsigned{receivers[i]->address()}; },
        [&watch_byte, i](std::uint8_t b, Time now) { watch_byte(i, b, now); }));
    lines.push_back(watched.back().get());
  }
  // Control lines are read between two turns of the serve loop (every kServePoll at the most), at
  // the time since it began; a device fault with a duration clears when that has passed.
  struct PendingClear {
    std::size_t drive;
    Time at;
  };
  std::vector<PendingClear> clears;
  const auto t0 = std::chrono::steady_clock::now();
  const auto poll_control = [&]() {
    const Time now{std::chrono::duration_cast<Duration>(std::chrono::steady_clock::now() - t0)};
    for (auto it = clears.begin(); it != clears.end();) {
      if (it->at > now) {
        ++it;
        continue;
      }
      devices::PlantEvent clear;
      clear.kind = devices::PlantEvent::Kind::fault_clear;
      if (controlled[it->drive].drive->apply_event) controlled[it->drive].drive->apply_event(clear, now);
      if (o.json) {
        nlohmann::ordered_json j = drive_event(it->drive, now, "control");
        j["what"] = "device fault's cause gone";
        j["taken"] = true;
        events.print(j);
      } else {
        err << "ibs lustbus emulate: " << controlled[it->drive].spec << ": device fault's cause gone\n" << std::flush;
      }
      it = clears.erase(it);
    }
    control->poll(
        [&](const control::Origin& from, std::string_view text) {
          try {
            const ControlEvent c = parse_emulate_control(text, controlled);
            const ControlledDrive& d = controlled[c.drive];
            const bool taken = d.drive->apply_event && d.drive->apply_event(c.event, now);
            if (o.json) {
              nlohmann::ordered_json j = drive_event(c.drive, now, "control");
              j["what"] = c.text;
              j["taken"] = taken;
              j["control_line"] = from.line;
              if (from.client != 0) j["control_client"] = from.client;
              events.print(j);
            } else {
              err << "ibs lustbus emulate: " << from << ": " << d.spec << ": " << c.text
                  << (taken ? "" : " (not taken by the drive)") << "\n"
                  << std::flush;
            }
            if (taken && c.clear_after) clears.push_back({c.drive, now + *c.clear_after});
          } catch (const std::invalid_argument& e) {
            err << from << ": " << e.what() << "\n" << std::flush;
          }
        },
        [&](const control::Origin& from, std::string_view what) { err << from << ": " << what << "\n"; },
        [&](std::string_view notice) { err << notice << "\n" << std::flush; });
  };
  serial::serve(port, lines, [&]() {
    if (control) poll_control();
    return signals.raised();
  });
  // What each drive's receiver took, answered and threw away (3, LB-D23), as `ibs dfs1 emulate`
  // tells its controllers'.
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const lb::ReceiverCounters& n = receivers[i]->counters();
    if (o.json) {
      const Time end{std::chrono::duration_cast<Duration>(std::chrono::steady_clock::now() - t0)};
      nlohmann::ordered_json j = drive_event(i, end, "summary");
      j["counters"] = {{"enquiries", n.enquiries},         {"selects", n.selects},
                       {"broadcasts", n.broadcasts},       {"answers", n.answers},
                       {"checksum_errors", n.checksum_errors}, {"dropped", n.dropped},
                       {"fragments", n.fragments},         {"cut_answers", n.cut_answers}};
      events.print(j);
      continue;
    }
    err << "ibs lustbus emulate: " << specs[i].spec << ": " << n.enquiries << " ENQUIRY(s), " << n.selects
        << " SELECT(s), " << n.broadcasts << " broadcast(s), " << n.answers << " answer(s) sent, "
        << n.checksum_errors << " BCC error(s), " << n.dropped << " improper telegram(s) dropped, " << n.fragments
        << " fragment(s) dropped after silence, " << n.cut_answers << " answer(s) cut by EOT\n";
  }
  return kExitLustbusOk;
}

// The drives' own settings as options of `emulate`: one per name the LUSTBUS faces declare, its
// help the declarations' meanings. Declarations of one name must agree on its type.
void add_drive_setting_options(CLI::App* cmd, devices::SettingValues& values) {
  struct Declared {
    std::string_view name;
    std::vector<std::pair<const devices::Drive*, const devices::SettingSpec*>> by;
  };
  std::vector<Declared> declared;
  for (const devices::Drive* d : devices::drives_on(devices::Bus::lustbus)) {
    for (const devices::SettingSpec& spec : d->lustbus->settings) {
      auto it = std::find_if(declared.begin(), declared.end(), [&](const Declared& x) { return x.name == spec.name; });
      if (it == declared.end()) it = declared.insert(declared.end(), Declared{spec.name, {}});
      if (!it->by.empty() && it->by.front().second->kind != spec.kind) {
        throw std::logic_error("LUSTBUS setting '" + std::string(spec.name) + "' is declared as " +
                               std::string(devices::to_string(it->by.front().second->kind)) + " and as " +
                               std::string(devices::to_string(spec.kind)));
      }
      it->by.emplace_back(d, &spec);
    }
  }
  for (const Declared& x : declared) {
    std::string help;
    for (const auto& [drive, spec] : x.by) {
      help += (help.empty() ? "" : "; ") + std::string(drive->name) + ": " + std::string(spec->meaning) + " (" +
              std::string(spec->seed) + ")";
    }
    const devices::SettingSpec& first = *x.by.front().second;
    const std::string option = "--" + std::string(x.name);
    const std::string_view name = x.name;
    switch (first.kind) {
      case devices::SettingKind::boolean:
        cmd->add_flag_function(option, [&values, name](std::int64_t n) { values.set_boolean(name, n > 0); }, help);
        break;
      case devices::SettingKind::integer:
        cmd->add_option_function<std::int64_t>(
            option, [&values, name](const std::int64_t& v) { values.set_integer(name, v); },
            help + "; " + std::string(first.range));
        break;
      case devices::SettingKind::choice: {
        std::vector<std::string> names(first.choices.begin(), first.choices.end());
        cmd->add_option_function<std::string>(
               option,
               [&values, name, names](const std::string& v) {
                 const auto at = std::find(names.begin(), names.end(), v);
                 values.set(name, devices::SettingKind::choice, at - names.begin());
               },
               help)
            ->check(CLI::IsMember(names));
        break;
      }
      case devices::SettingKind::duration:
        // No LUSTBUS face declares a time; the command line would need the scenario's time syntax.
        throw std::logic_error("LUSTBUS setting '" + std::string(x.name) +
                               "' is a time, which `ibs lustbus emulate` has no option form for");
    }
  }
}

// Opens the port and the log for a host command.
struct HostPort {
  std::optional<serial::SerialPort> port;
  std::unique_ptr<serial::ByteLog> log;
};
HostPort open_host_port(const LustbusPortOptions& o) {
  if (o.port.empty()) throw BadInput("--port PATH is required");
  HostPort h;
  try {
    h.port.emplace(serial::SerialPort::open(o.port, port_options(o)));
    std::unique_ptr<serial::ByteLog>& log = o.shared_log != nullptr ? *o.shared_log : h.log;
    if (!log) log = open_byte_log(o.log, o.log_stream);
    h.port->set_log(log.get());
  } catch (const std::exception& e) {
    throw BadInput(e.what());
  }
  h.port->set_tap(o.tap);
  return h;
}

int device_failure(const std::string& cmd, const std::string& who, const lb::Outcome& o,
                   nlohmann::json& j, bool json, std::ostream& out, std::ostream& err) {
  j["outcome"] = std::string(lb::to_string(o.kind));
  if (o.siof) {
    j["siof"] = *o.siof;
    j["cause"] = drive::describe_siof(*o.siof);
  }
  if (json) out << j.dump() << "\n";
  err << "ibs lustbus " << cmd << ": " << who << ": " << lb::describe(o) << "\n";
  return kExitLustbusDevice;
}

// 11.4: a parameter dataset file, one `PARAM VALUE` a line ('#' starts a comment), sent with the
// 80-SLOAD handshake as one host request. The values are checked for their type only: the servo
// tests the whole dataset (11.4, "without individual testing").
int download_file(const LustbusClientOptions& o, std::ostream& out, std::ostream& err) {
  const std::string name = "download";
  try {
    if (o.addr < 0 || o.addr > 30) throw BadInput("--addr must be 0..30 (31 is broadcast)");
    // A regular file of bounded size only: a FIFO would block, /dev/zero never end.
    std::istringstream in;
    try {
      in.str(read_text_file(o.parameter));
    } catch (const FileReadError& e) {
      throw BadInput(o.parameter + ": " + e.what());
    }
    // 11.4: the drive that offers the download, and the handshake parameter it runs through.
    const devices::Drive& drive = download_drive();
    const lb::DownloadProcedure& procedure = *drive.lustbus->procedures->download;
    const std::string handshake =
        label(find_param(*drive.lustbus, std::to_string(procedure.parameter)));
    std::vector<lb::Assignment> records;
    std::vector<std::string> labels;
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
      std::istringstream ls(line);
      std::string param;
      std::string value;
      std::string extra;
      if (!(ls >> param)) continue;
      if (!(ls >> value) || (ls >> extra)) {
        throw BadInput(o.parameter + ":" + std::to_string(n) + ": expected `PARAM VALUE`");
      }
      try {
        const Param p = find_param(*drive.lustbus, param);
        if (!p.in_dataset) {
          throw BadInput(label(p) + " cannot be part of a dataset");
        }
        records.push_back({value_code(p, false), format_value(p, parse_value(p, value, false))});
        labels.push_back(label(p));
      } catch (const BadInput& e) {
        throw BadInput(o.parameter + ":" + std::to_string(n) + ": " + e.what());
      }
    }
    if (records.empty()) throw BadInput("'" + o.parameter + "' holds no parameter");
    lb::HostConfig cfg;
    cfg.response_timeout = std::chrono::milliseconds(o.timeout_ms);
    HostPort hp = open_host_port(o.port);
    lb::Host host(cfg);
    const lb::Outcome r = ask(
        *hp.port, host, lb::download(procedure, static_cast<lb::Address>(o.addr), records));
    nlohmann::json j;
    j["address"] = o.addr;
    j["records"] = records.size();
    j["outcome"] = std::string(lb::to_string(r.kind));
    const std::string who = std::string(drive.name) + "@" + std::to_string(o.addr);
    if (r.kind == lb::OutcomeKind::downloaded) {
      if (o.json) {
        out << j.dump() << "\n";
      } else {
        out << who << ": " << records.size() << " parameters downloaded, " << handshake << " = 0\n";
      }
      return kExitLustbusOk;
    }
    std::string why = lb::describe(r);
    if (r.kind == lb::OutcomeKind::download_rejected) {
      j["rejected_parameter"] = r.rejected_parameter;
      why = "the servo rejected the dataset: first invalid parameter " +
            std::to_string(r.rejected_parameter) + " (" + handshake + "); the old dataset is back";
    } else if (r.kind == lb::OutcomeKind::download_refused) {
      j["failed_step"] = r.failed_step;
      const auto step = r.failed_step;
      why = "refused at " +
            (step == lb::kDownloadStartStep ? handshake + " = " + std::to_string(procedure.start)
             : step >= static_cast<std::int32_t>(labels.size())
                 ? handshake + " = " + std::to_string(procedure.end)
                 : labels[static_cast<std::size_t>(step)]) +
            ": " + why;
    }
    if (r.siof) j["siof"] = *r.siof;
    if (o.json) out << j.dump() << "\n";
    err << "ibs lustbus download: " << who << ": " << why << "\n";
    return kExitLustbusDevice;
  } catch (const BadInput& e) {
    err << "ibs lustbus " << name << ": " << e.what() << "\n";
    return kExitLustbusBadInput;
  }
}

int client(const CLI::App& which, const LustbusClientOptions& o, std::ostream& out,
           std::ostream& err) {
  const std::string name = which.get_name();
  try {
    if (o.timeout_ms <= 0) throw BadInput("--timeout-ms must be positive");
    lb::HostConfig cfg;
    cfg.response_timeout = std::chrono::milliseconds(o.timeout_ms);
    nlohmann::json j;

    if (name == "scan") {
      HostPort hp = open_host_port(o.port);
      lb::Host host(cfg);
      const lb::Outcome r = ask(*hp.port, host, lb::network_scan());
      if (r.kind != lb::OutcomeKind::scan) return device_failure(name, "scan", r, j, o.json, out, err);
      j["devices"] = nlohmann::json::array();
      for (const lb::ScanEntry& e : r.scan.found()) {
        const std::string fam = e.family ? std::string(lb::to_string(*e.family)) : "unknown";
        const std::string kind = e.family ? std::string(lb::device_kind(*e.family)) : "unknown";
        j["devices"].push_back({{"address", e.address}, {"family", fam}, {"kind", kind},
                                {"type", e.type}});
        if (!o.json) {
          out << "address " << int(e.address) << ": " << fam << " (" << kind << "), 91-TYPE "
              << e.type << "\n";
        }
      }
      if (o.json) out << j.dump() << "\n";
      if (!o.json && r.scan.count == 0) out << "no device answered at 1..30\n";
      return kExitLustbusOk;
    }

    if (o.addr < 0 || o.addr > 30) throw BadInput("--addr must be 0..30 (31 is broadcast)");
    const devices::LustbusFace& face = parse_face(o.device);
    const lb::Family family = face.family;
    const Param p = find_param(face, o.parameter);
    const auto addr = static_cast<lb::Address>(o.addr);
    const std::string who = o.device + "@" + std::to_string(o.addr) + " " + label(p);
    j["device"] = o.device;
    j["address"] = o.addr;
    j["parameter"] = p.number;
    j["name"] = p.name;
    if (!p.unit.empty()) j["unit"] = p.unit;

    lb::Request req;
    std::uint32_t written = 0;
    if (name == "write") {
      if (!o.value) throw BadInput("VALUE is required");
      if (!p.writable) throw BadInput(label(p) + " is read-only");
      written = parse_value(p, *o.value);
      req = lb::select(addr, value_code(p, false), format_value(p, written));
      if (p.prog) req.response_timeout = std::chrono::seconds(10);  // 10 exception 1
    } else {
      if (o.value) throw BadInput(name + " takes no VALUE");
      req = lb::enquiry(addr, value_code(p, name == "describe"));
    }
    HostPort hp = open_host_port(o.port);
    lb::Host host(cfg);
    const lb::Outcome r = ask(*hp.port, host, req);
    const bool ok = name == "write" ? r.kind == lb::OutcomeKind::acknowledged
                                    : r.kind == lb::OutcomeKind::value;
    if (!ok) return device_failure(name, who, r, j, o.json, out, err);
    j["outcome"] = std::string(lb::to_string(r.kind));

    if (name == "describe") {
      // The VALUE of a description is binary (names padded with NUL, 11.2): in JSON its bytes in
      // hex, "53 50 45 45 44 00 ...", so that no string carries a NUL or a control character.
      std::string raw_hex;
      for (const char c : r.value.view()) {
        if (!raw_hex.empty()) raw_hex += ' ';
        raw_hex += tool::hex2(static_cast<unsigned char>(c));
      }
      j["raw_hex"] = raw_hex;
      if (family == lb::Family::standard) {
        const auto d = lb::parse_vf_description(r.value.view());
        if (!d.ok()) throw std::runtime_error("description: " + std::string(lb::to_string(d.error)));
        const auto t = lb::vf_type_from_char(d.value.type);
        const lb::DataType dt = t.value_or(p.type);
        j["value"] = {{"name", d.value.name_view()},
                      {"unit", d.value.unit_view()},
                      {"kind", std::string(1, d.value.kind)},
                      {"type", std::string(lb::to_string(dt))},
                      {"min", engineering_text(dt, d.value.min)},
                      {"max", engineering_text(dt, d.value.max)},
                      {"default", engineering_text(dt, d.value.basis)}};
      } else {
        const auto d = lb::parse_mc_description(r.value.view());
        if (!d.ok()) throw std::runtime_error("description: " + std::string(lb::to_string(d.error)));
        j["value"] = {{"name", d.value.name_view()},
                      {"unit", d.value.unit},
                      {"kind", std::string(1, d.value.kind)},
                      {"type", std::string(lb::to_string(p.type))},
                      {"min", engineering_text(p.type, d.value.min)},
                      {"max", engineering_text(p.type, d.value.max)},
                      {"default", engineering_text(p.type, d.value.reference)},
                      {"attribute", d.value.attribute}};
      }
      if (o.json) {
        out << j.dump() << "\n";
      } else {
        const auto& v = j["value"];
        out << who << ": " << v["name"].get<std::string>() << ", kind "
            << v["kind"].get<std::string>() << ", " << v["type"].get<std::string>() << ", min "
            << v["min"].get<std::string>() << ", max " << v["max"].get<std::string>()
            << ", default " << v["default"].get<std::string>() << "\n";
      }
      return kExitLustbusOk;
    }

    std::uint32_t bits = written;
    if (name == "read") {
      const auto b = lb::parse_typed(family, p.type, r.value.view());
      if (!b.ok()) throw std::runtime_error("answer '" + std::string(r.value.view()) + "' is no " +
                                            std::string(lb::to_string(p.type)));
      bits = b.value;
    }
    const unsigned digits = lb::width_bits(p.type) / 4;
    j["raw"] = bits;
    j["raw_hex"] = tool::hex(bits, static_cast<int>(digits));
    const auto e = lb::to_engineering(p.type, bits);
    if (e.ok()) {
      j["value"] = e.value;
    } else {
      j["value"] = nullptr;
    }
    if (o.json) {
      out << j.dump() << "\n";
    } else {
      out << who << (name == "write" ? " := " : " = ") << engineering_text(p.type, bits)
          << (p.unit.empty() ? "" : " " + p.unit) << " (" << tool::hex(bits, static_cast<int>(digits)) << "H)\n";
    }
    return kExitLustbusOk;
  } catch (const BadInput& e) {
    err << "ibs lustbus " << name << ": " << e.what() << "\n";
    return kExitLustbusBadInput;
  } catch (const std::runtime_error& e) {
    err << "ibs lustbus " << name << ": " << e.what() << "\n";
    return kExitLustbusDevice;
  }
}

void add_port_options(CLI::App* cmd, LustbusPortOptions& p) {
  cmd->add_option("--baud", p.baud, "baud rate (default 9600; a pty ignores it); 7E1 always");
  add_line_output_options(cmd, p.log, p.pcap);
}

void add_client_options(CLI::App* cmd, LustbusClientOptions& o, bool parameter) {
  cmd->add_option("-p,--port", o.port.port, "the serial port (e.g. /dev/ttyUSB0 or a pty)")
      ->required();
  if (parameter) {
    cmd->add_option("-a,--address,--addr", o.addr, "the device's address, 1..30 (0: the only device)")
        ->required();
    cmd->add_option("--device", o.device,
                    devices::drive_names(devices::Bus::lustbus, ", ", " or ") + ": the parameter table to use")
        ->required();
    cmd->add_option("PARAM", o.parameter, "parameter number or name")->required();
  }
  cmd->add_option("--timeout-ms", o.timeout_ms, "response timeout in ms (default 250)");
  cmd->add_flag("-j,--json", o.json, "print JSON");
  add_port_options(cmd, o.port);
}

}  // namespace

std::vector<devices::SettingValues> lustbus_drive_settings(const devices::SettingValues& given,
                                                           std::span<const ServedLustbusDrive> served) {
  std::vector<devices::SettingValues> out(served.size());
  for (const devices::SettingValue& v : given.all()) {
    bool taken = false;
    for (std::size_t i = 0; i < served.size(); ++i) {
      const devices::SettingSpec* spec = devices::find_setting(served[i].face->settings, v.name);
      if (spec == nullptr) continue;
      const std::string who = "device '" + served[i].spec + "': --" + v.name;
      if (spec->kind != v.kind) {
        throw std::invalid_argument(who + " must be " + std::string(devices::to_string(spec->kind)));
      }
      if (v.value < spec->min || v.value > spec->max) {
        throw std::invalid_argument(who + " " + std::to_string(v.value) + " is out of range (" +
                                    std::string(spec->range) + (spec->seed.empty() ? "" : ", ") +
                                    std::string(spec->seed) + ")");
      }
      out[i].set(v.name, v.kind, v.value);
      taken = true;
    }
    if (!taken) {
      std::string specs;
      for (const ServedLustbusDrive& d : served) specs += (specs.empty() ? "" : ", ") + d.spec;
      throw std::invalid_argument("--" + v.name + " applies to none of the drives served (" + specs +
                                  "): no LUSTBUS face of theirs declares '" + v.name + "'");
    }
  }
  return out;
}

void add_lustbus_commands(CLI::App& app, LustbusCommandState& state) {
  state.lustbus = app.add_subcommand(
      "lustbus", "LUSTBUS (LUSTBUS manual) over a serial port: emulate VF1000/MC6000 drives, or ask one "
                 "(docs/lustbus.md)");
  state.lustbus->require_subcommand(1);

  LustbusEmulateOptions& eo = state.emulate_options;
  state.emulate = state.lustbus->add_subcommand(
      "emulate", "emulate drives on a port or a new pty until SIGINT/SIGTERM");
  state.emulate->add_option("DEVICE", eo.devices, device_forms() + ", one per drive")
      ->required();
  state.emulate->add_option("-p,--port", eo.port.port, "the serial port to serve");
  state.emulate->add_flag("--pty", eo.pty, "create a pseudo-terminal and print `pty: PATH` first");
  state.emulate->add_option("--pty-link", eo.pty_link,
                            "with --pty (implied): a symbolic link PATH to the pty, as socat's pty,link=PATH; "
                            "a PATH that exists is refused, the link is removed at exit");
  add_drive_setting_options(state.emulate, eo.settings);
  state.emulate->add_option("--seed", eo.seed, "seed of the reaction times (default 1; + address)");
  state.emulate->add_option("--reaction-ms", eo.reaction_ms, "a fixed reaction time instead, 0..10000 ms")
      ->check(CLI::Range(0, 10000));
  add_port_options(state.emulate, eo.port);
  state.emulate->add_flag("-j,--json", eo.json,
                          "one JSON object a line per event: serving, telegram, answer, corrupt, answer-cut, "
                          "control, summary (docs/lustbus.md)");
  state.emulate->add_option("--control", eo.control,
                            "a live control channel, '-' (standard input) or unix:PATH: JSON lines of "
                            "events (fault, mains, load, input) for the drives served");

  LustbusClientOptions& co = state.client_options;
  state.read = state.lustbus->add_subcommand("read", "ENQUIRY: read a parameter's value");
  add_client_options(state.read, co, true);
  add_repeat_options(state.read, co.repeat);
  state.write = state.lustbus->add_subcommand("write", "SELECT: write a parameter's value");
  add_client_options(state.write, co, true);
  state.write
      ->add_option_function<std::string>(
          "VALUE", [&co](const std::string& v) { co.value = v; },
          "in the parameter's unit, or raw with 0x")
      ->required();
  state.describe = state.lustbus->add_subcommand(
      "describe", "ENQUIRY of the description (11.1 specifier 1, 11.2 specifier 3)");
  add_client_options(state.describe, co, true);
  state.download = state.lustbus->add_subcommand(
      "download", "11.4: send a parameter dataset file (PARAM VALUE lines) to an MC6000 through "
                  "the 80-SLOAD handshake");
  state.download->add_option("-p,--port", co.port.port, "the serial port")->required();
  state.download->add_option("-a,--address,--addr", co.addr, "the servo's address, 1..30")->required();
  state.download->add_option("FILE", co.parameter, "the dataset: `PARAM VALUE` per line")
      ->required();
  state.download->add_option("--timeout-ms", co.timeout_ms, "response timeout in ms (default 250)");
  state.download->add_flag("-j,--json", co.json, "print JSON");
  add_port_options(state.download, co.port);
  state.scan = state.lustbus->add_subcommand(
      "scan", "ENQUIRY of 91-TYPE at 1..30, telling inverters from servos (5.2)");
  add_client_options(state.scan, co, false);
}

std::optional<int> run_lustbus_commands(const LustbusCommandState& state, std::ostream& out,
                                        std::ostream& err) {
  if (state.lustbus == nullptr || !state.lustbus->parsed()) return std::nullopt;
  // `--log -` (issue 27.1) and `--pcap -`: that is standard output, and what the command prints
  // itself goes to standard error, as `ibs run --pcap -` does (line_outputs.hpp).
  LustbusEmulateOptions eo = state.emulate_options;
  LustbusClientOptions co = state.client_options;
  const LustbusPortOptions& port = state.emulate->parsed() ? eo.port : co.port;
  if (port.log == "-") eo.port.log_stream = co.port.log_stream = &out;
  const std::vector<CLI::App*> chosen = state.lustbus->get_subcommands();  // the one parsed (require_subcommand(1))
  if (chosen.empty()) return kExitLustbusBadInput;
  const CLI::App* which = chosen.front();
  const LineOutputs outputs{port.log, port.pcap, serial::LineProtocol::lustbus, state.emulate->parsed(),
                            "ibs lustbus " + which->get_name(), kExitLustbusBadInput};
  return run_with_line_outputs(outputs, out, err, [&](serial::ByteTap* tap, std::ostream& say) {
    eo.port.tap = co.port.tap = tap;
    if (state.emulate->parsed()) return emulate(eo, say, err);
    if (state.download->parsed()) return download_file(co, say, err);
    if (state.read->parsed()) {
      std::unique_ptr<serial::ByteLog> shared_log;  // the readings' one byte log (open_host_port)
      if (co.repeat.repeat != 1) co.port.shared_log = &shared_log;
      return repeat_readings(co.repeat, "ibs lustbus read", err, kExitLustbusBadInput, [&] {
        const int rc = client(*state.read, co, say, err);
        say.flush();  // a pipe sees each reading as it comes
        return rc;
      });
    }
    return client(*which, co, say, err);
  });
}

std::optional<int> run_lustbus_commands(const LustbusCommandState& state) {
  return run_lustbus_commands(state, std::cout, std::cerr);
}

}  // namespace ibs::cli
