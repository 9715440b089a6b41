#include "bench.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "ibs/devices/dfs1/events.hpp"
#include "ibs/dfs1/capture_framer.hpp"
#include "ibs/lustbus/capture_framer.hpp"
#include "ibs/serial/capture.hpp"
#include "ibs/devices/dfs1/served_controller.hpp"
#include "ibs/devices/drives.hpp"
#include "ibs/lustbus/receiver.hpp"
#include "ibs/lustbus/served_receiver.hpp"
#include "ibs/serial/pty.hpp"
#include "ibs/serial/serial_port.hpp"
#include "ibs/serial/serve.hpp"
#include "ibs/tool/format.hpp"

namespace ibs::cli {

using sim::Action;
using sim::DeviceConfig;
using sim::LineController;
using sim::Scenario;
using sim::ServedLine;
using sim::Simulator;
using sim::TimelineEntry;

namespace {

// A served line: a new pty or a named port, and the devices on it.
struct Line {
  std::string key;   // "lustbus", "dfs1"
  std::string path;  // the port named (empty for a pty)
  std::optional<serial::PtyPair> pair;
  std::optional<serial::SerialPort> opened;
  std::vector<base::LineDevice*> devices;

  serial::SerialPort& port() { return pair ? pair->master() : *opened; }
  std::vector<std::string> notes;  // what the port refused when opened
  // The capture of the line (Bench::capture): its framer, and the time of the turn under way.
  std::unique_ptr<base::TelegramFramer> framer;
  std::optional<serial::LineCapture> capture;
  Time now{0};
  [[nodiscard]] std::string ready() const {
    return key + (pair ? " pty: " + pair->slave_path() : " port: " + path);
  }
};

void open_line(Line& line, const ServedLine& config, const serial::PortOptions& options, const std::string& file) {
  try {
    if (config.pty) {
      line.pair.emplace(serial::PtyPair::open(options));
    } else {
      line.opened.emplace(serial::SerialPort::open(config.port, options));
      line.path = config.port;
    }
  } catch (const std::exception& e) {
    throw std::invalid_argument(file + ": [" + line.key + "]: " + e.what());
  }
  for (const std::string& n : line.port().notes()) line.notes.push_back(line.key + ": " + n);
}

// A timeline or control entry for a DFS-1 controller as the wing's own control parser reads it
// (devices/dfs1/events.hpp): one reader of the events, whether they come from `ibs dfs1 emulate
// --control` or from a scenario. Either the event or what is wrong with it.
devices::dfs1::ParsedControl controller_event(const TimelineEntry& e) {
  using devices::dfs1::ControlValue;
  devices::dfs1::ControlFields f;
  switch (e.action) {
    case Action::fault_device:
      f.emplace_back("fault", ControlValue::string("device"));
      if (!e.cause.empty()) f.emplace_back("cause", ControlValue::string(e.cause));
      if (e.duration > Duration{0}) f.emplace_back("duration", ControlValue::string(format_time(e.duration)));
      break;
    case Action::fault_power_cycle: f.emplace_back("fault", ControlValue::string("power-cycle")); break;
    case Action::mains: f.emplace_back("mains", ControlValue::string(e.value)); break;
    case Action::load: f.emplace_back("load", ControlValue::of_number(e.number)); break;
    case Action::input:
      f.emplace_back("input", ControlValue::string(e.value));
      f.emplace_back("level", ControlValue::string(e.level ? "high" : "low"));
      break;
    default: {
      devices::dfs1::ParsedControl bad;
      bad.error = "a DFS-1 controller of the bench takes the events of a drive without a master: fault = \"device\" "
                  "(with its 'cause') or \"power-cycle\", mains, load, input";
      return bad;
    }
  }
  if (e.action == Action::fault_device && e.cause.empty()) {
    devices::dfs1::ParsedControl bad;
    bad.error = "fault = \"device\" on a DFS-1 controller needs its 'cause' (one of the status bits of the DFS-1 manual: ";
    for (std::size_t i = 0; i < devices::dfs1::fault_causes().size(); ++i) {
      bad.error += (i == 0 ? "" : ", ") + std::string(devices::dfs1::fault_causes()[i].seed_name);
    }
    bad.error += ")";
    return bad;
  }
  return devices::dfs1::parse_event(f);
}

}  // namespace

struct Bench::Impl {
  // LUSTBUS: one face per served drive on the simulator's drive core, its receiver at its address.
  struct LustbusDrive {
    std::string name;
    int address = 0;
    devices::LustbusEmulated face;
    std::unique_ptr<lustbus::Receiver> receiver;
    std::unique_ptr<lustbus::ServedReceiver> served;
  };
  struct Controller {
    std::string name;
    int uid = 0;
    std::unique_ptr<devices::dfs1::Controller> controller;
    std::unique_ptr<devices::dfs1::ServedController> served;
  };
  std::vector<LustbusDrive> lustbus_drives;
  std::vector<Controller> controllers;
  std::optional<Line> lustbus;
  std::optional<Line> controller_line;
  // The controllers' timeline entries, in time order, and the next one due.
  std::vector<TimelineEntry> controller_entries;
  std::size_t next_entry = 0;
  std::vector<std::string> events;
};

Bench::Bench(Simulator& sim, const Scenario& scenario, const std::string& file) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (scenario.lustbus) {
    for (std::size_t i = 0; i < scenario.devices.size(); ++i) {
      const DeviceConfig& d = scenario.devices[i];
      if (!d.lustbus) continue;
      const devices::Drive* drive = devices::find_drive(d.kind, devices::Bus::lustbus);
      const std::string who = file + ": device '" + d.name + "': ";
      if (drive == nullptr || drive->lustbus->attach == nullptr) {
        throw std::invalid_argument(who + "a " + d.kind + " does not answer on LUSTBUS: it takes no 'lustbus'");
      }
      devices::LustbusFaceOptions options;
      // The drive's own settings its LUSTBUS face declares (a KEYPAD slows both faces, LUSTBUS manual 10
      // and 001 7.1): the scenario gives them once, for the drive.
      for (const devices::SettingValue& v : d.settings.all()) {
        const devices::SettingSpec* spec = devices::find_setting(drive->lustbus->settings, v.name);
        if (spec != nullptr && spec->kind == v.kind) options.settings.set(v.name, v.kind, v.value);
      }
      options.seed = 1 + static_cast<std::uint64_t>(*d.lustbus);
      options.baud = scenario.lustbus->baud;
      Impl::LustbusDrive served;
      served.name = d.name;
      served.address = *d.lustbus;
      try {
        served.face = drive->lustbus->attach(sim.emulator(i), options);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(who + e.what());
      }
      served.receiver = std::make_unique<lustbus::Receiver>(*served.face.responder,
                                                            static_cast<lustbus::Address>(*d.lustbus));
      served.served = std::make_unique<lustbus::ServedReceiver>(served.receiver.get(), served.face.advance,
                                                                 served.face.line_baud);
      m.lustbus_drives.push_back(std::move(served));
    }
    m.lustbus.emplace();
    m.lustbus->key = "lustbus";
    // LUSTBUS manual 4: 7 data bits, even parity, 1 stop bit on RS-485 (as `ibs lustbus emulate`).
    serial::PortOptions options;
    options.baud = scenario.lustbus->baud;
    options.framing = serial::k7E1;
    options.rs485 = true;
    open_line(*m.lustbus, *scenario.lustbus, options, file);
    for (Impl::LustbusDrive& d : m.lustbus_drives) m.lustbus->devices.push_back(d.served.get());
  }
  if (scenario.controller_line) {
    const devices::Drive* drive = devices::drives_on(devices::Bus::dfs1).front();
    for (const LineController& c : scenario.controllers) {
      Impl::Controller ctl;
      ctl.name = c.name;
      ctl.uid = c.uid;
      try {
        ctl.controller = drive->dfs1->make(static_cast<std::uint8_t>(c.uid), scenario.controller_line->baud);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(file + ": controller '" + c.name + "': " + e.what());
      }
      ctl.served = std::make_unique<devices::dfs1::ServedController>(*ctl.controller);
      m.controllers.push_back(std::move(ctl));
    }
    m.controller_line.emplace();
    m.controller_line->key = "dfs1";
    // docs/dfs1.md, decision D9: binary data needs 8 data bits; no parity, 1 stop bit.
    serial::PortOptions options;
    options.baud = scenario.controller_line->baud;
    options.framing = serial::k8N1;
    open_line(*m.controller_line, *scenario.controller_line, options, file);
    for (Impl::Controller& c : m.controllers) m.controller_line->devices.push_back(c.served.get());
    for (const TimelineEntry& e : scenario.timeline) {
      for (const LineController& c : scenario.controllers) {
        if (c.name != e.device) continue;
        if (const auto parsed = controller_event(e); !parsed.event) {
          throw std::invalid_argument(file + ":" + std::to_string(e.source_line) + ": controller '" + c.name +
                                      "': " + parsed.error);
        }
        m.controller_entries.push_back(e);
      }
    }
  }
}

Bench::~Bench() = default;

std::vector<std::string> Bench::ready_lines() const {
  std::vector<std::string> out;
  if (impl_->lustbus) out.push_back(impl_->lustbus->ready());
  if (impl_->controller_line) out.push_back(impl_->controller_line->ready());
  return out;
}

std::vector<std::string> Bench::notes() const {
  std::vector<std::string> out;
  for (const std::optional<Line>* l : {&impl_->lustbus, &impl_->controller_line}) {
    if (!*l) continue;
    out.insert(out.end(), (*l)->notes.begin(), (*l)->notes.end());
  }
  return out;
}

void Bench::turn(Time now) {
  Impl& m = *impl_;
  while (m.next_entry < m.controller_entries.size() && m.controller_entries[m.next_entry].at <= now) {
    apply(m.controller_entries[m.next_entry++], now);
  }
  for (std::optional<Line>* l : {&m.lustbus, &m.controller_line}) {
    if (!*l) continue;
    (*l)->now = now;  // the capture's clock
    serial::serve_turn((*l)->port(), (*l)->devices, now);
  }
}

namespace {

std::optional<Line>& line_of(std::optional<Line>& lustbus, std::optional<Line>& dfs1, std::string_view key) {
  return key == "lustbus" ? lustbus : dfs1;
}

}  // namespace

bool Bench::serves_line(std::string_view key) const {
  return (key == "lustbus" && impl_->lustbus) || (key == "dfs1" && impl_->controller_line);
}

void Bench::capture(std::string_view key, std::ostream& out, Time epoch) {
  std::optional<Line>& l = line_of(impl_->lustbus, impl_->controller_line, key);
  if (!serves_line(key) || !l) throw std::invalid_argument("the scenario serves no " + std::string(key) + " line");
  const bool lustbus = key == "lustbus";
  l->framer = lustbus ? std::unique_ptr<base::TelegramFramer>(std::make_unique<lustbus::CaptureFramer>())
                      : std::make_unique<dfs1::CaptureFramer>();
  Line* line = &*l;
  // The bench serves devices: the host's bytes are the ones its port reads.
  l->capture.emplace(out, lustbus ? serial::LineProtocol::lustbus : serial::LineProtocol::dfs1, *l->framer,
                     serial::Direction::rx, epoch, [line] { return line->now; });
  l->port().set_tap(&*l->capture);
}

void Bench::drop_captures() {
  for (std::optional<Line>* l : {&impl_->lustbus, &impl_->controller_line}) {
    if (!*l || !(*l)->capture) continue;
    (*l)->port().set_tap(nullptr);
    (*l)->capture.reset();
  }
}

std::uint64_t Bench::finish_capture(std::string_view key) {
  std::optional<Line>& l = line_of(impl_->lustbus, impl_->controller_line, key);
  if (!l || !l->capture) return 0;
  l->port().set_tap(nullptr);
  l->capture->finish();
  return l->capture->packets();
}

bool Bench::serves_controller(const std::string& name) const {
  for (const Impl::Controller& c : impl_->controllers) {
    if (c.name == name) return true;
  }
  return false;
}

std::optional<std::string> Bench::check(const TimelineEntry& e) const {
  if (!serves_controller(e.device)) return std::nullopt;
  const auto parsed = controller_event(e);
  if (parsed.event) return std::nullopt;
  return "controller '" + e.device + "': " + parsed.error;
}

bool Bench::apply(const TimelineEntry& e, Time now) {
  Impl& m = *impl_;
  for (Impl::Controller& c : m.controllers) {
    if (c.name != e.device) continue;
    const auto parsed = controller_event(e);
    if (!parsed.event) return true;  // check() says why; nothing to apply
    // The plant is stepped to `now` first (Controller::apply); the report is the status a host
    // reads right after it.
    const devices::dfs1::EventReport r = c.controller->apply(parsed.event->event, now);
    m.events.push_back(tool::seconds(now) + " " + c.name + ": " + devices::dfs1::to_string(r));
    return true;
  }
  return false;
}

std::size_t Bench::served() const { return impl_->lustbus_drives.size() + impl_->controllers.size(); }

Bench::Counters Bench::counters(std::size_t i) const {
  const Impl& m = *impl_;
  if (i < m.lustbus_drives.size()) {
    const Impl::LustbusDrive& d = m.lustbus_drives[i];
    const lustbus::ReceiverCounters& n = d.receiver->counters();
    return {d.name, "lustbus", d.address, n.enquiries + n.selects + n.broadcasts, n.answers, n.checksum_errors,
            n.dropped + n.fragments};
  }
  const Impl::Controller& c = m.controllers[i - m.lustbus_drives.size()];
  const auto& n = c.controller->counters();
  return {c.name, "dfs1", c.uid, n.requests, n.requests - n.globals - n.dropped_replies, n.decode_errors, n.fragments};
}

BenchReport Bench::report() const {
  const Impl& m = *impl_;
  BenchReport r;
  r.lines = ready_lines();
  // A DFS-1 controller answers every request (an ACK, data or a NAK) but a global one (DFS-1 manual:
  // UID 0 gets no reply) and one overtaken by the next request.
  for (std::size_t i = 0; i < served(); ++i) {
    const Counters c = counters(i);
    r.devices.push_back({std::string(c.name), std::string(c.line), c.address, c.telegrams, c.answers, c.errors, c.dropped});
  }
  r.events = m.events;
  return r;
}

std::string format_bench_text(const BenchReport& r) {
  std::string out = "test bench:\n";
  for (const std::string& l : r.lines) out += "  served " + l + "\n";
  for (const BenchDeviceReport& d : r.devices) {
    out += "  " + d.name + " (" + d.line + " " + (d.line == "dfs1" ? "uid " : "address ") + std::to_string(d.address) +
           "): " + std::to_string(d.telegrams) + " telegram(s), " + std::to_string(d.answers) + " answer(s), " +
           std::to_string(d.errors) + " check error(s), " + std::to_string(d.dropped) + " dropped\n";
  }
  for (const std::string& e : r.events) out += "  " + e + "\n";
  return out;
}

std::string format_bench_json(const BenchReport& r) {
  nlohmann::json devices = nlohmann::json::array();
  for (const BenchDeviceReport& d : r.devices) {
    devices.push_back({{"name", d.name},
                       {"line", d.line},
                       {"address", d.address},
                       {"telegrams", d.telegrams},
                       {"answers", d.answers},
                       {"errors", d.errors},
                       {"dropped", d.dropped}});
  }
  return nlohmann::json{{"lines", r.lines}, {"devices", devices}, {"events", r.events}}.dump();
}

}  // namespace ibs::cli
