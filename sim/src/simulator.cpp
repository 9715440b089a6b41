// The cycle simulator: the ring built from a scenario, and the run from start to finish (simulator_internal.hpp lists the other parts).
#include "simulator_internal.hpp"

#include "ibs/devices/trace_adapters.hpp"

namespace ibs::sim {

using detail::fmt_value;
using detail::wall_now;
using detail::next_random;

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
  master_side_ = std::make_unique<MasterTimeline>(*loop_, image_, summary_);
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

void Simulator::set_switched_off(std::size_t i, bool off) {
  if (i < devices_.size()) devices_[i]->switched_off = off;
}

bool Simulator::switched_off(std::size_t i) const { return i < devices_.size() && devices_[i]->switched_off; }

double Simulator::device_actual(std::size_t i) const { return devices_[i]->emu->actual(); }

devices::DeviceEmulator& Simulator::emulator(std::size_t i) { return *devices_[i]->emu; }

const devices::DeviceEmulator& Simulator::emulator(std::size_t i) const { return *devices_[i]->emu; }

devices::LayoutDescription Simulator::layout(std::size_t i) const {
  const Device& d = *devices_[i];
  return d.kind->descriptor->layout(d.configuration);
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
      // The settings without a header of their own (`setting: NAME VALUE`), and the parameters
      // the channels the recorded words do not carry change (`! write PNR VALUE`).
      devices::write_device_settings(*d->kind, d->configuration.settings, r.trace.header);
      d->emu->record_changes(true);
      // The watchdog as the scenario set it (without one the device's own default, which a
      // replay takes without the header too); one step is one sample of the device, the time a
      // row stands for (the bus cycle of the run is another: samples no cycle reached are the
      // trace's steps without data).
      r.trace.header.watchdog_ms = d->configuration.settings.watchdog_ms;
      r.trace.header.step_time = d->period;
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
  if (options_.measure_master_time) {
    // Written once now (then emptied, its memory kept): a cycle that records its time takes no
    // page fault, and a long run's memory does not grow with its cycles.
    master_ns_.assign(static_cast<std::size_t>(scenario_.duration / cycle_time_) + 2, 0);
    master_ns_.clear();
  }
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

void Simulator::run(const SimOptions& options) { run_until(scenario_.duration, options); }

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
  master_side_->finish();
  if (!master_ns_.empty()) {
    const auto budgets = processing_budgets();
    summary_.master = timing_stats(master_ns_, cycle_time_, budgets);
  }
}

std::vector<Duration> processing_budgets() {
  std::vector<Duration> out;
  for (const devices::DriveKind& k : devices::drive_kinds()) {
    const Duration p = k->facts().sample_period;
    if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  }
  return out;
}

TimingStats timing_stats(std::span<const std::uint32_t> ns, Duration cycle_time, std::span<const Duration> budgets) {
  TimingStats t;
  if (ns.empty()) return t;
  std::vector<std::uint32_t> v(ns.begin(), ns.end());
  std::sort(v.begin(), v.end());
  // Nearest rank: the smallest value at or below which `per_thousand` of the cycles lie.
  const auto rank = [&v](std::size_t per_thousand) {
    const std::size_t r = (v.size() * per_thousand + 999) / 1000;  // ceil, 1-based
    return static_cast<double>(v[std::clamp<std::size_t>(r, 1, v.size()) - 1]);
  };
  t.cycles = v.size();
  t.median_ns = v[v.size() / 2];
  t.p99_ns = rank(990);
  t.p999_ns = rank(999);
  t.max_ns = v.back();
  const auto worst = std::max_element(ns.begin(), ns.end());
  t.worst_cycle = static_cast<std::uint64_t>(worst - ns.begin());
  // Cycle k ends on the bus at (k + 1) cycle times (the first cycle end is one cycle in).
  const auto at = [cycle_time](std::size_t k) { return Time{0} + cycle_time * static_cast<std::int64_t>(k + 1); };
  t.worst_at = at(t.worst_cycle);
  for (const Duration b : budgets) {
    OverBudget o;
    o.budget = b;
    for (std::size_t k = 0; k < ns.size(); ++k) {
      if (static_cast<std::int64_t>(ns[k]) <= b.count()) continue;
      if (o.cycles++ == 0) o.first = at(k);
    }
    t.over.push_back(o);
  }
  return t;
}

const Summary& Simulator::summary() { return summary_; }

}  // namespace ibs::sim
