// The process-data side of both drives: what the VF1000 and the MC6000 do with their output
// words each processing sample, and the master-side drivers that compose the DRIVECOM sequencer
// with the reference/actual conversion to engineering units.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/devices/drive_plant.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/drivecom/sequencer.hpp"
#include "ibs/interbus/mc6000_layout.hpp"
#include "ibs/interbus/time.hpp"
#include "ibs/interbus/words.hpp"

namespace ibs::devices {

// How a drive starts a run (the trace `init` header).
enum class InitState { operational, power_on, fault };

// ---------------------------------------------------------------------------------------------
// MC6000 (seed 001, 3.2, 5.3): DRIVECOM sampled every 1 ms, reference and actual in the layout
// 405-SUPI / 406-IBCNF chose at power-on, speed control.

struct Mc6000PdConfig {
  interbus::mc6000::Layout layout = interbus::mc6000::make_layout(11, 2);
  Duration init_time = 500ms;         // power-on self-test (NOT READY)
  DrivePlantParams plant{};           // speed loop and load (drive_plant.hpp)
  double max_speed_rpm = 6000;        // the reference is limited to +-this (status bit 11)
  double standstill_rpm = 0.5;        // below this the fault reaction counts as done
};

class Mc6000PdDevice {
 public:
  explicit Mc6000PdDevice(const Mc6000PdConfig& config = {});

  // Power-on: NOT READY for init_time, then START-UP INHIBIT.
  void power_on();
  // Starts in a given state without the power-on delay (trace `init`).
  void start(InitState s);

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
  // The words the device shows: after the last sample, or before the first.
  void output(std::span<Word> s2m) const;

  void set_fault(bool present) { fault_present_ = present; }
  // While set the drive is not engaged: ENABLE stops in ON (80-SLOAD download, seed 000 11.4).
  void set_enable_locked(bool locked) { enable_locked_ = locked; }
  void set_inputs(bool is00, bool is01) { is00_ = is00; is01_ = is01; }
  void set_load_torque(double nm) { load_nm_ = nm; }
  // The control word the drive acts on instead of the master's while set (watchdog reactions).
  void override_control(std::optional<Word> w) { override_ = w; }

  [[nodiscard]] const interbus::mc6000::Layout& layout() const { return config_.layout; }
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

// ---------------------------------------------------------------------------------------------
// VF1000 (seed 001, 3.1, 5.2): three words (control, reference, communication word), DRIVECOM
// sampled every 8.2 ms, ramp generator bits 4-6, STL/STR, stop ramp 36-RSTOP.

struct Vf1000PdConfig {
  Duration init_time = 4s;            // initialisation and self-test after power-on (6.1)
  double acceleration_hz_per_s = 20;  // ramp generator, up
  double deceleration_hz_per_s = 20;  // ramp generator, down
  double stop_ramp_hz_per_s = 50;     // 36-RSTOP: stop ramp; 0 = no stop ramp (power stage off)
  double max_frequency_hz = 400;
};

// The rotating-field frequency in the reference word: 0.05 Hz per bit, an absolute value (5.2.3).
inline constexpr double kVf1000HzPerBit = 0.05;
Word vf1000_reference_word(double hz);
double vf1000_reference_hz(Word w);
// The actual frequency in the second status-side word: 0.05 Hz per bit, signed (negative =
// counter-clockwise) -- a modelling choice, the manual does not define this word.
Word vf1000_actual_word(double hz);
double vf1000_actual_hz(Word w);

class Vf1000PdDevice {
 public:
  static constexpr std::size_t kWords = 3;
  explicit Vf1000PdDevice(const Vf1000PdConfig& config = {});

  void power_on();
  void start(InitState s);

  // One 8.2 ms processing sample of words 1 and 2. The communication word (word 3) belongs to the
  // parameter channel: the caller passes the channel's answer in `comm_out` (or nullopt for an
  // idle channel: 8000H in operation, 0000H while initialising).
  void sample(std::span<const Word> m2s, std::span<Word> s2m, Duration dt,
              std::optional<Word> comm_out = std::nullopt);
  void output(std::span<Word> s2m) const;

  void set_fault(bool present) { fault_present_ = present; }
  void set_outputs(bool s2out, bool s1out) { s2out_ = s2out; s1out_ = s1out; }
  void set_stop_ramp(double hz_per_s) { config_.stop_ramp_hz_per_s = hz_per_s; }
  void set_max_frequency(double hz) { config_.max_frequency_hz = hz; }
  // The control word the drive acts on instead of the master's while set (watchdog reactions).
  void override_control(std::optional<Word> w) { override_ = w; }

  [[nodiscard]] bool initialised() const { return initialised_; }
  [[nodiscard]] drivecom::State state() const { return machine_.state(); }
  [[nodiscard]] double frequency_hz() const { return frequency_; }
  [[nodiscard]] double setpoint_hz() const { return setpoint_; }
  [[nodiscard]] Word status_word() const { return status_; }
  [[nodiscard]] const drivecom::SampleResult& last_sample() const { return last_; }

 private:
  void run_ramp(Word control, double dt_s);

  Vf1000PdConfig config_;
  drivecom::DeviceStateMachine machine_;
  drivecom::SampleResult last_{};
  Duration since_power_on_{0};
  bool initialised_ = true;
  bool fault_present_ = false;
  bool s2out_ = false;
  bool s1out_ = false;
  double setpoint_ = 0.0;   // signed, after direction
  double frequency_ = 0.0;  // signed ramp output
  bool at_setpoint_ = false;
  std::optional<Word> override_;
  Word status_ = 0;
  Word comm_ = 0x8000;
};

// ---------------------------------------------------------------------------------------------
// Master-side drivers: the DRIVECOM sequencer plus the reference in engineering units.

class Mc6000PdMaster {
 public:
  explicit Mc6000PdMaster(const interbus::mc6000::Layout& layout,
                          const drivecom::SequencerConfig& config = drivecom::SequencerConfig::defaults());

  drivecom::Sequencer& sequencer() { return sequencer_; }
  [[nodiscard]] const drivecom::Sequencer& sequencer() const { return sequencer_; }
  void set_reference_rpm(double rpm) { reference_ = rpm; }
  [[nodiscard]] double reference_rpm() const { return reference_; }

  // One master cycle: reads the status-side words, writes the control-side words.
  void cycle(std::span<const Word> s2m, std::span<Word> m2s, Time now);
  // The words before the first cycle: BLOCK POWER, reference 0.
  void initial(std::span<Word> m2s) const;

  [[nodiscard]] double actual_rpm() const { return actual_.value; }
  [[nodiscard]] const interbus::mc6000::Actual& actual() const { return actual_; }
  [[nodiscard]] const interbus::mc6000::Layout& layout() const { return layout_; }

 private:
  interbus::mc6000::Layout layout_;
  drivecom::Sequencer sequencer_;
  double reference_ = 0.0;
  // The reference as bus words, encoded again only when it changes.
  std::array<Word, 2> reference_words_{};
  double encoded_reference_ = 0.0;
  interbus::mc6000::Actual actual_{};
};

class Vf1000PdMaster {
 public:
  explicit Vf1000PdMaster(const drivecom::SequencerConfig& config = drivecom::SequencerConfig::defaults());

  drivecom::Sequencer& sequencer() { return sequencer_; }
  [[nodiscard]] const drivecom::Sequencer& sequencer() const { return sequencer_; }
  // Signed: positive runs clockwise (STR), negative counter-clockwise (STL), 0 sets neither.
  void set_frequency_hz(double hz);
  [[nodiscard]] double frequency_setpoint_hz() const { return setpoint_; }

  // One master cycle over words 1 and 2; `comm` is the parameter channel's word 3 to send.
  void cycle(std::span<const Word> s2m, std::span<Word> m2s, Time now, Word comm = 0);
  void initial(std::span<Word> m2s) const;

  [[nodiscard]] double actual_hz() const { return actual_; }

 private:
  drivecom::Sequencer sequencer_;
  double setpoint_ = 0.0;
  double actual_ = 0.0;
};

}  // namespace ibs::devices
