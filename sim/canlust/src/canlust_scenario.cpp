#include "ibs/sim/canlust_scenario.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "ibs/devices/drives.hpp"
#include "ibs/sim/scenario.hpp"
#include "canlust_reader.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim::canlust {

namespace {

using detail::Node;

const Node* child(const Node& table, std::string_view key, std::size_t* key_line = nullptr) {
  for (std::size_t i = 0; i < table.keys.size(); ++i) {
    if (table.keys[i] == key) {
      if (key_line != nullptr) *key_line = table.key_lines[i];
      return &table.children[i];
    }
  }
  return nullptr;
}

class Reader {
 public:
  explicit Reader(std::string file, std::size_t line = 0) : file_(std::move(file)), line_(line) {}

  // A control line is one line: every error names it, whatever line its node says.
  [[noreturn]] void fail(std::size_t line, const std::string& what) const {
    throw ScenarioError(file_, line_ != 0 ? line_ : line, what);
  }

  void only(const Node& table, const std::vector<std::string_view>& known, const std::string& where) const {
    for (std::size_t i = 0; i < table.keys.size(); ++i) {
      bool ok = false;
      for (const auto k : known) ok = ok || table.keys[i] == k;
      if (ok) continue;
      const auto near = detail::closest_name(table.keys[i], known);
      fail(table.key_lines[i], "unknown key '" + table.keys[i] + "' in " + where +
                                   (near.empty() ? "" : " (did you mean '" + std::string(near) + "'?)"));
    }
  }
  std::string text(const Node& n, const std::string& key) const {
    if (n.kind != Node::Kind::string) fail(n.line, key + ": expected a string");
    return n.text;
  }
  std::int64_t integer(const Node& n, const std::string& key, std::int64_t lo, std::int64_t hi) const {
    if (n.kind != Node::Kind::integer) fail(n.line, key + ": expected a whole number");
    if (n.integer < lo || n.integer > hi) {
      fail(n.line, key + " = " + std::to_string(n.integer) + " is outside " + std::to_string(lo) + ".." +
                       std::to_string(hi));
    }
    return n.integer;
  }
  double number(const Node& n, const std::string& key) const {
    if (n.kind == Node::Kind::integer) return static_cast<double>(n.integer);
    if (n.kind != Node::Kind::floating) fail(n.line, key + ": expected a number");
    return n.floating;
  }
  Duration time(const Node& n, const std::string& key) const {
    try {
      return parse_time(text(n, key));
    } catch (const std::invalid_argument& e) {
      fail(n.line, key + ": " + e.what());
    }
  }

 private:
  std::string file_;
  std::size_t line_ = 0;
};

}  // namespace

bool is_master_command(Action a) {
  switch (a) {
    case Action::mains_reset:
    case Action::mains_off:
    case Action::mains_on:
    case Action::device_fault:
    case Action::load:
    case Action::input: return false;
    default: return true;
  }
}

devices::CanlustEvent event_of(const Entry& e) {
  devices::CanlustEvent ev;
  switch (e.action) {
    case Action::device_fault: ev.kind = devices::CanlustEvent::Kind::fault; break;
    case Action::mains_off: ev.kind = devices::CanlustEvent::Kind::mains_off; break;
    case Action::mains_on: ev.kind = devices::CanlustEvent::Kind::mains_on; break;
    case Action::mains_reset: ev.kind = devices::CanlustEvent::Kind::power_cycle; break;
    case Action::load: ev.kind = devices::CanlustEvent::Kind::load; break;
    case Action::input: ev.kind = devices::CanlustEvent::Kind::input; break;
    default: break;
  }
  ev.cause = e.cause;
  ev.load = e.load;
  ev.input = e.input;
  ev.level = e.level;
  return ev;
}

namespace {

Entry read_entry(const Reader& r, const Node& t, const Scenario& s, bool control) {
  if (t.kind != Node::Kind::table) r.fail(t.line, "[[timeline]] must be a table");
  r.only(t, {"at", "device", "system", "state", "easydrive", "reference_hz", "read", "write", "value", "fault",
             "duration", "cause", "mains", "load", "input", "level"},
         control ? "a control entry" : "[[timeline]]");
  Entry e;
  e.line = t.line;
  const Node* at = child(t, "at");
  if (control) {
    if (at != nullptr) r.fail(at->line, "control entries apply at once: no 'at'");
  } else {
    if (at == nullptr) r.fail(t.line, "[[timeline]] needs at");
    e.at = r.time(*at, "at");
    if (e.at >= s.duration) r.fail(at->line, "at = " + format_time(e.at) + " is not inside the duration " + format_time(s.duration));
  }
  int actions = 0;
  const Node* device = child(t, "device");
  if (device != nullptr) e.device = r.text(*device, "device");
  if (const Node* n = child(t, "system")) {
    ++actions;
    const std::string v = r.text(*n, "system");
    if (v != "start" && v != "stop") r.fail(n->line, "system = \"" + v + "\": expected \"start\" or \"stop\"");
    e.action = v == "start" ? Action::start : Action::stop;
  }
  if (const Node* n = child(t, "state")) {
    ++actions;
    e.action = Action::state;
    const std::string v = r.text(*n, "state");
    bool found = false;
    for (std::size_t i = 0; i < drivecom::kTargetKeys.size(); ++i) {
      if (drivecom::kTargetKeys[i] == v) {
        e.target = drivecom::kTargets[i];
        found = true;
      }
    }
    if (!found) r.fail(n->line, "state = \"" + v + "\": expected start_up_inhibit, ready, on or enabled");
  }
  if (const Node* n = child(t, "easydrive")) {
    ++actions;
    e.action = Action::easydrive;
    e.bits = static_cast<std::uint16_t>(r.integer(*n, "easydrive", 0, 65535));
  }
  if (const Node* n = child(t, "reference_hz")) {
    ++actions;
    e.action = Action::reference;
    e.hz = r.number(*n, "reference_hz");
  }
  // Parameters are the table of the drive the entry names (its [[device]]'s type); an entry
  // that names no known device is refused below, before its parameter matters.
  const devices::CanlustFace* face = nullptr;
  for (const auto& d : s.drives) {
    if (device != nullptr && d.name == e.device) face = &canlust_face(d.kind);
  }
  const auto parameter = [&](const Node& n, const std::string& key) {
    std::optional<devices::CanlustParameter> p;
    if (face == nullptr) return p;
    if (n.kind == Node::Kind::string) {
      p = face->find_parameter(n.text);
    } else if (n.kind == Node::Kind::integer && n.integer >= 0 && n.integer <= 65535) {
      p = face->parameter(static_cast<std::uint16_t>(n.integer));
    }
    if (!p) r.fail(n.line, key + ": the " + std::string(face->title) + " has no such parameter");
    return p;
  };
  if (const Node* n = child(t, "read")) {
    ++actions;
    e.action = Action::read;
    if (const auto p = parameter(*n, "read")) e.parameter = p->number;
  }
  if (const Node* n = child(t, "write")) {
    ++actions;
    e.action = Action::write;
    const auto p = parameter(*n, "write");
    if (p) e.parameter = p->number;
    const Node* v = child(t, "value");
    if (v == nullptr) r.fail(t.line, "write needs a value");
    e.value = v->kind == Node::Kind::string ? v->text
              : v->kind == Node::Kind::integer ? std::to_string(v->integer)
              : v->kind == Node::Kind::floating ? detail::format_number(v->floating)
                                                : (r.fail(v->line, "value: expected a number or a string"), "");
    if (p && !p->writable) r.fail(n->line, "write: " + p->name + " is read-only");
    if (p && !p->is_string) {
      const auto parsed = face->parse_value(p->number, e.value);
      if (!parsed.wire) r.fail(v->line, parsed.error);
    }
  } else if (child(t, "value") != nullptr) {
    r.fail(t.line, "value belongs to a write");
  }
  if (const Node* n = child(t, "fault")) {
    ++actions;
    const std::string v = r.text(*n, "fault");
    if (v == "mains_reset") e.action = Action::mains_reset;
    else if (v == "mains_off") e.action = Action::mains_off;
    else if (v == "mains_on") e.action = Action::mains_on;
    else if (v == "master_silent") e.action = Action::master_silent;
    else if (v == "device") e.action = Action::device_fault;
    else r.fail(n->line, "fault = \"" + v + "\": expected device, mains_reset, mains_off, mains_on or master_silent");
  }
  if (const Node* n = child(t, "mains")) {
    ++actions;
    const std::string v = r.text(*n, "mains");
    if (v != "off" && v != "on") r.fail(n->line, "mains = \"" + v + "\": expected \"off\" or \"on\"");
    e.action = v == "off" ? Action::mains_off : Action::mains_on;
  }
  if (const Node* n = child(t, "load")) {
    ++actions;
    e.action = Action::load;
    e.load = r.number(*n, "load");
  }
  if (const Node* n = child(t, "input")) {
    ++actions;
    e.action = Action::input;
    e.input = r.text(*n, "input");
    const Node* level = child(t, "level");
    if (level == nullptr) r.fail(t.line, "input needs a level (\"high\" or \"low\")");
    const std::string v = r.text(*level, "level");
    if (v != "high" && v != "low") r.fail(level->line, "level = \"" + v + "\": expected \"high\" or \"low\"");
    e.level = v == "high";
  } else if (const Node* level = child(t, "level")) {
    r.fail(level->line, "level belongs to an input");
  }
  if (const Node* n = child(t, "cause")) {
    if (e.action != Action::device_fault) r.fail(n->line, "cause belongs to fault = \"device\"");
    e.cause = n->kind == Node::Kind::integer ? std::to_string(n->integer) : r.text(*n, "cause");
  } else if (e.action == Action::device_fault && actions == 1) {
    r.fail(t.line, "fault = \"device\" needs a cause (an error of the drive's table, by name or number)");
  }
  if (actions != 1) {
    r.fail(t.line, std::string(control ? "a control entry" : "[[timeline]]") +
                       " needs exactly one of system, state, easydrive, reference_hz, read, write, fault, mains, load, "
                       "input");
  }
  // The drive checks its own events: its error numbers, its terminals, its load range.
  if (face != nullptr && (e.action == Action::device_fault || e.action == Action::load || e.action == Action::input)) {
    const std::string why = face->check_event(event_of(e));
    if (!why.empty()) r.fail(t.line, why);
  }
  if (!s.bus.empty() && is_master_command(e.action)) {
    r.fail(t.line, std::string(to_string(e.action)) + ": with bus = \"" + s.bus +
                       "\", your own master drives the bus; the timeline holds drive events only (fault, mains, load, "
                       "input)");
  }
  const bool global = e.action == Action::start || e.action == Action::stop || e.action == Action::master_silent;
  if (global && device != nullptr) r.fail(device->line, std::string(to_string(e.action)) + " concerns the whole bus: no device");
  if (!global) {
    if (device == nullptr) r.fail(t.line, std::string(to_string(e.action)) + " needs a device");
    bool known = false;
    for (const auto& d : s.drives) known = known || d.name == e.device;
    if (!known) r.fail(device->line, "device '" + e.device + "' is not among the [[device]] tables");
    for (const auto& d : s.drives) {
      if (d.name != e.device) continue;
      if (e.action == Action::state && d.cacnf == 4) {
        r.fail(t.line, "device '" + e.device + "' runs EasyDrive (cacnf = 4): give easydrive bits, not a DRIVECOM state");
      }
      if (e.action == Action::easydrive && d.cacnf != 4) {
        r.fail(t.line, "device '" + e.device + "' runs DRIVECOM (cacnf " + std::to_string(d.cacnf) +
                           "): easydrive needs cacnf = 4");
      }
    }
  }
  if (const Node* n = child(t, "duration")) {
    if (e.action != Action::master_silent) r.fail(n->line, "duration belongs to fault = \"master_silent\"");
    e.duration = r.time(*n, "duration");
  } else if (e.action == Action::master_silent) {
    r.fail(t.line, "master_silent needs a duration");
  }
  return e;
}

}  // namespace

Entry parse_control_entry(const Scenario& s, const std::string& line, std::size_t number,
                          const std::string& source) {
  detail::Node root;
  try {
    root = detail::json_tree(line, source);
  } catch (const ScenarioError& e) {
    // The JSON reader counts lines inside the text; a control line is one line of the channel.
    std::string what = e.what();
    const std::string prefix = source + ":" + std::to_string(e.line()) + ": ";
    if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
    throw ScenarioError(source, number, what);
  }
  const Reader r(source, number);
  if (root.kind != Node::Kind::table) r.fail(number, "a control line is a JSON object: a timeline entry without 'at'");
  return read_entry(r, root, s, true);
}

std::string_view to_string(Action a) {
  switch (a) {
    case Action::start: return "system start";
    case Action::stop: return "system stop";
    case Action::state: return "state";
    case Action::easydrive: return "easydrive";
    case Action::reference: return "reference";
    case Action::read: return "read";
    case Action::write: return "write";
    case Action::mains_reset: return "mains reset";
    case Action::mains_off: return "mains off";
    case Action::mains_on: return "mains on";
    case Action::master_silent: return "master silent";
    case Action::device_fault: return "device fault";
    case Action::load: return "load";
    case Action::input: return "input";
  }
  return "?";
}

bool is_canlust_tree(const detail::Node& root) {
  const Node* bus = child(root, "bus");
  if (bus == nullptr || bus->kind != Node::Kind::table) return false;
  const Node* p = child(*bus, "protocol");
  return p != nullptr && p->kind == Node::Kind::string && p->text == "canlust";
}

Scenario load_scenario(const std::string& path) {
  const detail::ScenarioText file = detail::read_scenario_file(path);
  Scenario s = parse_scenario(file.text, path, file.format == detail::Format::json);
  if (s.name.empty()) s.name = std::filesystem::path(path).stem().string();
  return s;
}

Scenario parse_scenario(const std::string& text, const std::string& file, bool json) {
  return read_tree(json ? detail::json_tree(text, file) : detail::toml_tree(text, file), file);
}

Scenario read_tree(const detail::Node& root, const std::string& file) {
  const Reader r(file);
  Scenario s;
  r.only(root, {"name", "duration", "bus", "device", "timeline"}, "the scenario");
  if (const Node* n = child(root, "name")) s.name = r.text(*n, "name");
  std::size_t duration_line = root.line;
  if (const Node* n = child(root, "duration", &duration_line)) {
    s.duration = r.time(*n, "duration");
    if (s.duration <= Duration::zero()) r.fail(n->line, "duration must be above 0");
    if (s.duration > std::chrono::hours(1)) r.fail(n->line, "duration: a CANLust run is at most 1 h");
  }
  const Node* bus = child(root, "bus");
  if (bus == nullptr || bus->kind != Node::Kind::table) r.fail(root.line, "a CANLust scenario needs [bus] with protocol = \"canlust\"");
  r.only(*bus, {"protocol", "bitrate", "id_step", "control_period", "bus"}, "[bus]");
  const Node* proto = child(*bus, "protocol");
  if (proto == nullptr || r.text(*proto, "protocol") != "canlust") r.fail(bus->line, "[bus] protocol must be \"canlust\" here");
  if (const Node* n = child(*bus, "bitrate")) s.bitrate = static_cast<std::uint32_t>(r.integer(*n, "bitrate", 25'000, 500'000));
  if (s.bitrate % 1000 != 0) r.fail(child(*bus, "bitrate")->line, "bitrate: 489-CLBDR is in whole kbit/s");
  if (const Node* n = child(*bus, "id_step")) s.id_step = static_cast<std::uint16_t>(r.integer(*n, "id_step", 1, 2));
  if (const Node* n = child(*bus, "control_period")) {
    s.control_period = r.time(*n, "control_period");
    if (s.control_period < std::chrono::milliseconds(1) || s.control_period > std::chrono::seconds(1)) {
      r.fail(n->line, "control_period must be 1 ms .. 1 s");
    }
  }

  if (const Node* n = child(*bus, "bus")) {
    s.bus = r.text(*n, "bus");
    s.bus_line = n->line;
    const std::string& b = s.bus;
    const auto colons = std::count(b.begin(), b.end(), ':');
    const bool udp = b.rfind("udp:", 0) == 0 && colons == 3;
    const bool socketcan = b.rfind("socketcan:", 0) == 0 && colons == 1 && b.size() > 10;
    if (!udp && !socketcan) {
      r.fail(n->line, "bus = \"" + b + "\": expected \"udp:LOCALPORT:HOST:PORT\" or \"socketcan:IFACE\"");
    }
  }

  const Node* devices = child(root, "device");
  if (devices == nullptr || devices->kind != Node::Kind::array || devices->children.empty()) {
    r.fail(root.line, "no [[device]]: a CANLust scenario needs at least one " +
                          devices::drive_names(devices::Bus::canlust, ", ", " or "));
  }
  std::set<std::string> names;
  std::set<int> addresses;
  const unsigned max_address = s.id_step == 2 ? 99U : 99U;
  for (const Node& d : devices->children) {
    if (d.kind != Node::Kind::table) r.fail(d.line, "[[device]] must be a table");
    r.only(d, {"name", "type", "address", "cacnf", "watchdog_ms", "status_ms", "power_on"}, "[[device]]");
    DriveSpec spec;
    spec.line = d.line;
    const Node* name = child(d, "name");
    if (name == nullptr) r.fail(d.line, "[[device]] needs a name");
    spec.name = r.text(*name, "name");
    if (!names.insert(spec.name).second) r.fail(name->line, "device name '" + spec.name + "' is given twice");
    const Node* type = child(d, "type");
    // The drive by its name in the registry, among those that speak CANLust.
    if (type == nullptr || devices::find_drive(r.text(*type, "type"), devices::Bus::canlust) == nullptr) {
      r.fail(type != nullptr ? type->line : d.line,
             "device '" + spec.name + "': type must be \"" +
                 devices::drive_names(devices::Bus::canlust, "\", \"", "\" or \"") + "\" on a CANLust bus");
    }
    spec.kind = r.text(*type, "type");
    // One master drives the bus (canlust_run.cpp): it is the wing's of the drives' one type.
    if (!s.drives.empty() && spec.kind != s.drives.front().kind) {
      r.fail(type->line, "device '" + spec.name + "': type \"" + spec.kind + "\" differs from \"" +
                             s.drives.front().kind + "\": the drives of one CANLust bus are of one type");
    }
    const Node* addr = child(d, "address");
    if (addr == nullptr) r.fail(d.line, "device '" + spec.name + "' needs an address (571-CLADR)");
    spec.address = static_cast<std::uint8_t>(r.integer(*addr, "address", 0, max_address));
    if (!addresses.insert(spec.address).second) {
      r.fail(addr->line, "address " + std::to_string(spec.address) + " is given twice (both drives would answer)");
    }
    if (const Node* n = child(d, "cacnf")) spec.cacnf = static_cast<std::uint8_t>(r.integer(*n, "cacnf", 1, 4));
    if (const Node* n = child(d, "watchdog_ms")) spec.watchdog_ms = static_cast<std::uint16_t>(r.integer(*n, "watchdog_ms", 0, 255));
    if (const Node* n = child(d, "status_ms")) spec.status_ms = static_cast<std::uint16_t>(r.integer(*n, "status_ms", 1, 32000));
    if (const Node* n = child(d, "power_on")) {
      spec.power_on = r.time(*n, "power_on");
      if (spec.power_on >= s.duration) r.fail(n->line, "power_on is not inside the duration");
    }
    s.drives.push_back(spec);
  }

  if (const Node* tl = child(root, "timeline")) {
    if (tl->kind != Node::Kind::array) r.fail(tl->line, "timeline must be an array of tables");
    for (const Node& t : tl->children) {
      s.timeline.push_back(read_entry(r, t, s, false));
    }
  }
  std::stable_sort(s.timeline.begin(), s.timeline.end(), [](const Entry& a, const Entry& b) { return a.at < b.at; });
  (void)duration_line;
  return s;
}

const devices::CanlustFace& canlust_face(std::string_view kind) {
  const devices::Drive* d = devices::find_drive(kind, devices::Bus::canlust);
  if (d == nullptr) throw std::logic_error("no drive '" + std::string(kind) + "' speaks CANLust");
  return *d->canlust;
}

}  // namespace ibs::sim::canlust
