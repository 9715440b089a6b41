#include "ibs/board/run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "ibs/devices/registry.hpp"
#include "ibs/interbus/cycle_time.hpp"
#include "ibs/master/master_loop.hpp"
#include "ibs/sim/master_timeline.hpp"
#include "ibs/sim/realtime.hpp"

namespace ibs::board {

namespace {

std::string ms_text(Duration d) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f ms", static_cast<double>(d.count()) / 1e6);
  return b;
}

}  // namespace

MasterRing make_master_ring(const sim::Scenario& s) {
  if (s.devices.empty()) throw std::invalid_argument("scenario '" + s.name + "': no devices");
  MasterRing r;
  std::vector<interbus::DeviceSpec> specs;
  for (const sim::DeviceConfig& c : s.devices) {
    const devices::DriveKind* kind = devices::find_drive_kind(c.kind);
    if (kind == nullptr) {
      throw std::invalid_argument("device '" + c.name + "': unknown type '" + c.kind + "' (" +
                                  devices::drive_kind_names(", ", " or ", "\"") + ")");
    }
    devices::Configuration conf;
    try {
      conf = (*kind)->configure(sim::device_settings(c));
    } catch (const devices::SettingsError& e) {
      throw std::invalid_argument("device '" + c.name + "': " + e.what());
    }
    specs.push_back({c.name, conf.id_code, conf.bus});
    r.drivers.push_back((*kind)->make_driver(conf));
    r.kinds.push_back(c.kind);
  }
  try {
    r.config = interbus::make_bus_config(specs);
  } catch (const interbus::ConfigError& e) {
    throw std::invalid_argument(std::string("bus configuration: ") + e.what());
  }
  if (s.bus.cycle_time) {
    r.cycle_time = *s.bus.cycle_time;
  } else {
    interbus::CycleTimeParams p =
        interbus::params_for(s.bus.baud_2mbit ? interbus::BaudRate::mbit2 : interbus::BaudRate::kbit500);
    p.software_time = s.bus.software_time;
    r.cycle_time = interbus::cycle_time(r.config, p);
  }
  return r;
}

namespace {

// The loop's clock: the time of each cycle, and in real time the wait for its deadline with the
// wake-up latency and the overruns of `ibs run --realtime`.
class LoopClock {
 public:
  LoopClock(Clock kind, Duration period) : kind_(kind), period_(period), start_(sim::monotonic_ns()) {}
  // Cycle k's deadline, k = 1, 2, ...
  [[nodiscard]] Time deadline() const { return Time{0} + period_ * (k_ + 1); }
  // Waits for the next cycle; its time.
  Time next() {
    ++k_;
    const Time d = Time{0} + period_ * k_;
    if (kind_ == Clock::stepped) return d;
    const std::int64_t at = start_ + d.count();
    sim::sleep_until_ns(at);
    const std::int64_t woke = sim::monotonic_ns();
    wake_.push_back(static_cast<std::uint32_t>(std::clamp<std::int64_t>(woke - at, 0, 0xFFFFFFFF)));
    return Time{woke - start_};
  }
  // The cycle's work is done: an overrun when it ended after the next deadline.
  void done(sim::RealtimeStats& r) {
    if (kind_ == Clock::stepped) return;
    const Time cycle = Time{0} + period_ * k_;
    const std::int64_t late = sim::monotonic_ns() - (start_ + (cycle + period_).count());
    if (late <= 0) return;
    ++r.overruns;
    if (!r.first_overrun) r.first_overrun = cycle;
    if (Duration{late} > r.worst_overrun_by) {
      r.worst_overrun_by = Duration{late};
      r.worst_overrun = cycle;
    }
  }
  std::vector<std::uint32_t>& wake() { return wake_; }

 private:
  Clock kind_;
  Duration period_;
  std::int64_t start_;
  std::int64_t k_ = 0;
  std::vector<std::uint32_t> wake_;
};

std::string hex4(unsigned v) {
  char b[16];
  std::snprintf(b, sizeof b, "%04XH", v & 0xFFFFU);
  return b;
}

// What the board reported, as the summary's faults (the device's name where there is one).
sim::FaultRecord fault_of(const master::BoardEvent& e, const interbus::BusConfig& config, const std::string& board) {
  using K = master::BoardEvent::Kind;
  sim::FaultRecord f;
  f.at = e.at;
  f.kind = std::string(master::to_string(e.kind));
  const bool named = e.kind == K::peripheral_fault || e.kind == K::peripheral_ok ||
                     ((e.kind == K::segment_off || e.kind == K::segment_on) && e.number != 0);
  if (named && e.device < config.devices.size()) f.device = config.devices[e.device].name;
  switch (e.kind) {
    case K::bus_error: f.detail = "the board reports BUS: cycles without valid data"; break;
    case K::bus_ok: f.detail = "BUS cleared: the cycles carry valid data again"; break;
    case K::peripheral_fault:
      f.detail = "the board reports a module error of device " + hex4(e.number) + " (PF)";
      break;
    case K::peripheral_ok: f.detail = "device " + hex4(e.number) + " without a module error again"; break;
    case K::segment_off:
      f.detail = e.number != 0 ? "device " + hex4(e.number) + " switched off with its segment (BSA)"
                               : "the board reports a segment switched off (BSA)";
      break;
    case K::segment_on:
      f.detail = e.number != 0 ? "device " + hex4(e.number) + " switched on again" : "BSA cleared";
      break;
    case K::sysfail:
      f.detail = "the board's controller failed (SysFail): " +
                 master::ddi_call_text(e.call, board + "_D", e.code) + "; every device lost, the run ends";
      break;
    case K::call_failed:
      f.detail = master::ddi_call_text(e.call, board + (e.call == master::DdiCall::send_message ||
                                                                e.call == master::DdiCall::receive_message
                                                            ? "_M"
                                                            : "_D"),
                                       e.code);
      break;
    case K::service_refused: f.detail = "a diagnostic or segment service refused: result " + hex4(static_cast<unsigned>(e.code)); break;
    case K::user_error:
      f.detail = "the board reports USER: a service was refused (parameter register " + hex4(static_cast<unsigned>(e.code)) + ")";
      break;
  }
  return f;
}

std::string state_text(devices::DeviceDriver& d) {
  const auto seen = d.sequencer().report().state_seen;
  return seen ? std::string(drivecom::to_string(*seen)) : std::string("unknown");
}

}  // namespace

RunResult run(const sim::Scenario& scenario, const RunOptions& o) {
  RunResult res;
  res.board = o.board;
  res.clock = o.clock;
  MasterRing ring = make_master_ring(scenario);
  const std::size_t n = ring.config.devices.size();

  master::DdiBoardOptions bo;
  bo.board = o.board;
  bo.service_deadline = o.service_deadline;
  auto opened = master::DdiBoard::open(ring.config, bo);
  if (!opened) {
    res.error = opened.error();
    return res;
  }
  master::DdiBoard& board = *opened.value();
  master::DdiBus& bus = board.bus();
  res.started = true;
  res.board_cycle_time = board.cycle_time();
  const Duration period = o.period > Duration::zero()         ? o.period
                          : board.cycle_time() > Duration::zero() ? board.cycle_time()
                                                                  : ring.cycle_time;
  res.period = period;

  master::MasterLoop loop(ring.config, std::move(ring.drivers));
  board.attach(loop);  // the PCP drivers' transactions through the board's mailbox
  interbus::ProcessImage image;
  loop.initial(image);

  sim::Summary& summary = res.summary;
  summary.scenario = scenario.name;
  summary.cycle_time = board.cycle_time() > Duration::zero() ? board.cycle_time() : period;
  summary.cycle_time_basis = (board.cycle_time() > Duration::zero() ? "the board's, Read_Value 2231H"
                                                                    : "the scenario's (the board gives none)") +
                             std::string("; the master's loop every ") + ms_text(period) +
                             (o.clock == Clock::realtime ? " in real time" : ", stepped") + " on " + o.board;
  summary.devices.resize(n);
  sim::MasterTimeline timeline(loop, image, summary);

  const auto index_of = [&](const std::string& name) -> std::optional<std::size_t> {
    for (std::size_t i = 0; i < n; ++i) {
      if (ring.config.devices[i].name == name) return i;
    }
    return std::nullopt;
  };
  const auto waiting = [&](const sim::TimelineEntry& e) {
    if (e.device.empty()) return false;
    const auto i = index_of(e.device);
    return i && timeline.waiting(*i);
  };
  // The master's entries; the faults and the drives' events are the board's.
  const auto apply = [&](const sim::TimelineEntry& e, Time t) {
    if (e.action == sim::Action::master_restart) {
      loop.restart(t);
      summary.faults.push_back({t, "", "master-restart", "drivers and channels start over"});
      return;
    }
    if (!sim::MasterTimeline::is_master_command(e.action)) return;
    if (const auto i = index_of(e.device)) timeline.apply(e, *i, t);
  };
  std::vector<const sim::TimelineEntry*> deferred;
  std::size_t next_entry = 0;
  const auto apply_due = [&](Time t) {
    for (auto it = deferred.begin(); it != deferred.end();) {
      if (!waiting(**it)) {
        apply(**it, t);
        it = deferred.erase(it);
      } else {
        ++it;
      }
    }
    while (next_entry < scenario.timeline.size() && scenario.timeline[next_entry].at <= t) {
      const sim::TimelineEntry& e = scenario.timeline[next_entry++];
      if (waiting(e)) {
        deferred.push_back(&e);
      } else {
        apply(e, t);
      }
    }
  };

  const Duration duration = o.duration.value_or(scenario.duration);
  const auto cycles = static_cast<std::size_t>(duration / period) + 2;
  std::vector<std::uint32_t> master_ns;
  master_ns.reserve(cycles);
  std::vector<std::uint64_t> device_cycles(n, 0);
  sim::RealtimeStats rt;
  rt.cycle_time = period;
  LoopClock clock(o.clock, period);
  clock.wake().reserve(cycles);
  const double wall_start = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  Time t{0};
  // Cycles still run after the board failed: the bus is gone, the drivers see every device lost
  // and their requests fail (what the summary then says); then the run ends.
  int after_failure = 0;
  constexpr int kCyclesAfterFailure = 5;
  while (clock.deadline() <= Time{0} + duration) {
    t = clock.next();
    apply_due(t);
    const auto t0 = std::chrono::steady_clock::now();
    const master::Exchange ex = loop.cycle(bus, image, t);
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0);
    master_ns.push_back(static_cast<std::uint32_t>(std::min<std::int64_t>(ns.count(), 0xFFFFFFFF)));
    ++summary.cycles;
    if (ex.data_valid) ++summary.valid_cycles;
    for (std::size_t i = 0; i < n; ++i) {
      const master::LinkState l = ex.link(i);
      if (l.data_valid && !l.module_error) ++device_cycles[i];
    }
    for (const master::BoardEvent& e : bus.events()) summary.faults.push_back(fault_of(e, ring.config, o.board));
    bus.clear_events();
    for (std::size_t i = 0; i < n; ++i) timeline.observe_device(i, t);
    timeline.observe_transactions(t);
    clock.done(rt);
    if (bus.failed() && ++after_failure >= kCyclesAfterFailure) {
      const auto& f = summary.faults;
      const auto it = std::find_if(f.rbegin(), f.rend(), [](const sim::FaultRecord& r) {
        return r.kind == "sysfail" || r.kind == "call-failed";
      });
      res.error = {ErrorCode::board_call_failed, it != f.rend() ? it->detail : "the board failed"};
      break;
    }
    if (o.stop && o.stop()) {
      res.interrupted = true;
      break;
    }
  }

  // The scenario's part of the summary, as `ibs run` closes it.
  summary.simulated = t - Time{0};
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count() - wall_start;
  summary.threads = 1;
  char headline[256];
  std::snprintf(headline, sizeof headline, "ibs master: scenario \"%s\", %.3f s run against the board %s in %.3f s of wall time%s",
                scenario.name.c_str(), static_cast<double>(summary.simulated.count()) / 1e9, o.board.c_str(),
                summary.wall_seconds, o.clock == Clock::stepped ? " (stepped)" : "");
  summary.headline = headline;
  for (std::size_t i = 0; i < n; ++i) {
    sim::DeviceReport& r = summary.devices[i];
    devices::DeviceDriver& d = loop.driver(i);
    r.name = ring.config.devices[i].name;
    r.kind = ring.kinds[i];
    r.id_code = interbus::describe(ring.config.devices[i].id);
    r.unit = std::string(d.unit());
    r.final_state = state_text(d);
    r.final_reference = d.reference();
    r.final_actual = d.actual();
    r.samples = device_cycles[i];  // the master's cycles with the device's valid data
  }
  timeline.finish();
  const auto budgets = sim::processing_budgets();
  if (!master_ns.empty()) summary.master = sim::timing_stats(master_ns, period, budgets);
  if (o.clock == Clock::realtime) {
    rt.wake = sim::timing_stats(clock.wake(), period, budgets);
    rt.processing = summary.master;
    summary.realtime = rt;
  }

  // The drives to a safe state, then the board down.
  if (!bus.failed()) {
    res.shutdown.drives_safe = master::stop_drives(
        loop, bus, image, [&clock] { return clock.next(); }, o.stop_drives);
  }
  for (std::size_t i = 0; i < n; ++i) res.shutdown.states.push_back(state_text(loop.driver(i)));
  res.shutdown.error = board.close();
  return res;
}

std::string format_board_text(const RunResult& r) {
  std::string o = "\nboard " + r.board + ": cycle time " +
                  (r.board_cycle_time > Duration::zero() ? ms_text(r.board_cycle_time) : std::string("not given")) +
                  "; the master's loop every " + ms_text(r.period) +
                  (r.clock == Clock::realtime ? ", real time" : ", stepped") + "\n";
  if (r.interrupted) o += "  interrupted by a signal: the run ended early\n";
  std::string states;
  for (std::size_t i = 0; i < r.shutdown.states.size() && i < r.summary.devices.size(); ++i) {
    states += (states.empty() ? "" : ", ") + r.summary.devices[i].name + " " + r.shutdown.states[i];
  }
  o += std::string("  shutdown: ") +
       (r.shutdown.drives_safe ? "every drive in a safe state (" : "not every drive reached a safe state in time (") +
       states + ")" +
       (r.shutdown.error ? "; " + r.shutdown.error.message : "; data transfer stopped, nodes closed") + "\n";
  return o;
}

std::string format_board_json(const RunResult& r) {
  nlohmann::ordered_json states = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < r.shutdown.states.size() && i < r.summary.devices.size(); ++i) {
    states[r.summary.devices[i].name] = r.shutdown.states[i];
  }
  nlohmann::ordered_json j = {
      {"node", r.board},
      {"cycle_time_ms", static_cast<double>(r.board_cycle_time.count()) / 1e6},
      {"period_ms", static_cast<double>(r.period.count()) / 1e6},
      {"clock", r.clock == Clock::realtime ? "realtime" : "stepped"},
      {"interrupted", r.interrupted},
      {"error", r.error.message},
      {"shutdown", {{"drives_safe", r.shutdown.drives_safe}, {"states", states}, {"error", r.shutdown.error.message}}}};
  return j.dump(2);
}

}  // namespace ibs::board
