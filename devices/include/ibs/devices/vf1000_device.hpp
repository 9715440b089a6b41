// The VF1000 as the simulator runs it (seed 001, 3.1, 4.1, 5.2, 6.1, 7.1): process data sampled
// every 8.2 ms, the parameter channel in the communication word with the inverter's parameter
// table behind it, the 906-IB-WD watchdog with the 907-IBCOD reactions, and the ~4 s
// initialisation after power-on during which the bus reports a module error.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "ibs/devices/drive_pd.hpp"
#include "ibs/interbus/time.hpp"
#include "ibs/vf1000_channel/server.hpp"

namespace ibs::devices {

struct Vf1000DeviceConfig {
  Vf1000PdConfig pd{};
  vf1000_channel::ServerConfig channel{};
  // How long the inverter takes for one step of the parameter channel, in 8.2 ms samples from the
  // sample that first sees the master's new word. Calibrated to seed 001, 7.1 (without KEYPAD,
  // motor stopped): value inquiry ~100 ms (3 steps), value transfer ~124-131 ms (4 steps), scan of
  // a description ~490 ms (19 steps); an EEPROM value that changes takes ~250 ms in all.
  int value_step_samples = 4;
  int description_step_samples = 3;
  int eeprom_change_extra_samples = 15;
};

// How the device starts a run.
enum class DeviceStart : std::uint8_t {
  power_on,     // switched on now: initialising (NOT READY, module error) for ~4 s
  initialised,  // initialisation done, power-on bit still set in 85-SIOF
  operational,  // running, 85-SIOF read and clear
  fault,        // a latched fault whose cause has gone (DRIVECOM FAULT)
};

// The watchdog error the VF1000 shows for 907-IBCOD = 1 (4.1.1): E-IBS, error number 12.
inline constexpr int kVf1000WatchdogError = 12;

class Vf1000Device {
 public:
  static constexpr std::size_t kWords = 3;
  Vf1000Device(const Vf1000DeviceConfig& config, DeviceStart start, Time now);

  // One 8.2 ms sample: reads the three words the master wrote (as the bus last delivered them),
  // writes the three words the master reads. No allocation, no exceptions.
  void sample(std::span<const Word> m2s, std::span<Word> s2m, Time now);
  // The words the device shows now.
  void output(std::span<Word> s2m) const { pd_.output(s2m); }

  // A valid data cycle reached the device (the process-data watchdog is fed by every one).
  void bus_cycle(Time now);
  // Switched off and on: initialising again, parameters from EEPROM, power-on bit set.
  void power_cycle(Time now);
  // A device fault (e.g. overcurrent) present or gone.
  void set_fault(bool present) { external_fault_ = present; }

  // The bus shows a module error for this device (initialisation, 6.1).
  [[nodiscard]] bool module_error(Time now) const { return server_.initialising(now); }
  [[nodiscard]] drivecom::State state() const { return pd_.state(); }
  [[nodiscard]] double frequency_hz() const { return pd_.frequency_hz(); }
  [[nodiscard]] double setpoint_hz() const { return pd_.setpoint_hz(); }
  [[nodiscard]] Word status_word() const { return pd_.status_word(); }
  [[nodiscard]] bool watchdog_tripped() const { return tripped_; }
  [[nodiscard]] std::optional<int> error_number() const {
    return watchdog_fault_ ? std::optional<int>(kVf1000WatchdogError) : std::nullopt;
  }
  [[nodiscard]] const vf1000_channel::Server& channel() const { return server_; }
  [[nodiscard]] vf1000_channel::Server& channel() { return server_; }
  [[nodiscard]] const drivecom::SampleResult& last_sample() const { return pd_.last_sample(); }

 private:
  Word channel_word(Word from_master, Time now);
  void apply_parameters();
  void mirror_parameters(Word control, Word reference);
  void run_watchdog(Time now);

  Vf1000DeviceConfig config_;
  Vf1000PdDevice pd_;
  vf1000_channel::Server server_;
  // Parameter channel timing: the inverter takes `pending_` more samples for the word it saw.
  int pending_ = 0;
  int hold_ = 0;          // samples the last answer is still held back (EEPROM write)
  Word taken_ = 0;        // the master word the last channel step answered
  Word shown_ = 0x0000;   // the communication word on the bus
  Word held_answer_ = 0;  // an answer waiting for hold_ to run out
  // Watchdog (906/907).
  bool armed_ = false;
  Time last_cycle_{0};
  bool tripped_ = false;
  bool watchdog_fault_ = false;
  bool external_fault_ = false;
};

}  // namespace ibs::devices
