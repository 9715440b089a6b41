#include "ibs/sim/simulator.hpp"

#include <sched.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <thread>

#include "ibs/interbus/cycle_time.hpp"
#include "ibs/interbus/id_code.hpp"

namespace ibs::sim {

namespace {

using drivecom::State;

// The state names of scenario files (docs/scenarios.md), every DRIVECOM state.
std::optional<State> state_named(const std::string& s) {
  if (s == "not-ready") return State::not_ready;
  if (s == "start-up-inhibit") return State::start_up_inhibit;
  if (s == "ready") return State::ready;
  if (s == "on") return State::on;
  if (s == "enabled") return State::enabled;
  if (s == "fault") return State::fault;
  if (s == "fault-response-active") return State::fault_response_active;
  if (s == "emergency-stop-active") return State::emergency_stop_active;
  return std::nullopt;
}

std::optional<drivecom::Target> target_named(const std::string& s) {
  if (s == "start-up-inhibit") return drivecom::Target::start_up_inhibit;
  if (s == "ready") return drivecom::Target::ready;
  if (s == "on") return drivecom::Target::on;
  if (s == "enabled") return drivecom::Target::enabled;
  return std::nullopt;
}

std::string fmt_value(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}


// The processor cores this process may run on (its affinity mask: `taskset` and container CPU
// sets count, not only the machine's cores).
unsigned usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return static_cast<unsigned>(std::max(1, CPU_COUNT(&set)));
  return std::max(1U, std::thread::hardware_concurrency());
}

// Copies a device's words (at most four) without a library call: every cycle does it for every
// device.
void copy_words(std::span<const Word> from, Word* to) {
  switch (from.size()) {
    case 4: to[3] = from[3]; [[fallthrough]];
    case 3: to[2] = from[2]; [[fallthrough]];
    case 2: to[1] = from[1]; [[fallthrough]];
    case 1: to[0] = from[0]; [[fallthrough]];
    case 0: break;
    default: std::copy(from.begin(), from.end(), to);
  }
}

// Exponentially distributed time to the next random fault of a given rate (per second).
Time next_random(std::mt19937_64& rng, Time from, double rate_per_s) {
  if (rate_per_s <= 0.0) return Time::max();
  std::exponential_distribution<double> d(rate_per_s);
  const double s = d(rng);
  return from + std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s));
}

}  // namespace

struct Simulator::Recording {
  trace::Trace trace;
  std::uint64_t step = 0;
  std::string remark;  // events to note on the next row
  // Device faults as trace events: injected before the device's next sample, they show in the
  // row after that sample's row (whose s2m is the first answer the fault can change).
  std::vector<trace::Event> events_pending;
  std::vector<trace::Event> events_ready;
  std::string file_name;
};

struct Simulator::Device {
  DeviceConfig cfg;
  std::size_t index = 0;
  const devices::DriveKind* kind = nullptr;
  devices::Configuration configuration;
  std::unique_ptr<devices::DeviceEmulator> emu;
  Duration period{0};
  std::size_t pd_words = 0;
  std::size_t pcp_words = 0;
  // The device's slices of the master's process image (set once the ring is built): its whole
  // input slot, and the words it exchanges each way.
  std::span<Word> in_slot, in, out, pcp_in, pcp_out;
  std::array<Word, 4> m2s{};  // the master's process-data words as the bus last delivered them
  std::array<Word, 4> pcp_m2s{};
  // What the device's sampling writes, in cache lines of its own: with several threads the
  // device is stepped on one while the cycle end runs on another.
  alignas(64) std::array<Word, 4> s2m{};  // the device's words, picked up by the next valid cycle
  std::array<Word, 4> pcp_s2m{};
  std::uint64_t k = 0;  // samples taken
  Time next_sample{0};
  Time last_sample{0};
  std::uint64_t jitter_state = 0;
  alignas(64) Time lost_until{-1};
  Time fault_until{-1};
  std::optional<State> waiting_for;
  Time wait_deadline{0};
  std::optional<State> last_seen;
  double reached_for = 0.0;  // the reference whose "reached" was last reported
  bool reached_reported = true;
  std::optional<int> reported_error;
  bool failure_reported = false;  // the sequencer's current failure is in the summary
  std::vector<Recording> recordings;
  bool recording = false;
  bool power_cycled = false;
  std::uint32_t notices = 0;  // the emulator's notices already in the records
  // Summary records the device's sampling made (15-PLRDY), moved into the summary at the next
  // cycle end: the sampling may run on another thread than the summary's.
  std::vector<StateRecord> records;
  std::optional<int> error_at_cycle;  // error_number() at the last cycle end
  // splitmix64: a small, fast generator of its own for the device's sample jitter.
  std::uint64_t jitter_rng() {
    std::uint64_t z = (jitter_state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31U);
  }
  // What a device started for a trace shows before its first sample (`init: power-on` and
  // `init: operational`).
  std::array<Word, 4> fresh_initialised{};
  std::array<Word, 4> fresh_operational{};

  [[nodiscard]] bool lost(Time t) const { return t < lost_until; }
  [[nodiscard]] bool module_error(Time t) const {
    return lost(t) || emu->module_error(t);
  }
  [[nodiscard]] State state() const { return emu->state(); }
  [[nodiscard]] std::span<Word> pd_m2s() { return {m2s.data(), pd_words}; }
  [[nodiscard]] std::span<Word> pd_s2m() { return {s2m.data(), pd_words}; }
};

Simulator::Simulator(const Scenario& scenario) : scenario_(scenario), rng_(scenario.random.seed) {
  if (scenario_.devices.empty()) throw std::invalid_argument("scenario '" + scenario_.name + "': no devices");
  std::vector<interbus::DeviceSpec> specs;
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  for (std::size_t i = 0; i < scenario_.devices.size(); ++i) {
    const DeviceConfig& c = scenario_.devices[i];
    auto d = std::make_unique<Device>();
    d->cfg = c;
    d->index = i;
    d->jitter_state = scenario_.random.seed ^ (0xD1B54A32D192ED03ULL * (i + 1));
    const DeviceStart start = c.initialised ? DeviceStart::initialised : DeviceStart::power_on;
    // The drive kind the scenario names, and where its settings place it on the bus.
    const devices::DriveKind* kind = devices::find_drive_kind(c.kind);
    if (kind == nullptr) {
      throw std::invalid_argument("device '" + c.name + "': unknown type '" + c.kind + "' (" +
                                  devices::drive_kind_names(", ", " or ", "\"") + ")");
    }
    try {
      d->configuration = (*kind)->configure(device_settings(c));
    } catch (const devices::SettingsError& e) {
      throw std::invalid_argument("device '" + c.name + "': " + e.what());
    }
    d->kind = kind;
    d->emu = prototype(*kind, d->configuration, start).clone();
    d->period = (*kind)->facts().sample_period;
    d->pd_words = d->configuration.exchanged_pd_words();
    d->pcp_words = d->configuration.pcp_words;
    specs.push_back({c.name, d->configuration.id_code, d->configuration.bus});
    drivers.push_back((*kind)->make_driver(d->configuration));
    devices_.push_back(std::move(d));
  }
  interbus::BusConfig config;
  try {
    config = interbus::make_bus_config(specs);
  } catch (const interbus::ConfigError& e) {
    throw std::invalid_argument(std::string("bus configuration: ") + e.what());
  }
  interbus::CycleTimeParams p = interbus::params_for(scenario_.bus.baud_2mbit ? interbus::BaudRate::mbit2
                                                                               : interbus::BaudRate::kbit500);
  p.software_time = scenario_.bus.software_time;
  const Duration formula = interbus::cycle_time(config, p);
  if (scenario_.bus.cycle_time) {
    cycle_time_ = *scenario_.bus.cycle_time;
    summary_.cycle_time_basis = "set by the scenario (the formula gives " + fmt_value(to_ms(formula)) + " ms)";
  } else {
    cycle_time_ = formula;
    summary_.cycle_time_basis = "formula SW + (13 * (6 + N) + 1.5 * M) * T_bit with N = " +
                                std::to_string(config.ring_bytes()) + " bytes, M = " +
                                std::to_string(config.remote_devices) + " remote devices, T_bit = " +
                                fmt_value(static_cast<double>(p.bit_time.count()) / 1000.0) + " us, SW = " +
                                fmt_value(static_cast<double>(p.software_time.count()) / 1000.0) + " us";
  }
  if (cycle_time_ <= Duration{0}) throw std::invalid_argument("bus cycle time must be positive");
  for (auto& d : devices_) {
    if (d->pd_words > 0 && config.devices[d->index].pd_in_words != d->pd_words) {
      throw std::invalid_argument("device '" + d->cfg.name + "': the ring gives it " +
                                  std::to_string(config.devices[d->index].pd_in_words) +
                                  " process-data words, its layout " + std::to_string(d->pd_words));
    }
  }
  loop_ = std::make_unique<master::MasterLoop>(std::move(config), std::move(drivers));
  for (auto& d : devices_) {
    // The device's slices, cut to the words it exchanges (an MC6000 with SUPI 0 has a slot on
    // the ring but exchanges nothing, 3.2.2).
    const interbus::Device& bd = loop_->config().devices[d->index];
    const auto cut = [](std::span<Word> slice, std::size_t words) {
      return slice.first(std::min(slice.size(), words));
    };
    d->in_slot = interbus::in_slice(image_, bd);
    d->in = cut(d->in_slot, d->pd_words);
    d->out = cut(interbus::out_slice(image_, bd), d->pd_words);
    d->pcp_in = cut(interbus::pcp_in_slice(image_, bd), d->pcp_words);
    d->pcp_out = cut(interbus::pcp_out_slice(image_, bd), d->pcp_words);
  }
  links_.resize(devices_.size());
  summary_.devices.resize(devices_.size());
  summary_.scenario = scenario_.name;
  summary_.cycle_time = cycle_time_;
}

Simulator::~Simulator() = default;

const devices::DeviceEmulator& Simulator::prototype(const devices::DriveKind& kind,
                                                   const devices::Configuration& config, DeviceStart start) {
  // Devices of the same kind and settings start out identical: one is built (a servo's plant
  // discretised) and the others are copies of it.
  for (const auto& p : prototypes_) {
    if (p.kind == &kind && p.start == start && p.settings == config.settings) return *p.emulator;
  }
  prototypes_.push_back({&kind, config.settings, start, kind.make_emulator(config, start, Time{0})});
  return *prototypes_.back().emulator;
}

std::optional<std::size_t> Simulator::index_of(const std::string& name) const {
  for (const auto& d : devices_) {
    if (d->cfg.name == name) return d->index;
  }
  return std::nullopt;
}

State Simulator::device_state(std::size_t i) const { return devices_[i]->state(); }
bool Simulator::module_error(std::size_t i, Time t) const { return devices_[i]->module_error(t); }
void Simulator::inject_fault(Action kind, std::size_t i, Duration duration, int count) {
  const bool bus_wide = kind == Action::fault_corrupt || kind == Action::master_restart;
  if (!bus_wide && i >= devices_.size()) return;
  fault(now_, bus_wide ? devices_.size() : i, kind, duration, count);
}
double Simulator::device_actual(std::size_t i) const { return devices_[i]->emu->actual(); }
devices::DeviceEmulator& Simulator::emulator(std::size_t i) { return *devices_[i]->emu; }
const devices::DeviceEmulator& Simulator::emulator(std::size_t i) const { return *devices_[i]->emu; }

Time Simulator::next_sample_time(Device& d) {
  // Nominal phase + k * period, moved by up to +-jitter, never before the previous sample. Each
  // device draws its jitter from its own generator, so the order in which devices are stepped
  // does not change the run.
  Time t = d.cfg.phase + static_cast<std::int64_t>(d.k) * d.period;
  if (d.cfg.jitter > Duration{0}) {
    const auto span = static_cast<std::uint64_t>(2 * d.cfg.jitter.count() + 1);
    t += Duration{static_cast<std::int64_t>(d.jitter_rng() % span) - d.cfg.jitter.count()};
  }
  return std::max(t, d.last_sample);
}

void Simulator::start(const SimOptions& options) {
  options_ = options;
  started_ = true;
  wall_start_ = wall_now();
  loop_->initial(image_);
  for (auto& d : devices_) {
    d->emu->output(d->pd_s2m());
    d->emu->output_pcp(Time{0}, {d->pcp_s2m.data(), d->pcp_words});
    d->next_sample = next_sample_time(*d);
    // A device without process data (MC6000 SUPI 0..3) has no `words: pd` rows to record.
    if (options_.record_traces && d->pd_words > 0) {
      Recording r;
      r.trace.file = d->cfg.name;
      r.trace.header.device = std::string((*d->kind)->name());
      r.trace.header.words = trace::WordsKind::pd;
      (*d->kind)->write_trace_settings(d->configuration, r.trace.header);
      // What a freshly started device of a trace `init` shows (record_sample starts on it).
      prototype(*d->kind, d->configuration, DeviceStart::initialised).output({d->fresh_initialised.data(), d->pd_words});
      prototype(*d->kind, d->configuration, DeviceStart::operational).output({d->fresh_operational.data(), d->pd_words});
      r.trace.header.init = DeviceStart::initialised;
      r.trace.header.init_given = true;
      r.file_name = d->cfg.name + ".trace";
      d->recordings.push_back(std::move(r));
      // A device switched on by the scenario is recorded once it has initialised.
      d->recording = d->cfg.initialised;
    }
  }
  prototypes_.clear();
  if (observers_.empty()) start_threads(options_.threads);
  master_ns_.reserve(static_cast<std::size_t>(scenario_.duration / cycle_time_) + 2);
  samples_.reserve(devices_.size());
  next_cycle_ = cycle_time_;
  const auto& r = scenario_.random;
  random_next_ = {next_random(rng_, Time{0}, r.corrupt_per_s), next_random(rng_, Time{0}, r.power_cycle_per_s),
                  next_random(rng_, Time{0}, r.device_fault_per_s), next_random(rng_, Time{0}, r.lost_per_s),
                  next_random(rng_, Time{0}, r.master_restart_per_s)};
}

bool Simulator::run_until(Time until, const SimOptions& options) {
  if (!started_) start(options);
  if (finished_) return false;
  const Time end = std::min<Time>(until, scenario_.duration);
  if (observers_.empty()) {
    run_device_major(end);
  } else {
    run_time_ordered(end);
  }
  merge_device_records();
  now_ = end;
  if (end >= scenario_.duration) {
    finish();
    return false;
  }
  return true;
}

void Simulator::run_device_major(Time end) {
  // Devices interact only through the bus exchange: between two cycle ends every device can take
  // all its samples on its own, in its own time order, with exactly the result of the globally
  // time-ordered loop (a sample at the instant of a cycle end comes after the exchange).
  // The master's cycle after a cycle end and the devices' samples up to the next one do not meet
  // either (the master's new words reach the devices only at that next cycle end), so they run
  // side by side: the master's on the calling thread, ahead of its part of the devices.
  Time last_progress = now_;
  while (true) {
    const Time limit = std::min(next_cycle_, end + Duration{1});
    step_devices(limit);
    master_due_.reset();
    if (next_cycle_ > end) break;
    now_ = next_cycle_;
    cycle_exchange(next_cycle_);
    master_due_ = next_cycle_;
    next_cycle_ += cycle_time_;
    if (options_.progress && now_ - last_progress >= 100ms) {
      options_.progress(now_, scenario_.duration);
      last_progress = now_;
    }
  }
}

void Simulator::step_devices(Time limit) {
  window_limit_ = limit;
  if (!workers_) {
    step_part(0);
    return;
  }
  workers_->run();
}

void Simulator::step_part(unsigned part) {
  if (part == 0 && master_due_) cycle_master(*master_due_);
  const Part p = parts_.empty() ? Part{0, devices_.size()} : parts_[part];
  for (std::size_t k = p.first; k < p.end; ++k) step_device(*devices_[k], window_limit_);
}

void Simulator::start_threads(unsigned requested) {
  // Work of a device: its samples per simulated millisecond (an MC6000 1, a VF1000 0.12).
  std::vector<double> work;
  double total = 0.0;
  for (const auto& d : devices_) {
    work.push_back(1e6 / static_cast<double>(d->period.count()));
    total += work.back();
  }
  // Automatic: a thread only for at least this much work (servo samples per millisecond); less
  // cannot pay for the hand-over each cycle. (On the 2-vCPU machine of docs/performance.md even
  // 32 per thread did not, hence one thread by default.)
  constexpr double kWorkPerThread = 16.0;
  // The master's cycle and the summary, on the first part's thread: about three servo samples
  // per device and cycle (measured with callgrind on the full bus).
  const double master = 3.0 * static_cast<double>(devices_.size()) * 1e6 / static_cast<double>(cycle_time_.count());
  unsigned n = requested;
  if (n == 0) {
    const unsigned cores = usable_cores();
    n = std::min(cores, static_cast<unsigned>(std::max(1.0, total / kWorkPerThread)));
  }
  n = std::min<unsigned>(n, static_cast<unsigned>(devices_.size()));
  if (n <= 1) return;
  // Contiguous parts of about (total + master) / n each, the first with the master's work.
  parts_.assign(n, Part{});
  std::size_t i = 0;
  double done = master;
  for (unsigned p = 0; p < n; ++p) {
    parts_[p].first = i;
    const double target = (total + master) * (p + 1) / n;
    const std::size_t keep = n - p - 1;  // devices left for the parts after this one
    while (i < devices_.size() - keep && (i == parts_[p].first || done + 0.5 * work[i] <= target)) {
      done += work[i++];
    }
    parts_[p].end = p + 1 == n ? devices_.size() : i;
  }
  workers_ = std::make_unique<ForkJoin>(n, [this](unsigned part) { step_part(part); });
}

void Simulator::step_device(Device& d, Time limit) {
  if (d.next_sample >= limit) return;
  if (!d.emu->defers_output() || !d.recordings.empty()) {
    while (d.next_sample < limit) handle_sample(d.index, d.next_sample);
    return;
  }
  // An MC6000 without PCP words, not recorded: nobody reads its process-data words before the
  // cycle end, so they are formed once, after its last sample before it. Without jitter its
  // samples up to the cycle end are known at once and it takes them in one go.
  if (d.cfg.jitter == Duration{0}) {
    const auto count = static_cast<std::uint64_t>((limit - d.next_sample + d.period - Duration{1}) / d.period);
    d.emu->sample_held(d.pd_m2s(), d.next_sample, d.period, static_cast<std::uint32_t>(count));
    d.k += count;
    d.last_sample = d.next_sample + static_cast<std::int64_t>(count - 1) * d.period;
    d.next_sample = next_sample_time(d);
  } else {
    do {
      d.last_sample = d.next_sample;
      d.emu->sample_deferred(d.pd_m2s(), d.next_sample);
      ++d.k;
      d.next_sample = next_sample_time(d);
    } while (d.next_sample < limit);
  }
  d.emu->output(d.pd_s2m());
}

void Simulator::run_time_ordered(Time end) {
  // With observers (a VCD file) the events go strictly in time order across devices.
  samples_.clear();
  for (const auto& d : devices_) samples_.push_back({d->next_sample, d->index});
  std::make_heap(samples_.begin(), samples_.end(), std::greater<>{});
  Time last_progress = now_;
  while (true) {
    const SampleEvent next = samples_.front();  // the earliest sample of any device
    const Time t = std::min(next_cycle_, next.at);
    if (t > end) break;
    now_ = t;
    // At the same instant the bus exchange comes first: a device sampling then sees its new words.
    if (next_cycle_ <= next.at) {
      handle_cycle(t);
      next_cycle_ += cycle_time_;
    } else {
      handle_sample(next.device, t);
      reschedule_front(devices_[next.device]->next_sample);
    }
    if (options_.progress && t - last_progress >= 100ms) {
      options_.progress(t, scenario_.duration);
      last_progress = t;
    }
  }
}

void Simulator::run(const SimOptions& options) { run_until(scenario_.duration, options); }

void Simulator::reschedule_front(Time at) {
  // The device at the top of the min-heap sampled: give it its next time and sift it down (one
  // pass instead of a pop and a push).
  const std::size_t n = samples_.size();
  SampleEvent moving{at, samples_[0].device};
  std::size_t i = 0;
  while (true) {
    const std::size_t l = 2 * i + 1;
    if (l >= n) break;
    std::size_t c = l;
    if (l + 1 < n && samples_[l + 1] < samples_[l]) c = l + 1;
    if (!(samples_[c] < moving)) break;
    samples_[i] = samples_[c];
    i = c;
  }
  samples_[i] = moving;
}

void Simulator::apply_timeline(Time t) {
  // Entries of a device that waits for a state stay deferred until the wait ends.
  auto waiting = [&](const TimelineEntry& e) {
    if (e.device.empty()) return false;
    const auto i = index_of(e.device);
    return i && devices_[*i]->waiting_for.has_value();
  };
  for (auto it = deferred_.begin(); it != deferred_.end();) {
    if (!waiting(**it)) {
      apply(**it, t);
      it = deferred_.erase(it);
    } else {
      ++it;
    }
  }
  while (timeline_next_ < scenario_.timeline.size() && scenario_.timeline[timeline_next_].at <= t) {
    const TimelineEntry& e = scenario_.timeline[timeline_next_++];
    if (waiting(e)) {
      deferred_.push_back(&e);
    } else {
      apply(e, t);
    }
  }
}

void Simulator::apply(const TimelineEntry& e, Time t) {
  std::optional<std::size_t> idx;
  if (!e.device.empty()) {
    idx = index_of(e.device);
    if (!idx) return;  // checked when the scenario was read
  }
  switch (e.action) {
    case Action::state: {
      const auto target = target_named(e.value);
      if (idx && target) loop_->driver(*idx).sequencer().request(*target, t);
      break;
    }
    case Action::emergency_stop:
      if (idx) loop_->driver(*idx).sequencer().request_emergency_stop(t);
      break;
    case Action::block_power:
      if (idx) loop_->driver(*idx).sequencer().request_block_power(t);
      break;
    case Action::speed:
    case Action::frequency:
      if (idx) {
        loop_->driver(*idx).set_reference(e.number);
        devices_[*idx]->reached_reported = false;
        devices_[*idx]->reached_for = e.number;
      }
      break;
    case Action::read:
    case Action::write:
    case Action::describe: {
      if (!idx) break;
      const devices::ParamOp op = e.action == Action::read    ? devices::ParamOp::read
                                  : e.action == Action::write ? devices::ParamOp::write
                                                              : devices::ParamOp::describe;
      TransactionRecord r;
      r.device = e.device;
      r.op = op;
      r.number = e.parameter;
      r.value = static_cast<std::int64_t>(e.number);
      r.submitted = t;
      r.source_line = e.source_line;
      r.id = loop_->driver(*idx).parameters().submit(op, e.parameter, r.value);
      if (r.id == 0) {
        r.answered = r.finished = t;
        r.kind = devices::ParamKind::refused;
        r.result = loop_->driver(*idx).parameters().describe(0);
      }
      summary_.transactions.push_back(std::move(r));
      break;
    }
    case Action::wait_state:
      if (idx) {
        devices_[*idx]->waiting_for = state_named(e.value);
        devices_[*idx]->wait_deadline = e.duration > Duration{0} ? t + e.duration : Time::max();
      }
      break;
    case Action::fault_corrupt:
    case Action::fault_power_cycle:
    case Action::fault_device:
    case Action::fault_lost:
    case Action::master_restart:
      fault(t, idx.value_or(devices_.size()), e.action, e.duration, e.count);
      break;
  }
}

void Simulator::fault(Time t, std::size_t i, Action kind, Duration duration, int count) {
  FaultRecord f;
  f.at = t;
  if (i < devices_.size()) f.device = devices_[i]->cfg.name;
  auto note = [&](Device& d, const std::string& what) {
    if (!d.recordings.empty() && d.recording) {
      auto& r = d.recordings.back().remark;
      r += (r.empty() ? "" : "; ") + what;
    }
  };
  auto event = [&](Device& d, trace::Event::Kind what, const std::string& text) {
    if (!d.recordings.empty() && d.recording) d.recordings.back().events_pending.push_back({what, text, 0});
  };
  switch (kind) {
    case Action::fault_corrupt:
      f.kind = "corrupt";
      f.detail = std::to_string(count) + " corrupted cycle(s), then " +
                 std::to_string(scenario_.bus.recovery_cycles) + " recovery cycles";
      corrupt_left_ += std::max(count, 1);
      break;
    case Action::fault_power_cycle: {
      Device& d = *devices_[i];
      f.kind = "power-cycle";
      f.detail = "switched off and on: initialising again";
      d.emu->power_cycle(t);
      if (d.recording) {
        // A power cycle is not in the trace format: this recording ends, a new one starts once the
        // device has initialised again.
        d.recordings.back().trace.trailing_comments.push_back("# recording ends: power cycle at " +
                                                              fmt_value(to_ms(t)) + " ms");
        Recording next;
        next.trace.file = d.cfg.name;
        next.trace.header = d.recordings.back().trace.header;
        next.file_name = d.cfg.name + "." + std::to_string(d.recordings.size() + 1) + ".trace";
        d.recordings.push_back(std::move(next));
        d.recording = false;
      }
      d.power_cycled = true;
      break;
    }
    case Action::fault_device: {
      Device& d = *devices_[i];
      f.kind = "device-fault";
      f.detail = "fault present for " + fmt_value(to_ms(duration)) + " ms";
      d.fault_until = t + std::max(duration, d.period);
      d.emu->set_fault(true);
      note(d, "device fault injected");
      event(d, trace::Event::Kind::fault, "injected at " + fmt_value(to_ms(t)) + " ms");
      break;
    }
    case Action::fault_lost: {
      Device& d = *devices_[i];
      f.kind = "lost";
      f.detail = duration > Duration{0} ? "off the bus for " + fmt_value(to_ms(duration)) + " ms"
                                        : "off the bus until the end";
      d.lost_until = duration > Duration{0} ? t + duration : Time::max();
      note(d, "device lost from the bus");
      break;
    }
    case Action::master_restart:
      f.kind = "master-restart";
      f.detail = "drivers and channels start over";
      loop_->restart(t);
      break;
    default: return;
  }
  summary_.faults.push_back(std::move(f));
}

void Simulator::apply_random_faults(Time t) {
  const auto& r = scenario_.random;
  auto pick = [&]() {
    std::uniform_int_distribution<std::size_t> u(0, devices_.size() - 1);
    return u(rng_);
  };
  if (t >= random_next_.corrupt) {
    fault(t, devices_.size(), Action::fault_corrupt, Duration{0}, 1);
    random_next_.corrupt = next_random(rng_, t, r.corrupt_per_s);
  }
  if (t >= random_next_.power_cycle) {
    fault(t, pick(), Action::fault_power_cycle, Duration{0}, 1);
    random_next_.power_cycle = next_random(rng_, t, r.power_cycle_per_s);
  }
  if (t >= random_next_.device_fault) {
    fault(t, pick(), Action::fault_device, 50ms, 1);
    random_next_.device_fault = next_random(rng_, t, r.device_fault_per_s);
  }
  if (t >= random_next_.lost) {
    fault(t, pick(), Action::fault_lost, 100ms, 1);
    random_next_.lost = next_random(rng_, t, r.lost_per_s);
  }
  if (t >= random_next_.master_restart) {
    fault(t, devices_.size(), Action::master_restart, Duration{0}, 1);
    random_next_.master_restart = next_random(rng_, t, r.master_restart_per_s);
  }
}

void Simulator::handle_cycle(Time t) {
  cycle_exchange(t);
  cycle_master(t);
}

void Simulator::cycle_exchange(Time t) {
  merge_device_records();
  apply_timeline(t);
  apply_random_faults(t);
  for (auto& d : devices_) {
    if (d->fault_until >= Time{0} && t >= d->fault_until) {
      d->fault_until = Time{-1};
      d->emu->set_fault(false);
      summary_.faults.push_back({t, d->cfg.name, "fault-cleared", "the fault's cause has gone"});
      if (!d->recordings.empty() && d->recording) {
        d->recordings.back().events_pending.push_back(
            {trace::Event::Kind::fault_cleared, "at " + fmt_value(to_ms(t)) + " ms", 0});
      }
    }
    if (d->lost_until >= Time{0} && d->lost_until != Time::max() && t >= d->lost_until) {
      d->lost_until = Time{-1};
      summary_.faults.push_back({t, d->cfg.name, "back", "back on the bus"});
    }
  }
  // The cycle just ended: a corrupted one and the recovery cycles after it deliver nothing.
  bool valid = true;
  if (corrupt_left_ > 0) {
    --corrupt_left_;
    valid = false;
    if (corrupt_left_ == 0) recovery_left_ = scenario_.bus.recovery_cycles;
  } else if (recovery_left_ > 0) {
    --recovery_left_;
    valid = false;
  }
  ++summary_.cycles;
  if (valid) ++summary_.valid_cycles;
  for (auto& d : devices_) {
    master::LinkState& link = links_[d->index];
    link.data_valid = valid;
    link.module_error = d->module_error(t);
    if (!valid) continue;
    if (link.module_error) {
      std::fill(d->in_slot.begin(), d->in_slot.end(), Word{0});  // no data from a device with a module error
      // A device that is on the ring but initialising (6.1) still takes the master's words into
      // its bus interface: it acts on the newest ones once it is ready, not on words from before.
      if (!d->lost(t) && d->emu->takes_words_in_module_error()) copy_words(d->out, d->m2s.data());
      continue;
    }
    copy_words(d->out, d->m2s.data());
    copy_words({d->s2m.data(), d->in.size()}, d->in.data());
    copy_words(d->pcp_out, d->pcp_m2s.data());
    copy_words({d->pcp_s2m.data(), d->pcp_in.size()}, d->pcp_in.data());
    d->emu->bus_cycle(t);
  }
  // What the master's side reports of the devices, as they are at this cycle end (the devices
  // may be sampling again while the master's cycle runs).
  for (auto& d : devices_) d->error_at_cycle = d->emu->error_number();
  last_cycle_valid_ = valid;
}

void Simulator::cycle_master(Time t) {
  const auto t0 = options_.measure_master_time ? std::chrono::steady_clock::now()
                                               : std::chrono::steady_clock::time_point{};
  loop_->cycle(image_, t, master::Exchange{last_cycle_valid_, links_});
  if (options_.measure_master_time) {
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0);
    master_ns_.push_back(static_cast<std::uint32_t>(std::min<std::int64_t>(ns.count(), 0xFFFFFFFF)));
  }
  for (Observer* o : observers_) o->on_cycle(t, last_cycle_valid_, image_);
  observe_master(t);
}

void Simulator::merge_device_records() {
  for (auto& d : devices_) {
    if (d->records.empty()) continue;
    auto& states = summary_.devices[d->index].states;
    states.insert(states.end(), d->records.begin(), d->records.end());
    d->records.clear();
  }
}

void Simulator::observe_master(Time t) {
  for (auto& d : devices_) {
    devices::DeviceDriver& drv = loop_->driver(d->index);
    const auto seen = drv.sequencer().report().state_seen;
    auto& states = summary_.devices[d->index].states;
    if (seen && seen != d->last_seen) {
      states.push_back({t, std::string(drivecom::to_string(*seen))});
      d->last_seen = seen;
    }
    // A reference the master sees reached (status bit 10 while ENABLED, the actual at it).
    const std::span<const Word> in = d->in_slot;
    // (the actual must be at the new reference too: the status word may still show the old one)
    const bool at_reference = std::fabs(drv.actual() - d->reached_for) <= 0.01 * std::fabs(d->reached_for) + 0.1;
    if (!d->reached_reported && !in.empty() && seen == State::enabled &&
        bit(in[0], drivecom::sw::kReferenceReached) && at_reference) {
      d->reached_reported = true;
      states.push_back({t, "reference " + fmt_value(d->reached_for) + " " + std::string(drv.unit()) +
                               " reached (actual " + fmt_value(drv.actual()) + ")"});
    }
    if (d->waiting_for && (seen == d->waiting_for || t >= d->wait_deadline)) {
      if (seen != d->waiting_for) {
        states.push_back({t, "wait for " + std::string(drivecom::to_string(*d->waiting_for)) + " timed out"});
      }
      d->waiting_for.reset();
    }
    const drivecom::Report& rep = drv.sequencer().report();
    if (rep.phase != drivecom::Phase::failed) {
      d->failure_reported = false;
    } else if (!d->failure_reported) {
      d->failure_reported = true;
      const std::string why = drivecom::describe(rep);
      states.push_back({t, "master: request failed (" + std::string(drivecom::to_string(rep.failure)) + ")"});
      summary_.devices[d->index].failures.push_back({t, std::string(drivecom::to_string(rep.failure)), why});
    }
    const auto err = d->error_at_cycle;
    if (err && err != d->reported_error) {
      const std::string what((*d->kind)->facts().watchdog_error);
      summary_.faults.push_back({t, d->cfg.name, "watchdog", what});
      summary_.devices[d->index].errors.push_back(fmt_value(to_ms(t)) + " ms: " + what);
    }
    d->reported_error = err;
  }
  for (auto& r : summary_.transactions) {
    if (r.finished) continue;
    const auto i = index_of(r.device);
    const devices::ParameterAccess& pa = loop_->driver(*i).parameters();
    if (!r.answered) {
      const devices::ParamStatus s = pa.status(r.id);
      if (!s.done()) continue;
      r.answered = t;
      r.kind = s.kind;
      r.result_value = s.value;
      r.result = pa.describe(r.id);
    }
    if (!pa.closing()) r.finished = t;
  }
}

void Simulator::handle_sample(std::size_t i, Time t) {
  Device& d = *devices_[i];
  d.last_sample = t;
  const bool recording = !d.recordings.empty();  // only with SimOptions::record_traces
  std::array<Word, 4> before{};
  if (recording) before = d.s2m;
  d.emu->sample({d.pd_m2s(), d.pd_s2m(), {d.pcp_m2s.data(), d.pcp_words}, {d.pcp_s2m.data(), d.pcp_words}}, t);
  ++d.k;
  d.next_sample = next_sample_time(d);
  if (const devices::Notices n = d.emu->notices(); n.count != d.notices) {
    // E.g. 15-PLRDY = 1 makes the servo recalculate its controller parameters (seed 001, 4.2).
    d.notices = n.count;
    d.records.push_back({t, std::string(n.what)});
  }
  if (recording) record_sample(d, before, t);
  for (Observer* o : observers_) o->on_sample(t, i, d.pd_m2s(), d.pd_s2m());
}

void Simulator::record_sample(Device& d, const std::array<Word, 4>& before, Time t) {
  // In the trace timing convention: this row's m2s is what the device read now, its s2m what the
  // device showed before this sample (its answer to the previous row).
  if (!d.recording && !d.module_error(t)) {
    // Start (again) once the device shows exactly what a freshly started device of a trace
    // `init` shows: initialised, START-UP INHIBIT after BLOCK POWER, channel at rest.
    const DeviceStart init = d.emu->trace_start();
    const std::array<Word, 4>& fresh = init == DeviceStart::operational ? d.fresh_operational : d.fresh_initialised;
    if (std::equal(before.begin(), before.begin() + static_cast<std::ptrdiff_t>(d.pd_words), fresh.begin())) {
      d.recording = true;
      d.recordings.back().trace.header.init = init;
    }
  }
  if (d.recording) {
    Recording& r = d.recordings.back();
    trace::Row row;
    row.step = r.step++;
    for (std::size_t w = 0; w < d.pd_words; ++w) {
      row.m2s.push_back(trace::WordPattern::exact(d.m2s[w]));
      row.s2m.push_back(trace::WordPattern::exact(before[w]));
    }
    row.remark = fmt_value(to_ms(t)) + " ms";
    if (!r.remark.empty()) row.remark += ": " + r.remark;
    r.remark.clear();
    row.events_before = std::move(r.events_ready);
    r.events_ready = std::move(r.events_pending);
    r.events_pending.clear();
    r.trace.rows.push_back(std::move(row));
  }
}

void Simulator::finish() {
  if (finished_) return;
  finished_ = true;
  summary_.simulated = scenario_.duration;
  summary_.wall_seconds = wall_now() - wall_start_;
  summary_.threads = threads();
  const interbus::BusConfig& cfg = loop_->config();
  for (auto& d : devices_) {
    DeviceReport& r = summary_.devices[d->index];
    r.name = d->cfg.name;
    r.kind = d->cfg.kind;
    r.id_code = interbus::describe(cfg.devices[d->index].id);
    const devices::DeviceDriver& drv = loop_->driver(d->index);
    r.unit = std::string(drv.unit());
    r.final_state = std::string(drivecom::to_string(d->state()));
    r.final_reference = drv.reference();
    r.final_actual = device_actual(d->index);
    r.samples = d->k;
  }
  for (auto& r : summary_.transactions) {
    if (!r.finished) r.result = "still pending at the end of the run";
  }
  if (!master_ns_.empty()) {
    std::vector<std::uint32_t> v = master_ns_;
    std::sort(v.begin(), v.end());
    summary_.master.cycles = v.size();
    summary_.master.median_ns = v[v.size() / 2];
    summary_.master.p99_ns = v[std::min(v.size() - 1, v.size() * 99 / 100)];
    summary_.master.max_ns = v.back();
  }
}

const Summary& Simulator::summary() { return summary_; }

std::vector<Simulator::RecordedTrace> Simulator::traces() const {
  std::vector<RecordedTrace> out;
  for (const auto& d : devices_) {
    for (const auto& r : d->recordings) {
      if (r.trace.rows.empty()) continue;
      out.push_back({r.file_name, r.trace});
    }
  }
  return out;
}

}  // namespace ibs::sim
