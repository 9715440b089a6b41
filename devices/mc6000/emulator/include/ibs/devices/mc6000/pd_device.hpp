// The MC6000's process data as the servo handles it (INTERBUS manual 3.2, 5.3): DRIVECOM sampled every
// 1 ms, reference and actual in the layout 405-SUPI / 406-IBCNF chose at power-on, speed control
// with the servo plant behind it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/devices/mc6000/plant.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/interbus/device_start.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"

namespace ibs::devices {

struct Mc6000PdConfig {
  mc6000::Layout layout = mc6000::make_layout(11, 2);
  Duration init_time = 500ms;         // power-on self-test (NOT READY)
  DrivePlantParams plant{};           // speed loop and load (plant.hpp)
  double max_speed_rpm = 6000;        // the reference is limited to +-this (status bit 11)
  double standstill_rpm = 0.5;        // below this the fault reaction counts as done
};

// The process-data words a servo shows in `layout`: the status word, then the actual words
// (IBCNF 3: speed and torque in % of the rated torque); all zero for SUPI 0 (3.2.2).
void write_pd_words(const mc6000::Layout& layout, Word status, double actual_rpm, double torque_percent,
                    std::span<Word> s2m);

class Mc6000PdDevice {
 public:
  explicit Mc6000PdDevice(const Mc6000PdConfig& config = {});

  // Power-on: NOT READY for init_time, then START-UP INHIBIT.
  void power_on();
  // Starts initialised, without the power-on delay: START-UP INHIBIT, or FAULT for
  // DeviceStart::fault (use power_on() for a drive switched on now).
  void start(DeviceStart s);

  // One processing sample (dt = 1 ms normally): reads the pd words the master wrote (control
  // word first), writes the pd words the master reads (status word first). Both spans are
  // layout().pd_words long. No allocation, no exceptions.
  void sample(std::span<const Word> m2s, std::span<Word> s2m, Duration dt) {
    step(m2s, dt);
    output(s2m);
  }
  // The same sample without writing the words: output() then writes them as they stand after
  // the last sample. A simulator that reads the words only at a bus cycle end forms them once
  // per cycle instead of once per sample; the words are the same.
  void step(std::span<const Word> m2s, Duration dt) { step_held(m2s, dt, 1); }
  // `count` samples with the same master words (between two bus cycles they do not change):
  // exactly what `count` calls of step() do, with the words decoded once.
  void step_held(std::span<const Word> m2s, Duration dt, std::uint32_t count);
  // The same with the words already decoded: the control word and the speed reference (rpm), as
  // the drive core (drive.hpp) takes them from whichever interface has the control location.
  void step_held(Word control, double reference_rpm, Duration dt, std::uint32_t count);
  // The words the device shows: after the last sample, or before the first.
  void output(std::span<Word> s2m) const;

  // A fault present; `coast`: its reaction switches the power stage off at once, so the fault
  // reaction is done in the sample it starts (FAULT without braking: docs/errata.md MC-D7).
  void set_fault(bool present, bool coast = false) {
    fault_present_ = present;
    coast_ = coast;
  }
  // While set the drive is not engaged: ENABLE stops in ON (80-SLOAD download, LUSTBUS manual 11.4).
  void set_enable_locked(bool locked) { enable_locked_ = locked; }
  void set_inputs(bool is00, bool is01) { is00_ = is00; is01_ = is01; }
  void set_load_torque(double nm) { load_nm_ = nm; }
  // The control word the drive acts on instead of the master's while set (watchdog reactions).
  void override_control(std::optional<Word> w) { override_ = w; }

  [[nodiscard]] const mc6000::Layout& layout() const { return config_.layout; }
  [[nodiscard]] drivecom::State state() const { return machine_.state(); }
  [[nodiscard]] double reference_rpm() const { return reference_; }
  [[nodiscard]] double actual_rpm() const { return actual_; }
  [[nodiscard]] double torque_nm() const { return plant_.torque_nm(); }
  // The motor torque in % of the rated torque (IBCNF 3's second actual word).
  [[nodiscard]] double torque_percent() const { return 100.0 * plant_.torque_nm() / config_.plant.rated_torque; }
  [[nodiscard]] bool initialised() const { return initialised_; }
  [[nodiscard]] Word status_word() const { return status_; }
  [[nodiscard]] const drivecom::SampleResult& last_sample() const { return last_; }

 private:
  void sample_held(Word control, Duration dt);
  [[nodiscard]] PlantInput plant_input() const;
  void move_actual(Duration dt);
  void reset_motion();

  Mc6000PdConfig config_;
  drivecom::DeviceStateMachine machine_;
  drivecom::SampleResult last_{};
  Duration since_power_on_{0};
  bool initialised_ = true;
  bool fault_present_ = false;
  bool coast_ = false;
  bool enable_locked_ = false;
  bool is00_ = false;
  bool is01_ = false;
  double load_nm_ = 0.0;
  std::optional<Word> override_;
  DrivePlant plant_;
  double reference_ = 0.0;
  double actual_ = 0.0;
  Word status_ = 0;
};

}  // namespace ibs::devices
