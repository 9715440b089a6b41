// The cycle simulator: a bus ring of emulated drives and the master's cycle loop in simulated
// time (integer nanoseconds). The bus cycles at its computed (or a set) cycle time; each device
// samples at its own period with phase and jitter; a device sees the master's words only when it
// samples, the master sees the devices' words only at cycle ends. Faults come from the scenario's
// timeline or at random from a seed, and every one is recorded.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "ibs/devices/driver.hpp"
#include "ibs/devices/emulator.hpp"
#include "ibs/devices/registry.hpp"
#include "ibs/interbus/process_image.hpp"
#include "ibs/interbus/trace.hpp"
#include "ibs/sim/fork_join.hpp"
#include "ibs/master/master_loop.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::sim {

class MasterTimeline;  // master_timeline.hpp

struct StateRecord {
  Time at{0};
  std::string what;  // a DRIVECOM state as the master saw it, or an event such as a reached reference
};

struct TransactionRecord {
  std::string device;
  devices::ParamOp op = devices::ParamOp::read;
  std::uint16_t number = 0;
  std::int64_t value = 0;  // write: the value sent
  Time submitted{0};
  std::optional<Time> answered;  // the outcome was known
  std::optional<Time> finished;  // the channel was free again (the transfer time of 7.1)
  devices::ParamKind kind = devices::ParamKind::pending;
  std::int64_t result_value = 0;  // read: the value read
  std::string result;             // the outcome in words
  std::size_t source_line = 0;    // the timeline entry's line in the scenario file
  devices::ParamId id = 0;
};

struct FaultRecord {
  Time at{0};
  std::string device;  // empty: the whole bus
  std::string kind;    // corrupt, power-cycle, device-fault, fault-cleared, lost, back, master-restart,
                       // watchdog
  std::string detail;
};

// An entry of the live control channel that was applied (`ibs run --control`).
struct ControlRecord {
  Time at{0};              // when it was applied (deferred ones: when their device's wait ended)
  std::size_t line = 0;    // its line on the channel (in its client's input)
  std::uint32_t client = 0;  // the socket's client that sent it (0: standard input)
  std::string entry;       // as a control line (write_control_line)
  std::string device;      // its device; empty: bus-wide
};

// The master's sequencer failed a request (drivecom::Failure): it then sends BLOCK POWER until
// the next request.
struct FailureRecord {
  Time at{0};
  std::string failure;  // "fault", "left target", "timeout", "invalid status word"
  std::string what;     // drivecom::describe of the report
};

struct DeviceReport {
  std::string name;
  std::string kind;     // the drive kind's name, as the scenario's `type`
  std::string id_code;  // e.g. "4DBH: remote bus device, ..."
  std::string unit;     // rpm / Hz
  std::vector<StateRecord> states;
  std::string final_state;
  double final_reference = 0.0;
  double final_actual = 0.0;
  std::uint64_t samples = 0;
  std::vector<std::string> errors;  // e.g. "error 16 (E-OP1), location 1: bus watchdog"
  std::vector<FailureRecord> failures;  // the master's sequencer gave up on a request
};

// Cycles whose time exceeded one budget (a drive kind's processing period: 1 ms, 8.2 ms).
struct OverBudget {
  Duration budget{0};
  std::uint64_t cycles = 0;
  std::optional<Time> first;  // the first such cycle's time
};

struct TimingStats {
  std::uint64_t cycles = 0;
  double median_ns = 0.0;
  double p99_ns = 0.0;
  double p999_ns = 0.0;
  double max_ns = 0.0;
  std::uint64_t worst_cycle = 0;  // the index (0 = the first cycle) of the maximum
  Time worst_at{0};               // its time (the cycle's end on the bus)
  std::vector<OverBudget> over;   // per budget, the cycles above it
};
// The statistics of one value per cycle: `at(k)` is cycle k's time; `budgets` the limits to count.
TimingStats timing_stats(std::span<const std::uint32_t> ns, Duration cycle_time, std::span<const Duration> budgets);

// `ibs run --realtime` (sim/realtime.hpp): the master paced at the bus cycle in real time.
struct RealtimeStats {
  Duration cycle_time{0};
  TimingStats wake;        // wake-up latency against each cycle's deadline
  TimingStats processing;  // the master's processing per cycle (as `Summary::master`)
  std::uint64_t overruns = 0;       // cycles whose work ended after the next deadline
  std::optional<Time> first_overrun;
  std::optional<Time> worst_overrun;  // the cycle that ended latest behind its next deadline
  Duration worst_overrun_by{0};
  int rt_priority = 0;     // SCHED_FIFO priority in effect (0: none)
  bool memory_locked = false;
  std::vector<std::string> notes;  // what the system refused ("SCHED_FIFO priority 50 refused: ...")
};

struct Summary {
  // The report's first line when the run was not the simulator's (`ibs master --board`: the
  // master against a board, in real time); empty: "ibs run: scenario ..., simulated ...".
  std::string headline;
  std::string scenario;
  Duration simulated{0};
  Duration cycle_time{0};
  std::string cycle_time_basis;  // how the cycle time was obtained
  std::uint64_t cycles = 0;
  std::uint64_t valid_cycles = 0;
  std::vector<DeviceReport> devices;
  std::vector<TransactionRecord> transactions;
  std::vector<FaultRecord> faults;
  std::vector<ControlRecord> control;  // the control channel's entries, as applied
  TimingStats master;  // wall-clock processing time of the master's cycle (both drivers)
  double wall_seconds = 0.0;
  unsigned threads = 1;  // that stepped the devices
  std::optional<RealtimeStats> realtime;  // `ibs run --realtime`
};
// The drive kinds' processing periods (the MC6000's 1 ms, the VF1000's 8.2 ms), the budgets the
// master's time per cycle is set against.
std::vector<Duration> processing_budgets();

struct SimOptions {
  bool measure_master_time = true;  // wall-clock timing of every master cycle
  bool record_traces = false;       // keep per-device traces (traces() after run)
  // Called now and then with the simulated time reached (for a progress display).
  std::function<void(Time now, Duration total)> progress;
  // Threads that step the devices between two cycle ends; the run is the same for any number.
  // 1: everything on the calling thread (the default: on the 2-core machine of
  // docs/performance.md a second thread costs more in hand-overs than it gains, even on the
  // full bus); 0: one per core the process may use, as far as the ring has 16 MC6000 -- or
  // the samples of as many -- per thread. A run with an observer (a VCD file) uses one.
  unsigned threads = 1;
};

// Signals for a waveform recorder, reported after every event.
class Observer {
 public:
  virtual ~Observer() = default;
  virtual void on_cycle(Time at, bool valid, const interbus::ProcessImage& image) = 0;
  virtual void on_sample(Time at, std::size_t device, std::span<const Word> m2s,
                         std::span<const Word> s2m) = 0;
};

// A master other than ibs's own cycle loop (the virtual DDI board's firmware, ddi/): called at
// every cycle end after the bus exchange instead of MasterLoop::cycle, with the same image (read
// `in` and `pcp_in`, write `out` and `pcp_out` for the next exchange). A scenario run under one
// holds faults only: the commands of its timeline address ibs's master, which then does not run.
class ExternalMaster {
 public:
  virtual ~ExternalMaster() = default;
  virtual void cycle(interbus::ProcessImage& image, Time now, const master::Exchange& exchange) = 0;
  // The scenario's master_restart fault (the master's controller starts over).
  virtual void restart(Time now) = 0;
};

class Simulator {
 public:
  // Builds the ring, the device models and the master; throws std::invalid_argument with a clear
  // message for a configuration the bus or a device refuses.
  explicit Simulator(const Scenario& scenario);
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  void run(const SimOptions& options = {});
  // Runs until `until` (for tests that look in between); returns false once the scenario's end
  // has been reached.
  bool run_until(Time until, const SimOptions& options = {});
  void add_observer(Observer* o) { observers_.push_back(o); }
  // Before the run starts: `m` takes the master's place for the whole run (nullptr: ibs's own).
  void set_external_master(ExternalMaster* m) { external_ = m; }
  // The master's data transfer (the bus cycles): while stopped, every cycle end exchanges
  // nothing and delivers no valid data, as a bus whose master has stopped; the devices see no
  // bus cycles (their watchdogs run). On from the start.
  void set_bus_running(bool running) { bus_running_ = running; }
  [[nodiscard]] bool bus_running() const { return bus_running_; }
  // Device `i` switched off (bypassed) by the master: nothing is exchanged with it and its input
  // words read 0, without a module error; it sees no bus cycles. Until switched on again.
  void set_switched_off(std::size_t i, bool off);
  [[nodiscard]] bool switched_off(std::size_t i) const;

  [[nodiscard]] const Summary& summary();
  // The real-time runner's results go into the summary (sim/realtime.hpp).
  void set_realtime(RealtimeStats r) { summary_.realtime = std::move(r); }
  [[nodiscard]] Time now() const { return now_; }
  [[nodiscard]] const interbus::BusConfig& bus() const { return loop_->config(); }
  [[nodiscard]] Duration cycle_time() const { return cycle_time_; }
  [[nodiscard]] Duration scenario_duration() const { return scenario_.duration; }
  // The threads stepping the devices (1 until the run has started, or without worker threads).
  [[nodiscard]] unsigned threads() const { return workers_ ? workers_->parts() : 1; }
  // Recorded traces, one or more per device (a power cycle starts a new one), with file names.
  struct RecordedTrace {
    std::string file_name;
    trace::Trace trace;
  };
  [[nodiscard]] std::vector<RecordedTrace> traces() const;

  // The emulated devices and the master's drivers, by ring position.
  [[nodiscard]] std::size_t device_count() const { return devices_.size(); }
  devices::DeviceDriver& driver(std::size_t i) { return loop_->driver(i); }
  [[nodiscard]] drivecom::State device_state(std::size_t i) const;
  [[nodiscard]] double device_actual(std::size_t i) const;
  devices::DeviceEmulator& emulator(std::size_t i);
  [[nodiscard]] const devices::DeviceEmulator& emulator(std::size_t i) const;
  // The device's process-data words as `ibs layout` describes them (roles and meanings).
  [[nodiscard]] devices::LayoutDescription layout(std::size_t i) const;
  [[nodiscard]] std::optional<std::size_t> index_of(const std::string& name) const;
  // The bus reports a module error for the device (lost, or initialising).
  [[nodiscard]] bool module_error(std::size_t i, Time t) const;
  // Applies a fault now (between two run_until calls), exactly as a timeline entry at the time
  // reached would, and records it in the summary: fault_corrupt (count cycles from the next cycle
  // end on), fault_power_cycle, fault_device (duration), fault_lost (duration) of device `i`,
  // master_restart (i ignored). Other actions are ignored. Used by the fault campaign.
  void inject_fault(Action kind, std::size_t i, Duration duration = Duration{0}, int count = 1);
  // A control channel's entry (parse_control_line) at the simulated time reached: by the same
  // path as a timeline entry at that time, deferred like one while its device waits for a state.
  // Recorded in the summary's `control` when it is applied.
  void control(const TimelineEntry& e);

 private:
  struct Device;
  struct Recording;

  const devices::DeviceEmulator& prototype(const devices::DriveKind& kind, const devices::Configuration& config,
                                           DeviceStart start);
  void start(const SimOptions& options);
  void run_device_major(Time end);
  void step_devices(Time limit);
  void step_device(Device& d, Time limit);
  void start_threads(unsigned requested);
  void run_time_ordered(Time end);
  void handle_cycle(Time t);  // cycle_exchange, then cycle_master
  // The cycle end up to the bus exchange: timeline, faults, validity, the words both ways.
  void cycle_exchange(Time t);
  // The master's cycle after the exchange and what the summary takes from it.
  void cycle_master(Time t);
  void merge_device_records();
  void step_part(unsigned part);
  void handle_sample(std::size_t i, Time t);
  void record_sample(Device& d, const std::array<Word, 4>& before, Time t);
  void record_changes(Device& d);
  void apply_timeline(Time t);
  void apply(const TimelineEntry& e, Time t);
  void apply_random_faults(Time t);
  void fault(Time t, std::size_t i, Action kind, Duration duration, int count,
             const TimelineEntry* entry = nullptr);
  void plant(Time t, std::size_t i, const TimelineEntry& e, FaultRecord& f);
  void record_control(const TimelineEntry& e, Time t);
  void observe_master(Time t);
  Time next_sample_time(Device& d);
  void reschedule_front(Time at);
  void finish();

  Scenario scenario_;
  struct Prototype {
    const devices::DriveKind* kind;
    devices::DeviceSettings settings;
    DeviceStart start;
    std::unique_ptr<devices::DeviceEmulator> emulator;
  };
  std::vector<Prototype> prototypes_;  // while the ring is built, until the run starts
  std::unique_ptr<master::MasterLoop> loop_;
  // The master's side of the scenario: its commands, what its drivers saw (master_timeline.hpp).
  std::unique_ptr<MasterTimeline> master_side_;
  std::vector<std::unique_ptr<Device>> devices_;
  interbus::ProcessImage image_;
  std::vector<master::LinkState> links_;  // the exchange of the cycle end (master/bus.hpp)
  Duration cycle_time_{0};
  Time now_{0};
  Time next_cycle_{0};
  bool started_ = false;
  bool finished_ = false;
  int corrupt_left_ = 0;
  int recovery_left_ = 0;
  std::size_t timeline_next_ = 0;
  std::vector<const TimelineEntry*> deferred_;  // entries of devices waiting for a state
  // The control channel's entries, kept here so that the pointers in deferred_ stay valid.
  std::deque<TimelineEntry> control_entries_;
  std::mt19937_64 rng_;
  struct RandomNext {
    Time corrupt, power_cycle, device_fault, lost, master_restart;
  } random_next_{};
  // Every device's next sample, as a min-heap on time (ties: lower ring position first).
  struct SampleEvent {
    Time at{0};
    std::size_t device = 0;
    friend auto operator<=>(const SampleEvent&, const SampleEvent&) = default;  // NOLINT(modernize-use-nullptr): clang-tidy 14 misreads a defaulted <=>
  };
  std::vector<SampleEvent> samples_;
  std::vector<std::uint32_t> master_ns_;
  std::vector<Observer*> observers_;
  ExternalMaster* external_ = nullptr;
  bool bus_running_ = true;
  SimOptions options_;
  Summary summary_;
  double wall_start_ = 0.0;
  // Device stepping on several threads: the ring split into parts of about equal work.
  struct Part {
    std::size_t first = 0;
    std::size_t end = 0;
  };
  std::vector<Part> parts_;
  Time window_limit_{0};              // the cycle end the parts step up to
  std::optional<Time> master_due_;    // a cycle whose master's part runs with the next stepping
  bool last_cycle_valid_ = true;
  std::unique_ptr<ForkJoin> workers_;  // last: its threads stop before the devices go
};

}  // namespace ibs::sim
