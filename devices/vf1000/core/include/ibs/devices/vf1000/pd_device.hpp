// The VF1000's process data as the inverter handles it (INTERBUS manual 3.1, 5.2): three words
// (control, reference, communication word), DRIVECOM sampled every 8.2 ms, ramp generator bits
// 4-6, STL/STR, stop ramp 36-RSTOP.
#pragma once

#include <cstddef>
#include <optional>
#include <span>

#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/interbus/device_start.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"

namespace ibs::devices {

struct Vf1000PdConfig {
  Duration init_time = 4s;            // initialisation and self-test after power-on (6.1)
  // RESET FAULT is a software reset (5.2.1): the inverter boots and runs its self-test again.
  // The manuals give no time for it; the one boot they time is 6.1's ~4 s for "initialization and
  // the self-test", and the LUSTBUS manual (8.1.1, 9.2) treats the reset as a new start like a power-on,
  // so the default is that time (decision D13, docs/vf1000_channel.md).
  Duration reset_time = 4s;
  double acceleration_hz_per_s = 20;  // ramp generator, up
  double deceleration_hz_per_s = 20;  // ramp generator, down
  double stop_ramp_hz_per_s = 50;     // 36-RSTOP: stop ramp; 0 = no stop ramp (power stage off)
  double max_frequency_hz = 400;
  // INTERBUS manual 5.2.3: "At a reference value of 0 Hz the inverter shuts down the motor if DC-Stop is
  // not programmed!" No seed names the parameter that programs DC-Stop, so it is the model's
  // configuration, off as the warning assumes (decision VF-E19).
  bool dc_stop = false;
};

class Vf1000PdDevice {
 public:
  static constexpr std::size_t kWords = vf1000::kWords;
  explicit Vf1000PdDevice(const Vf1000PdConfig& config = {});

  void power_on();
  // RESET FAULT taken (transition 15): the inverter performs a software reset (5.2.1) and boots
  // as after power-on, NOT READY for config().reset_time. `control` is the word that reset it:
  // a bit 7 still held high after the boot is no new edge, so a level resets only once.
  void software_reset(Word control);
  // Starts initialised, without the initialisation time: START-UP INHIBIT, or FAULT for
  // DeviceStart::fault (use power_on() for a drive switched on now).
  void start(DeviceStart s);

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
  [[nodiscard]] const Vf1000PdConfig& config() const { return config_; }
  [[nodiscard]] drivecom::State state() const { return machine_.state(); }
  // The power stage modulates: DRIVECOM's power stage states, except while the inverter has shut
  // the motor down at a reference of 0 Hz (5.2.3, VF-E19: the state stays ENABLED).
  [[nodiscard]] bool power_stage_on() const {
    return drivecom::power_stage_enabled(machine_.state()) && !zero_hz_off_;
  }
  [[nodiscard]] bool shut_down_at_zero_hz() const { return zero_hz_off_; }
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
  Duration boot_time_{0};  // init_time after power-on, reset_time after a software reset
  bool initialised_ = true;
  bool fault_present_ = false;
  bool s2out_ = false;
  bool s1out_ = false;
  double setpoint_ = 0.0;   // signed, after direction
  double frequency_ = 0.0;  // signed ramp output
  bool at_setpoint_ = false;
  bool zero_hz_off_ = false;  // 5.2.3: shut down at a reference of 0 Hz
  std::optional<Word> override_;
  Word status_ = 0;
  Word comm_ = 0x8000;
};

}  // namespace ibs::devices
