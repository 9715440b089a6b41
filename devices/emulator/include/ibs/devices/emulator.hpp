// The device side of one drive, as the simulator and the `words: pd` replay run it: what every
// drive's emulator implements (devices/<drive>/emulator/), mirroring the master side's
// DeviceDriver (driver.hpp). One sample is one processing step of the drive at its period
// (DriveFacts::sample_period); time is passed in. sample(), sample_deferred(), sample_held(),
// output() and the fault and watchdog calls are cycle-path: no allocation, no exceptions.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "ibs/devices/plant_event.hpp"
#include "ibs/drive/parameter_journal.hpp"
#include "ibs/drivecom/status_word.hpp"
#include "ibs/interbus/device_start.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"

namespace ibs::devices {

// The words of one sample: as the bus last delivered the master's, and the device's own.
struct EmulatorIo {
  std::span<const Word> pd_in;   // the master's process-data words (control word first)
  std::span<Word> pd_out;        // the device's process-data words (status word first)
  std::span<const Word> pcp_in;  // PCP channel words from the master (empty without a channel)
  std::span<Word> pcp_out;       // PCP channel words to the master
};

// Something the device did that its words do not show, for the run summary.
struct Notices {
  std::uint32_t count = 0;  // how often, since the device was made
  std::string_view what;    // e.g. "15-PLRDY = 1: controller parameters recalculated"
};

class DeviceEmulator {
 public:
  virtual ~DeviceEmulator() = default;
  DeviceEmulator& operator=(const DeviceEmulator&) = delete;
  // An identical device: servos of one configuration are built once and copied.
  [[nodiscard]] virtual std::unique_ptr<DeviceEmulator> clone() const = 0;

  // One sample at `now`: reads the master's words, writes the device's.
  virtual void sample(const EmulatorIo& io, Time now) = 0;
  // True when the device's process-data words may be formed once after a stretch of samples
  // (nobody reads them in between; a device with a parameter channel answers sample by sample):
  // then the simulator calls sample_deferred() or sample_held() and output() at the stretch's end.
  [[nodiscard]] virtual bool defers_output() const { return false; }
  // One sample that does not write the process-data words.
  virtual void sample_deferred(std::span<const Word> pd_in, Time now) = 0;
  // `count` samples at first, first + period, ... with the same master words: exactly what as
  // many sample_deferred() calls do.
  virtual void sample_held(std::span<const Word> pd_in, Time first, Duration period, std::uint32_t count) {
    for (std::uint32_t k = 0; k < count; ++k) sample_deferred(pd_in, first + static_cast<std::int64_t>(k) * period);
  }
  // The words the device shows now: after its last sample, or before its first.
  virtual void output(std::span<Word> pd_out) const = 0;
  virtual void output_pcp(Time /*now*/, std::span<Word> /*pcp_out*/) {}
  // The parameter channel's interface side at a valid data cycle (the MC6000's INTERBUS CPU,
  // INTERBUS manual 3.2.2): reads the master's channel words of this cycle, writes the device's for the
  // next one. A caller that calls it gives sample() empty PCP spans; a caller without it (one
  // sample per cycle) gives sample() the words and the device runs its interface there.
  virtual void pcp_cycle(Time /*now*/, std::span<const Word> /*pcp_in*/, std::span<Word> /*pcp_out*/) {}

  // A valid data cycle reached the device (its bus watchdog is fed by every one).
  virtual void bus_cycle(Time now) = 0;
  // Switched off and on: initialising again.
  virtual void power_cycle(Time now) = 0;
  // A device fault (e.g. overcurrent) present or gone.
  virtual void set_fault(bool present) = 0;
  // A plant or fault event (plant_event.hpp), checked against the kind's EventFacts beforehand;
  // false: the drive does not take it. By default a drive takes a fault without a cause and a
  // power cycle; a wing with more overrides it.
  virtual bool apply_event(const PlantEvent& e, Time now) {
    switch (e.kind) {
      case PlantEvent::Kind::fault:
      case PlantEvent::Kind::fault_clear:
        set_fault(e.kind == PlantEvent::Kind::fault);
        return true;
      case PlantEvent::Kind::power_cycle:
        power_cycle(now);
        return true;
      default:
        return false;
    }
  }
  // The bus reports a module error for the device (initialising, or a configuration the running
  // ring cannot carry).
  [[nodiscard]] virtual bool module_error(Time now) const = 0;
  // True when the device, while the bus reports its module error, still takes the master's
  // words into its bus interface (the VF1000 initialising, INTERBUS manual 6.1).
  [[nodiscard]] virtual bool takes_words_in_module_error() const { return false; }
  // The error number the drive shows after its watchdog ran out; nullopt: none.
  [[nodiscard]] virtual std::optional<int> error_number() const = 0;
  [[nodiscard]] virtual bool watchdog_tripped() const = 0;

  [[nodiscard]] virtual drivecom::State state() const = 0;
  // The actual value in the drive's unit (DriveFacts::unit).
  [[nodiscard]] virtual double actual() const = 0;
  [[nodiscard]] virtual Notices notices() const { return {}; }
  // The trace `init` a device now at rest would be recorded with: initialised (power-on bit set)
  // or operational.
  [[nodiscard]] virtual DeviceStart trace_start() const { return DeviceStart::initialised; }

  // A recording of the process-data words (../shared/specs/trace-format.md, `! write PNR VALUE`):
  // the parameter changes the drive's channels made that those words do not carry -- the MC6000's
  // PCP, a LUSTBUS face serving the same drive core -- kept from record_changes(true) on and taken
  // in order (at most out.size() a call; the rest stay). Cycle path: no allocation.
  virtual void record_changes(bool /*on*/) {}
  virtual std::size_t take_changes(std::span<drive::ParameterChange> /*out*/) { return 0; }
  // The same change in a replay: the parameter takes `value` (a channel's raw value) as if written
  // through the device's own channel, with its checks; 85-SIOF/SERR, which no channel writes, takes
  // the bits a channel's requests left (docs/replay.md, "Events"). Empty when taken, else why not.
  // Replay only: may allocate.
  virtual std::string write_parameter(std::uint16_t number, std::int64_t /*value*/, Time /*now*/) {
    return "parameter " + std::to_string(number) + ": this device takes no parameter writes";
  }

 protected:
  DeviceEmulator() = default;
  DeviceEmulator(const DeviceEmulator&) = default;  // for clone()
};

}  // namespace ibs::devices
