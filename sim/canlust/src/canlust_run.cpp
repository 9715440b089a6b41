#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#if defined(IBS_HAVE_PCAP)
#include "ibs/can/pcap_writer.hpp"
#endif
#include "ibs/can/virtual_bus.hpp"
#include "ibs/devices/drives.hpp"
#include "ibs/sim/canlust_scenario.hpp"
#include "ibs/sim/scenario.hpp"
#include "canlust_reader.hpp"
#include "run_summary.hpp"

namespace ibs::sim::canlust {

namespace cl = ibs::canlust;

namespace {

constexpr Duration kLoadWindow = std::chrono::milliseconds(100);

struct Drive {
  explicit Drive(const DriveSpec& s, std::unique_ptr<devices::CanlustDrive> d) : spec(s), device(std::move(d)) {}
  DriveSpec spec;
  std::unique_ptr<devices::CanlustDrive> device;  // the drive's wing, found in the registry by its type
  can::NodeId bus_id = 0;
  bool on = false;
  std::optional<Time> power_on_at;  // pending mains on
  DriveResult result;
  std::optional<drivecom::State> last_state;
  cl::SystemState last_system = cl::SystemState::logon;
};

struct PendingRead {
  std::size_t entry = 0;
  cl::RequestId id = 0;
  std::uint16_t parameter = 0;
  bool is_string = false;
  bool write = false;
};

std::string seconds(Time t) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f s", to_ms(t) / 1000.0);
  return b;
}

}  // namespace

Report run(const Scenario& s, const std::string& pcap_path) {
  // The host's time for the run summary's wall_s (the simulation itself runs on simulated time).
  const auto wall_start = std::chrono::steady_clock::now();
  can::VirtualBus bus({s.bitrate, 256, 4096});
  const can::NodeId master_id = bus.attach("master");
  const can::NodeId spy = bus.attach("spy");

  // The drives and their master through the registry's CANLust face of the scenario's type (the
  // reader took only drives that speak CANLust, all of one type: one master drives them).
  if (s.drives.empty()) throw std::invalid_argument("scenario " + s.name + ": a CANLust bus needs at least one drive");
  const devices::CanlustFace& face = canlust_face(s.drives.front().kind);
  devices::CanlustMasterOptions mo;
  mo.ids.step = static_cast<std::uint8_t>(s.id_step);
  mo.control_period = s.control_period;
  std::uint16_t slowest_status = 1;
  for (const auto& d : s.drives) {
    mo.drives.push_back({d.address, d.cacnf, 400.0});
    slowest_status = std::max(slowest_status, d.status_ms);
  }
  mo.status_period = std::chrono::milliseconds(slowest_status);
  const std::unique_ptr<devices::CanlustMaster> master = face.make_master(mo);
  devices::CanlustMaster& driver = *master;

  std::vector<std::unique_ptr<Drive>> drives;
  for (const auto& d : s.drives) {
    devices::CanlustFaceOptions c;
    c.ids.step = static_cast<std::uint8_t>(s.id_step);
    c.address = d.address;
    c.cacnf = d.cacnf;
    c.bitrate = s.bitrate;
    c.watchdog_ms = d.watchdog_ms;
    c.status_ms = d.status_ms;
    auto drive = std::make_unique<Drive>(d, canlust_face(d.kind).make(c));
    drive->bus_id = bus.attach(d.name);
    drive->power_on_at = d.power_on;
    drive->result.name = d.name;
    drive->result.kind = d.kind;
    drive->result.address = d.address;
    drives.push_back(std::move(drive));
  }
  const auto find = [&](const std::string& name) -> Drive& {
    for (auto& d : drives) {
      if (d->spec.name == name) return *d;
    }
    throw std::logic_error("unknown drive " + name);  // the reader checked the names
  };

#if defined(IBS_HAVE_PCAP)
  std::unique_ptr<can::PcapWriter> pcap;
  if (!pcap_path.empty()) {
    auto opened = can::PcapWriter::open(pcap_path);
    if (!opened) throw std::runtime_error(pcap_path + ": " + opened.error);
    pcap = std::move(opened.transport);
  }
#else
  struct NoPcap {
    void write(const cl::CanFrame&, Time) {}
  };
  std::unique_ptr<NoPcap> pcap;
  if (!pcap_path.empty()) throw std::runtime_error(pcap_path + ": this build has no libpcap (libpcap-dev)");
#endif

  Report report;
  report.name = s.name;
  report.duration = s.duration;
  report.bitrate = s.bitrate;
  report.entries.resize(s.timeline.size());
  std::vector<PendingRead> pending;
  std::size_t next_entry = 0;
  Time silent_until = Time::min();
  Time now{0};
  Time window_start{0};
  Duration window_busy{};
  Duration last_busy{};

  const auto next_time = [&]() {
    Time t = std::min(bus.next_event(), driver.next_deadline());
    for (const auto& d : drives) {
      if (d->on) t = std::min(t, d->device->next_deadline());
      if (d->power_on_at) t = std::min(t, *d->power_on_at);
    }
    if (next_entry < s.timeline.size()) t = std::min(t, s.timeline[next_entry].at);
    if (silent_until > now) t = std::min(t, silent_until);
    t = std::min(t, window_start + kLoadWindow);
    return std::max(t, now);
  };

  const auto apply = [&](std::size_t i) {
    const Entry& e = s.timeline[i];
    EntryResult& r = report.entries[i];
    r.at = e.at;
    r.device = e.device;
    switch (e.action) {
      case Action::read:
      case Action::write: r.type = "parameter"; break;
      case Action::mains_reset:
      case Action::mains_off:
      case Action::mains_on:
      case Action::master_silent: r.type = "fault"; break;
      default: r.type = "command"; break;
    }
    r.what = (e.device.empty() ? std::string() : e.device + ": ") + std::string(to_string(e.action));
    switch (e.action) {
      case Action::start:
        driver.system_start(now);
        r.outcome = "broadcast";
        return;
      case Action::stop:
        driver.system_stop(now);
        r.outcome = "broadcast";
        return;
      case Action::master_silent:
        silent_until = now + e.duration;
        r.what += " for " + format_time(e.duration);
        r.outcome = "until " + seconds(silent_until);
        return;
      default:
        break;
    }
    Drive& d = find(e.device);
    switch (e.action) {
      case Action::state:
        r.what += " " + std::string(drivecom::to_string(e.target));
        r.ok = driver.request(d.spec.address, e.target, now);
        r.outcome = r.ok ? "requested" : "refused";
        return;
      case Action::easydrive: {
        char b[16];
        std::snprintf(b, sizeof b, " %04X", static_cast<unsigned>(e.bits));
        r.what += b;
        r.ok = driver.set_easydrive(d.spec.address, e.bits);
        r.outcome = r.ok ? "set" : "refused";
        return;
      }
      case Action::reference: {
        char b[48];
        std::snprintf(b, sizeof b, " %.2f Hz", e.hz);
        r.what += b;
        const auto refusal = driver.set_reference_hz(d.spec.address, e.hz);
        r.ok = !refusal;
        r.outcome = r.ok ? "set" : "refused: " + std::string(*refusal);
        return;
      }
      case Action::read:
      case Action::write: {
        const auto p = face.parameter(e.parameter);  // the reader took only the table's parameters
        r.what += " " + p->name + (e.action == Action::write ? " := " + e.value : "");
        const devices::CanlustSubmission sub = e.action == Action::read ? driver.read(d.spec.address, e.parameter)
                                                                         : driver.write(d.spec.address, e.parameter, e.value);
        if (!sub) {
          r.ok = false;
          r.outcome = "not sent: " + sub.error;
          return;
        }
        pending.push_back({i, sub.id, p->number, p->is_string, e.action == Action::write});
        r.outcome = "pending";
        return;
      }
      case Action::mains_reset:
        d.device->power_on(now);
        d.on = true;
        r.outcome = "done";
        return;
      case Action::mains_off:
        d.device->power_off();
        d.on = false;
        d.power_on_at.reset();
        r.outcome = "done";
        return;
      case Action::mains_on:
        if (!d.on) d.power_on_at = now;
        r.outcome = d.on ? "already on" : "done";
        return;
      default:
        return;
    }
  };

  const auto observe = [&]() {
    for (auto& d : drives) {
      if (!d->on) continue;
      const drivecom::State st = d->device->state();
      if (!d->last_state || *d->last_state != st) {
        d->result.states.push_back({now, std::string(drivecom::to_string(st))});
        d->last_state = st;
      }
      const cl::SystemState sys = d->device->system_state();
      if (sys == cl::SystemState::start && d->last_system != cl::SystemState::start && !d->result.started) {
        d->result.started = now;
      }
      d->last_system = sys;
    }
    for (auto it = pending.begin(); it != pending.end();) {
      const auto poll = driver.poll(it->id);
      if (poll.state != cl::RequestState::done || poll.outcome == nullptr) {
        ++it;
        continue;
      }
      EntryResult& r = report.entries[it->entry];
      const cl::Outcome& o = *poll.outcome;
      r.ok = o.kind == cl::OutcomeKind::done;
      if (!r.ok) {
        r.outcome = cl::describe(o);
      } else if (it->is_string) {
        r.outcome = it->write ? "ok" : "\"" + std::string(o.text.view()) + "\"";
      } else {
        r.outcome = (it->write ? "ok, " : "") + face.format_value(it->parameter, o.value);
      }
      r.outcome += " (" + seconds(o.finished) + ")";
      it = pending.erase(it);
    }
  };

  const auto process = [&](Time t) {
    now = t;
    for (auto& d : drives) {
      if (d->power_on_at && now >= *d->power_on_at) {
        d->device->power_on(*d->power_on_at);
        d->on = true;
        d->power_on_at.reset();
      }
    }
    while (next_entry < s.timeline.size() && s.timeline[next_entry].at <= now) apply(next_entry++);
    bus.advance(now);
    while (auto seen = bus.receive(spy)) {
      if (pcap) pcap->write(seen->frame, seen->start);
      if (const auto c = mo.ids.classify(seen->frame.id); c && c->kind == cl::TelegramKind::logon) {
        for (auto& d : drives) {
          if (d->spec.address == c->address && !d->result.logon) d->result.logon = seen->start;
        }
      }
    }
    while (auto r = bus.receive(master_id)) driver.receive(r->frame, r->time);
    for (auto& d : drives) {
      while (auto r = bus.receive(d->bus_id)) {
        if (d->on) d->device->receive(r->frame, r->time);
      }
    }
    driver.cycle(now);
    const bool silent = now < silent_until;
    while (auto f = driver.take_frame()) {
      if (!silent) bus.send(master_id, *f, now);
    }
    while (auto e = driver.take_error()) {
      for (auto& d : drives) {
        if (d->spec.address == e->address) ++d->result.errors;
      }
    }
    for (auto& d : drives) {
      if (!d->on) continue;
      d->device->step(now);
      while (auto f = d->device->take_frame()) bus.send(d->bus_id, *f, now);
    }
    bus.advance(now);
    observe();
    // The busiest window of the load.
    if (now >= window_start + kLoadWindow) {
      const Duration busy = bus.stats().busy;
      window_busy = busy - last_busy;
      last_busy = busy;
      report.peak_load = std::max(report.peak_load, static_cast<double>(window_busy.count()) /
                                                        static_cast<double>((now - window_start).count()));
      window_start = now;
    }
  };

  for (std::uint64_t guard = 0; guard < 500'000'000ULL; ++guard) {
    const Time t = next_time();
    if (t >= Time{0} + s.duration) break;
    process(t);
  }
  process(Time{0} + s.duration);

  const can::BusStats& st = bus.stats();
  report.frames = st.frames;
  report.bits = st.bits;
  report.stuff_bits = st.stuff_bits;
  report.arbitration_losses = st.arbitration_losses;
  report.overflows = st.tx_overflows + st.rx_overflows;
  report.load = st.load();
  std::optional<Time> first;
  std::optional<Time> last;
  for (auto& d : drives) {
    DriveResult& r = d->result;
    r.system_state = d->on ? std::string(cl::to_string(d->device->system_state())) : "off";
    r.state = d->on ? std::string(drivecom::to_string(d->device->state())) : "off";
    r.actual_hz = d->on ? d->device->actual_hz(now) : 0.0;
    r.reference_hz = d->on ? d->device->reference_hz() : 0.0;
    r.watchdog_trips = d->device->watchdog_trips();
    r.status = driver.status_text(d->spec.address).value_or("none received");
    if (r.started) {
      first = first ? std::min(*first, *r.started) : *r.started;
      last = last ? std::max(*last, *r.started) : *r.started;
    }
    report.drives.push_back(r);
  }
  if (first && last && report.drives.size() > 1) report.start_spread = *last - *first;
  for (auto& e : report.entries) {
    if (e.outcome == "pending") {
      e.ok = false;
      e.outcome = "no answer before the end of the run";
    }
  }
#if defined(IBS_HAVE_PCAP)
  if (pcap) {
    pcap->flush();
    pcap.reset();  // closed: the caller may rename it into place
  }
#endif
  report.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return report;
}

std::string format_text(const Report& r) {
  std::ostringstream o;
  char b[256];
  // The drives by their manual's name ("CDA3000") when they are all of one registered type.
  std::string title;
  for (const auto& d : r.drives) {
    const devices::Drive* drive = devices::find_drive(d.kind, devices::Bus::canlust);
    const std::string t = drive != nullptr ? std::string(drive->canlust->title) : std::string();
    title = &d == &r.drives.front() || t == title ? t : std::string();
  }
  o << "scenario " << r.name << ": CANLust, " << r.drives.size() << " " << (title.empty() ? "" : title + " ") << "drive"
    << (r.drives.size() == 1 ? "" : "s")
    << ", " << r.bitrate / 1000 << " kbit/s, " << format_time(r.duration) << " simulated\n";
  std::snprintf(b, sizeof b, "bus: %llu frames, %llu bits (%llu stuff), load %.1f %% (busiest 100 ms: %.1f %%), "
                "%llu arbitration losses, %llu overflows\n",
                static_cast<unsigned long long>(r.frames), static_cast<unsigned long long>(r.bits),
                static_cast<unsigned long long>(r.stuff_bits), 100.0 * r.load, 100.0 * r.peak_load,
                static_cast<unsigned long long>(r.arbitration_losses), static_cast<unsigned long long>(r.overflows));
  o << b;
  if (r.start_spread) o << "System Start executed by every drive within " << format_time(*r.start_spread) << "\n";
  for (const auto& d : r.drives) {
    std::snprintf(b, sizeof b, "%s (address %u): %s, %s, %.2f Hz (reference %.2f Hz), logon %s, start %s, "
                  "watchdog trips %u, error telegrams %u\n",
                  d.name.c_str(), unsigned{d.address}, d.system_state.c_str(), d.state.c_str(), d.actual_hz,
                  d.reference_hz, d.logon ? seconds(*d.logon).c_str() : "-", d.started ? seconds(*d.started).c_str() : "-",
                  d.watchdog_trips, d.errors);
    o << b;
    o << "  status " << d.status << "\n";
    o << "  states:";
    for (const auto& c : d.states) o << " " << seconds(c.at) << " " << c.state << ";";
    o << "\n";
  }
  for (const auto& e : r.entries) {
    o << seconds(e.at) << "  " << e.what << ": " << e.outcome << (e.ok ? "" : "  [failed]") << "\n";
  }
  return o.str();
}

std::string format_json(const Report& r) {
  using json = nlohmann::ordered_json;
  json bus = {{"bitrate", r.bitrate},
              {"frames", r.frames},
              {"bits", r.bits},
              {"stuff_bits", r.stuff_bits},
              {"load", r.load},
              {"peak_load_100ms", r.peak_load},
              {"arbitration_losses", r.arbitration_losses},
              {"overflows", r.overflows}};
  if (r.start_spread) bus["start_spread_ms"] = to_ms(*r.start_spread);
  json devices = json::array();
  for (const auto& d : r.drives) {
    json states = json::array();
    for (const auto& c : d.states) states.push_back({{"at_ms", to_ms(c.at)}, {"what", c.state}});
    json x{{"name", d.name},
           {"kind", d.kind},
           {"state", d.state},
           {"unit", "Hz"},
           {"reference", d.reference_hz},
           {"actual", d.actual_hz},
           {"states", states},
           {"address", d.address},
           {"system_state", d.system_state},
           {"status", d.status},
           {"watchdog_trips", d.watchdog_trips},
           {"error_telegrams", d.errors}};
    if (d.logon) x["logon_ms"] = to_ms(*d.logon);
    if (d.started) x["started_ms"] = to_ms(*d.started);
    devices.push_back(x);
  }
  json events = json::array();
  for (const auto& e : r.entries) {
    // The text names the device before the action ("left: read 575-CASCY"); the event has it apart.
    const std::string prefix = e.device.empty() ? std::string() : e.device + ": ";
    const std::string what = e.what.rfind(prefix, 0) == 0 ? e.what.substr(prefix.size()) : e.what;
    events.push_back({{"at_ms", to_ms(e.at)},
                      {"device", e.device},
                      {"type", e.type},
                      {"what", what},
                      {"outcome", e.outcome},
                      {"ok", e.ok}});
  }
  return sim::detail::run_summary(r.name, "canlust", r.duration, r.wall_seconds, 1, std::move(bus),
                                  std::move(devices), std::move(events))
             .dump(2) +
         "\n";
}

}  // namespace ibs::sim::canlust
