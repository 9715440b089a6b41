#include <time.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
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
#include "ibs/can/socketcan.hpp"
#include "ibs/can/udp.hpp"
#include "ibs/can/virtual_bus.hpp"
#include "ibs/devices/drives.hpp"
#include "ibs/sim/canlust_scenario.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/tool/format.hpp"
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

using tool::seconds;

Drive& find(std::vector<std::unique_ptr<Drive>>& drives, const std::string& name) {
  for (auto& d : drives) {
    if (d->spec.name == name) return *d;
  }
  throw std::logic_error("unknown drive " + name);  // the reader checked the names
}

// The drives of the scenario, each through its type's face; attached to `bus` when there is one.
std::vector<std::unique_ptr<Drive>> make_drives(const Scenario& s, can::VirtualBus* bus) {
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
    if (bus != nullptr) drive->bus_id = bus->attach(d.name);
    drive->power_on_at = d.power_on;
    drive->result.name = d.name;
    drive->result.kind = d.kind;
    drive->result.address = d.address;
    drives.push_back(std::move(drive));
  }
  return drives;
}

std::string entry_type(Action a) {
  switch (a) {
    case Action::read:
    case Action::write: return "parameter";
    case Action::mains_reset:
    case Action::mains_off:
    case Action::mains_on:
    case Action::device_fault:
    case Action::master_silent: return "fault";
    default: return "command";
  }
}

void power_on_when_due(Drive& d, Time now) {
  if (d.power_on_at && now >= *d.power_on_at) {
    d.device->power_on(*d.power_on_at);
    d.on = true;
    d.power_on_at.reset();
  }
}

// The events a drive takes without a master: mains, a device fault, the load, an input.
void apply_drive_event(Drive& d, const Entry& e, EntryResult& r, Time now) {
  switch (e.action) {
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
    case Action::device_fault:
    case Action::load:
    case Action::input: {
      const devices::CanlustEvent ev = event_of(e);
      if (e.action == Action::device_fault) r.what += " " + e.cause;
      if (e.action == Action::input) r.what += " " + e.input + (e.level ? " high" : " low");
      if (e.action == Action::load) {
        r.what += " " + tool::fixed(e.load, 1, "%");
      }
      // The load and the terminals stay while the mains is off; a fault needs a drive that is on
      // (the drive says so).
      const devices::CanlustEventResult res = d.device->apply(ev, now);
      r.ok = res.ok;
      r.outcome = res.text;
      return;
    }
    default:
      return;
  }
}

void observe_drive(Drive& d, Time now) {
  if (!d.on) return;
  const drivecom::State st = d.device->state();
  if (!d.last_state || *d.last_state != st) {
    d.result.states.push_back({now, std::string(drivecom::to_string(st))});
    d.last_state = st;
  }
  const cl::SystemState sys = d.device->system_state();
  if (sys == cl::SystemState::start && d.last_system != cl::SystemState::start && !d.result.started) {
    d.result.started = now;
  }
  d.last_system = sys;
}

// A run's capture (docs/pcap.md), the same for the simulated bus and a served one: nullptr
// without a path; a build without libpcap refuses a path.
#if defined(IBS_HAVE_PCAP)
using Capture = can::PcapWriter;
std::unique_ptr<Capture> open_capture(const std::string& pcap_path) {
  if (pcap_path.empty()) return nullptr;
  auto opened = can::PcapWriter::open(pcap_path);
  if (!opened) throw std::runtime_error(pcap_path + ": " + opened.error);
  // The run's time counts from its wall-clock start in the capture (not from 1970).
  opened.transport->set_epoch(
      std::chrono::duration_cast<Time>(std::chrono::system_clock::now().time_since_epoch()));
  return std::move(opened.transport);
}
#else
struct Capture {
  void write(const cl::CanFrame&, Time) {}
};
std::unique_ptr<Capture> open_capture(const std::string& pcap_path) {
  if (!pcap_path.empty()) throw std::runtime_error(pcap_path + ": this build has no libpcap (libpcap-dev)");
  return nullptr;
}
#endif

// The report's head, the same for either engine: the scenario's name, duration and rate, one
// result per timeline entry.
Report report_head(const Scenario& s) {
  Report r;
  r.name = s.name;
  r.duration = s.duration;
  r.bitrate = s.bitrate;
  r.entries.resize(s.timeline.size());
  return r;
}

void finish_drive(Drive& d, Time now) {
  DriveResult& r = d.result;
  r.system_state = d.on ? std::string(cl::to_string(d.device->system_state())) : "off";
  r.state = d.on ? std::string(drivecom::to_string(d.device->state())) : "off";
  r.actual_hz = d.on ? d.device->actual_hz(now) : 0.0;
  r.reference_hz = d.on ? d.device->reference_hz() : 0.0;
  r.watchdog_trips = d.device->watchdog_trips();
}

}  // namespace

namespace {

// The simulated bus: the scenario's master and drives on the virtual bus, stepped from event to
// event (`advance_to`); `run` goes to the end at once, `run_realtime` step by step at deadlines.
class Simulation {
 public:
  Simulation(const Scenario& s, const std::string& pcap_path) : s_(s), bus_({s.bitrate, 256, 4096}) {
    master_id_ = bus_.attach("master");
    spy_ = bus_.attach("spy");
    // The drives and their master through the registry's CANLust face of the scenario's type (the
    // reader took only drives that speak CANLust, all of one type: one master drives them).
    if (s.drives.empty()) throw std::invalid_argument("scenario " + s.name + ": a CANLust bus needs at least one drive");
    face_ = &canlust_face(s.drives.front().kind);
    mo_.ids.step = static_cast<std::uint8_t>(s.id_step);
    mo_.control_period = s.control_period;
    std::uint16_t slowest_status = 1;
    for (const auto& d : s.drives) {
      mo_.drives.push_back({d.address, d.cacnf, 400.0});
      slowest_status = std::max(slowest_status, d.status_ms);
    }
    mo_.status_period = std::chrono::milliseconds(slowest_status);
    master_ = face_->make_master(mo_);
    drives_ = make_drives(s, &bus_);

    pcap_ = open_capture(pcap_path);
    report_ = report_head(s);
  }

  // Everything due up to `t`, then the state at `t`.
  void advance_to(Time t) {
    for (std::uint64_t guard = 0; guard < 500'000'000ULL; ++guard) {
      const Time next = next_time();
      if (next >= t) break;
      process(next);
    }
    process(t);
  }

  // A control entry, applied now and listed with the timeline's.
  void inject(Entry e) {
    e.at = now_;
    report_.entries.emplace_back();
    apply(e, report_.entries.size() - 1);
  }

  Report finish(double wall_seconds) {
    const can::BusStats& st = bus_.stats();
    report_.frames = st.frames;
    report_.bits = st.bits;
    report_.stuff_bits = st.stuff_bits;
    report_.arbitration_losses = st.arbitration_losses;
    report_.overflows = st.tx_overflows + st.rx_overflows;
    report_.load = st.load();
    std::optional<Time> first;
    std::optional<Time> last;
    for (auto& d : drives_) {
      DriveResult& r = d->result;
      finish_drive(*d, now_);
      r.status = master_->status_text(d->spec.address).value_or("none received");
      if (r.started) {
        first = first ? std::min(*first, *r.started) : *r.started;
        last = last ? std::max(*last, *r.started) : *r.started;
      }
      report_.drives.push_back(r);
    }
    if (first && last && report_.drives.size() > 1) report_.start_spread = *last - *first;
    for (auto& e : report_.entries) {
      if (e.outcome == "pending") {
        e.ok = false;
        e.outcome = "no answer before the end of the run";
      }
    }
    std::stable_sort(report_.entries.begin(), report_.entries.end(),
                     [](const EntryResult& a, const EntryResult& b) { return a.at < b.at; });
#if defined(IBS_HAVE_PCAP)
    if (pcap_) {
      pcap_->flush();
      pcap_.reset();  // closed: the caller may rename it into place
    }
#endif
    report_.wall_seconds = wall_seconds;
    return std::move(report_);
  }

 private:
  Time next_time() const {
    Time t = std::min(bus_.next_event(), master_->next_deadline());
    for (const auto& d : drives_) {
      if (d->on) t = std::min(t, d->device->next_deadline());
      if (d->power_on_at) t = std::min(t, *d->power_on_at);
    }
    if (next_entry_ < s_.timeline.size()) t = std::min(t, s_.timeline[next_entry_].at);
    if (silent_until_ > now_) t = std::min(t, silent_until_);
    t = std::min(t, window_start_ + kLoadWindow);
    return std::max(t, now_);
  }

  void apply(const Entry& e, std::size_t i) {
    EntryResult& r = report_.entries[i];
    r.at = now_;
    r.device = e.device;
    r.type = entry_type(e.action);
    r.what = (e.device.empty() ? std::string() : e.device + ": ") + std::string(to_string(e.action));
    devices::CanlustMaster& driver = *master_;
    switch (e.action) {
      case Action::start:
        driver.system_start(now_);
        r.outcome = "broadcast";
        return;
      case Action::stop:
        driver.system_stop(now_);
        r.outcome = "broadcast";
        return;
      case Action::master_silent:
        silent_until_ = now_ + e.duration;
        r.what += " for " + format_time(e.duration);
        r.outcome = "until " + seconds(silent_until_);
        return;
      default:
        break;
    }
    Drive& d = find(drives_, e.device);
    switch (e.action) {
      case Action::state:
        r.what += " " + std::string(drivecom::to_string(e.target));
        r.ok = driver.request(d.spec.address, e.target, now_);
        r.outcome = r.ok ? "requested" : "refused";
        return;
      case Action::easydrive: {
        r.what += " " + tool::hex4(e.bits);
        r.ok = driver.set_easydrive(d.spec.address, e.bits);
        r.outcome = r.ok ? "set" : "refused";
        return;
      }
      case Action::reference: {
        r.what += " " + tool::fixed(e.hz, 2, "Hz");
        const auto refusal = driver.set_reference_hz(d.spec.address, e.hz);
        r.ok = !refusal;
        r.outcome = r.ok ? "set" : "refused: " + std::string(*refusal);
        return;
      }
      case Action::read:
      case Action::write: {
        const auto p = face_->parameter(e.parameter);  // the reader took only the table's parameters
        r.what += " " + p->name + (e.action == Action::write ? " := " + e.value : "");
        const devices::CanlustSubmission sub = e.action == Action::read ? driver.read(d.spec.address, e.parameter)
                                                                         : driver.write(d.spec.address, e.parameter, e.value);
        if (!sub) {
          r.ok = false;
          r.outcome = "not sent: " + sub.error;
          return;
        }
        pending_.push_back({i, sub.id, p->number, p->is_string, e.action == Action::write});
        r.outcome = "pending";
        return;
      }
      default:
        apply_drive_event(d, e, r, now_);
        return;
    }
  }

  void observe() {
    for (auto& d : drives_) observe_drive(*d, now_);
    for (auto it = pending_.begin(); it != pending_.end();) {
      const auto poll = master_->poll(it->id);
      if (poll.state != cl::RequestState::done || poll.outcome == nullptr) {
        ++it;
        continue;
      }
      EntryResult& r = report_.entries[it->entry];
      const cl::Outcome& o = *poll.outcome;
      r.ok = o.kind == cl::OutcomeKind::done;
      if (!r.ok) {
        r.outcome = cl::describe(o);
      } else if (it->is_string) {
        r.outcome = it->write ? "ok" : "\"" + std::string(o.text.view()) + "\"";
      } else {
        r.outcome = (it->write ? "ok, " : "") + face_->format_value(it->parameter, o.value);
      }
      r.outcome += " (" + seconds(o.finished) + ")";
      it = pending_.erase(it);
    }
  }

  void process(Time t) {
    now_ = t;
    devices::CanlustMaster& driver = *master_;
    for (auto& d : drives_) power_on_when_due(*d, now_);
    while (next_entry_ < s_.timeline.size() && s_.timeline[next_entry_].at <= now_) {
      apply(s_.timeline[next_entry_], next_entry_);
      ++next_entry_;
    }
    bus_.advance(now_);
    while (auto seen = bus_.receive(spy_)) {
      if (pcap_) pcap_->write(seen->frame, seen->start);
      if (const auto c = mo_.ids.classify(seen->frame.id); c && c->kind == cl::TelegramKind::logon) {
        for (auto& d : drives_) {
          if (d->spec.address == c->address && !d->result.logon) d->result.logon = seen->start;
        }
      }
    }
    while (auto r = bus_.receive(master_id_)) driver.receive(r->frame, r->time);
    for (auto& d : drives_) {
      while (auto r = bus_.receive(d->bus_id)) {
        if (d->on) d->device->receive(r->frame, r->time);
      }
    }
    driver.cycle(now_);
    const bool silent = now_ < silent_until_;
    while (auto f = driver.take_frame()) {
      if (!silent) bus_.send(master_id_, *f, now_);
    }
    while (auto e = driver.take_error()) {
      for (auto& d : drives_) {
        if (d->spec.address == e->address) ++d->result.errors;
      }
    }
    for (auto& d : drives_) {
      if (!d->on) continue;
      d->device->step(now_);
      while (auto f = d->device->take_frame()) bus_.send(d->bus_id, *f, now_);
    }
    bus_.advance(now_);
    observe();
    // The busiest window of the load.
    if (now_ >= window_start_ + kLoadWindow) {
      const Duration busy = bus_.stats().busy;
      const Duration window_busy = busy - last_busy_;
      last_busy_ = busy;
      report_.peak_load = std::max(report_.peak_load, static_cast<double>(window_busy.count()) /
                                                          static_cast<double>((now_ - window_start_).count()));
      window_start_ = now_;
    }
  }

  const Scenario& s_;
  can::VirtualBus bus_;
  can::NodeId master_id_ = 0;
  can::NodeId spy_ = 0;
  const devices::CanlustFace* face_ = nullptr;
  devices::CanlustMasterOptions mo_;
  std::unique_ptr<devices::CanlustMaster> master_;
  std::vector<std::unique_ptr<Drive>> drives_;
  std::unique_ptr<Capture> pcap_;
  Report report_;
  std::vector<PendingRead> pending_;
  std::size_t next_entry_ = 0;
  Time silent_until_ = Time::min();
  Time now_{0};
  Time window_start_{0};
  Duration last_busy_{};
};

}  // namespace

Report run(const Scenario& s, const std::string& pcap_path) {
  // The host's time for the run summary's wall_s (the simulation itself runs on simulated time).
  const auto wall_start = std::chrono::steady_clock::now();
  Simulation sim(s, pcap_path);
  sim.advance_to(Time{0} + s.duration);
  return sim.finish(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
}

namespace {

std::int64_t monotonic_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1'000'000'000LL + ts.tv_nsec;
}

// An absolute deadline (TIMER_ABSTIME): the steps do not drift by the time their work takes.
void sleep_until_ns(std::int64_t deadline) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(deadline / 1'000'000'000LL);
  ts.tv_nsec = static_cast<long>(deadline % 1'000'000'000LL);
  while (::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

// The scenario's drives on a real transport for the user's own master: every frame from the bus
// goes to every drive that is on, what a drive sends goes to the bus and to the other drives (they
// would see it on a real bus too). No master, no virtual bus.
class Served {
 public:
  explicit Served(const Scenario& s, const std::string& pcap_path) : s_(s) {
    drives_ = make_drives(s, nullptr);
    face_ = &canlust_face(s.drives.front().kind);
    ids_.step = static_cast<std::uint8_t>(s.id_step);
    const std::string& b = s.bus;
    if (b.rfind("udp:", 0) == 0) {
      const auto c1 = b.find(':', 4);
      const auto c2 = b.find(':', c1 + 1);
      const auto port = [&](const std::string& text) {
        int v = -1;
        const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
        if (text.empty() || r.ec != std::errc{} || r.ptr != text.data() + text.size() || v < 0 || v > 65535) {
          throw std::runtime_error("bus = \"" + b + "\": '" + text + "' is not a port number (0..65535)");
        }
        return static_cast<std::uint16_t>(v);
      };
      can::UdpConfig u;
      u.local_port = port(b.substr(4, c1 - 4));
      u.local_host = b.substr(c1 + 1, c2 - c1 - 1);
      if (u.local_host == "localhost") u.local_host = "127.0.0.1";
      u.remote_host = u.local_host;
      u.remote_port = port(b.substr(c2 + 1));
      auto opened = can::UdpCanTransport::open(u);
      if (!opened) throw std::runtime_error("bus = \"" + b + "\": " + opened.error);
      ready_ = "canlust udp: " + std::to_string(opened.transport->local_port());
      bus_ = std::move(opened.transport);
    } else {
      const std::string iface = b.substr(std::string("socketcan:").size());
      auto opened = can::SocketCan::open(iface);
      if (!opened) throw std::runtime_error("bus = \"" + b + "\": " + opened.error);
      ready_ = "canlust socketcan: " + iface;
      bus_ = std::move(opened.transport);
    }
    pcap_ = open_capture(pcap_path);
    report_ = report_head(s);
    last_status_.resize(drives_.size());
  }

  [[nodiscard]] const std::string& ready() const { return ready_; }

  void advance_to(Time t) {
    now_ = t;
    for (auto& d : drives_) power_on_when_due(*d, now_);
    while (next_entry_ < s_.timeline.size() && s_.timeline[next_entry_].at <= now_) {
      apply(s_.timeline[next_entry_], next_entry_);
      ++next_entry_;
    }
    for (int n = 0; n < 4096; ++n) {
      const can::Received r = bus_->receive(Duration::zero());
      if (r.status == can::IoStatus::error) ++bus_errors_;
      if (r.status != can::IoStatus::ok) break;
      if (pcap_) pcap_->write(r.frame, now_);
      const auto c = ids_.classify(r.frame.id);
      for (auto& d : drives_) {
        if (!d->on) continue;
        if (c && (c->kind == cl::TelegramKind::system || c->address == d->spec.address)) ++d->result.frames_received;
        d->device->receive(r.frame, now_);
      }
    }
    for (std::size_t i = 0; i < drives_.size(); ++i) {
      Drive& d = *drives_[i];
      if (!d.on) continue;
      d.device->step(now_);
      while (auto f = d.device->take_frame()) {
        ++d.result.frames_sent;
        if (pcap_) pcap_->write(*f, now_);
        if (bus_->send(*f) != can::IoStatus::ok) ++bus_errors_;
        const auto c = ids_.classify(f->id);
        if (c && c->kind == cl::TelegramKind::status && f->dlc >= 2) {
          last_status_[i] = static_cast<Word>(f->data[0] | (f->data[1] << 8));
        }
        if (c && c->kind == cl::TelegramKind::logon && !d.result.logon) d.result.logon = now_;
        if (c && c->kind == cl::TelegramKind::error) ++d.result.errors;
        for (auto& other : drives_) {
          if (other.get() != &d && other->on) other->device->receive(*f, now_);
        }
      }
    }
    for (auto& d : drives_) observe_drive(*d, now_);
  }

  void inject(Entry e) {
    e.at = now_;
    report_.entries.emplace_back();
    apply(e, report_.entries.size() - 1);
  }

  Report finish(double wall_seconds) {
    for (std::size_t i = 0; i < drives_.size(); ++i) {
      Drive& d = *drives_[i];
      finish_drive(d, now_);
      if (!last_status_[i]) {
        d.result.status = "none sent";
      } else if (d.spec.cacnf == 4) {
        d.result.status = "EasyDrive " + tool::hex4(*last_status_[i]);
      } else {
        d.result.status = face_->explain_status_word(*last_status_[i]);
      }
      report_.drives.push_back(d.result);
    }
    std::stable_sort(report_.entries.begin(), report_.entries.end(),
                     [](const EntryResult& a, const EntryResult& b) { return a.at < b.at; });
#if defined(IBS_HAVE_PCAP)
    if (pcap_) {
      pcap_->flush();
      pcap_.reset();
    }
#endif
    report_.wall_seconds = wall_seconds;
    return std::move(report_);
  }

  [[nodiscard]] std::uint64_t bus_errors() const { return bus_errors_; }

 private:
  void apply(const Entry& e, std::size_t i) {
    EntryResult& r = report_.entries[i];
    r.at = now_;
    r.device = e.device;
    r.type = entry_type(e.action);
    r.what = e.device + ": " + std::string(to_string(e.action));
    apply_drive_event(find(drives_, e.device), e, r, now_);
  }

  const Scenario& s_;
  std::vector<std::unique_ptr<Drive>> drives_;
  const devices::CanlustFace* face_ = nullptr;
  cl::IdentifierMap ids_{};
  std::unique_ptr<can::CanTransport> bus_;
  std::string ready_;
  std::unique_ptr<Capture> pcap_;
  Report report_;
  std::vector<std::optional<Word>> last_status_;
  std::size_t next_entry_ = 0;
  Time now_{0};
  std::uint64_t bus_errors_ = 0;
};

// Steps `engine` to the end of the scenario at absolute deadlines, one `o.step` apart.
template <typename Engine>
Report pace(Engine& engine, const Scenario& s, const RealtimeOptions& o, std::string served) {
  if (o.step <= Duration::zero()) throw std::invalid_argument("run_realtime: the step must be above 0");
  Report::Realtime rt;
  rt.served = std::move(served);
  rt.step = o.step;
  if (o.ready && !rt.served.empty()) o.ready(rt.served);
  const Time end = Time{0} + s.duration;
  std::vector<Entry> control;
  const auto wall_start = std::chrono::steady_clock::now();
  const std::int64_t start = monotonic_ns();
  for (std::uint64_t k = 0;; ++k) {
    const Time t = std::min(end, Time{0} + o.step * static_cast<Duration::rep>(k));
    sleep_until_ns(start + (t - Time{0}).count());
    engine.advance_to(t);
    if (o.each_step) {
      control.clear();
      o.each_step(t, control);
      for (const Entry& e : control) engine.inject(e);
    }
    ++rt.cycles;
    // The step's work ended after the next step's deadline: an overrun.
    const std::int64_t late = monotonic_ns() - (start + (t - Time{0} + o.step).count());
    if (late > 0) {
      ++rt.overruns;
      if (!rt.first_overrun) rt.first_overrun = t;
      rt.worst_overrun = std::max(rt.worst_overrun, Duration(late));
    }
    if (t >= end || (o.stop && o.stop())) break;
  }
  Report r = engine.finish(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
  r.realtime = rt;
  return r;
}

}  // namespace

Report run_realtime(const Scenario& s, const RealtimeOptions& o, const std::string& pcap_path) {
  if (s.bus.empty()) {
    Simulation sim(s, pcap_path);
    return pace(sim, s, o, "");
  }
  Served served(s, pcap_path);
  Report r = pace(served, s, o, served.ready());
  r.realtime->bus_errors = served.bus_errors();
  return r;
}

std::string format_text(const Report& r) {
  std::ostringstream o;
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
  const bool served = r.realtime && !r.realtime->served.empty();
  if (!served) {
    o << fmt::format("bus: {} frames, {} bits ({} stuff), load {:.1f} % (busiest 100 ms: {:.1f} %), "
                     "{} arbitration losses, {} overflows\n",
                     r.frames, r.bits, r.stuff_bits, 100.0 * r.load, 100.0 * r.peak_load, r.arbitration_losses,
                     r.overflows);
  }
  if (r.realtime) {
    const Report::Realtime& rt = *r.realtime;
    o << "real time: " << (served ? "served on " + rt.served.substr(std::string("canlust ").size()) + " for your master, "
                                  : std::string())
      << rt.cycles << " steps of " << format_time(rt.step) << ", " << rt.overruns << " overruns";
    if (rt.overruns != 0) o << " (worst " << format_time(rt.worst_overrun) << ", first at " << seconds(*rt.first_overrun) << ")";
    if (served) o << ", " << rt.bus_errors << " bus errors";
    o << "\n";
  }
  if (r.start_spread) o << "System Start executed by every drive within " << format_time(*r.start_spread) << "\n";
  for (const auto& d : r.drives) {
    o << fmt::format("{} (address {}): {}, {}, {:.2f} Hz (reference {:.2f} Hz), logon {}, start {}, "
                     "watchdog trips {}, error telegrams {}\n",
                     d.name, unsigned{d.address}, d.system_state, d.state, d.actual_hz, d.reference_hz,
                     d.logon ? seconds(*d.logon) : "-", d.started ? seconds(*d.started) : "-", d.watchdog_trips,
                     d.errors);
    o << "  status " << d.status << "\n";
    if (served) o << "  frames: received " << d.frames_received << ", sent " << d.frames_sent << "\n";
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
  const bool served = r.realtime && !r.realtime->served.empty();
  if (r.realtime) {
    const Report::Realtime& rt = *r.realtime;
    json x{{"served", rt.served},
           {"step_ms", to_ms(rt.step)},
           {"cycles", rt.cycles},
           {"overruns", rt.overruns},
           {"worst_overrun_by_ms", to_ms(rt.worst_overrun)}};
    if (rt.first_overrun) x["first_overrun_at_ms"] = to_ms(*rt.first_overrun);
    if (served) x["bus_errors"] = rt.bus_errors;
    bus["realtime"] = x;
  }
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
    if (served) {
      x["frames_received"] = d.frames_received;
      x["frames_sent"] = d.frames_sent;
    }
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
