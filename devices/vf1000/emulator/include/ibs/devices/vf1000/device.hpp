// The VF1000's INTERBUS face as the simulator runs it (INTERBUS manual 3.1, 4.1, 5.2, 6.1, 7.1): process
// data sampled every 8.2 ms, the parameter channel in the communication word, and the module
// error while the inverter initialises. The drive itself -- its parameters, 85-SIOF, DRIVECOM and
// ramp, the 906/907 watchdog, faults and resets, the ~4 s initialisation, the storing times -- is
// the drive core (drive.hpp); this face keeps only the channel's protocol state and its step
// timing, and may share its core with the LUSTBUS face (lustbus_device.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "ibs/devices/descriptor.hpp"
#include "ibs/devices/emulator.hpp"
#include "ibs/devices/vf1000/channel.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/devices/vf1000/drive.hpp"
#include "ibs/devices/vf1000/pd_device.hpp"
#include "ibs/interbus/device_start.hpp"
#include "ibs/base/time.hpp"
#include "ibs/vf1000_channel/server.hpp"

namespace ibs::devices {

struct Vf1000DeviceConfig {
  Vf1000PdConfig pd{};
  vf1000_channel::ServerConfig channel = vf1000::server_config();
  // How long the inverter takes for one step of the parameter channel, in 8.2 ms samples from the
  // sample that first sees the master's new word. Calibrated to the INTERBUS manual 7.1 (without KEYPAD,
  // motor stopped): value inquiry ~100 ms (3 steps), value transfer ~124-131 ms (4 steps), scan of
  // a description ~490 ms (19 steps). How long storing takes (an EEPROM value that changes: ~250
  // ms in all; 71-PROG) is the drive's (storing), held back here in whole 8.2 ms samples.
  int value_step_samples = 4;
  int description_step_samples = 3;
  vf1000::StoringTimes storing{};
  // The other rows of 7.1. A KEYPAD plugged into the inverter is served by the same processor: a
  // value inquiry takes ~115 ms instead of ~100 (2 samples more at its start) and a value
  // transfer ~192 ms instead of ~131 (7 samples more before its ACK); a description takes 490 ms
  // in every row. With the motor running (power stage on, modulating) a value transfer takes
  // ~131 ms instead of ~124 (1 sample more before its ACK). 7.1 has no row "KEYPAD, motor
  // stopped": there the two add up (decision D14, docs/vf1000_channel.md).
  bool keypad = false;
  int keypad_inquiry_extra_samples = 2;
  int keypad_transfer_extra_samples = 7;
  int running_transfer_extra_samples = 1;
};

class Vf1000Device final : public DeviceEmulator {
 public:
  static constexpr std::size_t kWords = vf1000::kWords;
  // A drive of its own, started as `start` (power_on: initialising, NOT READY, module error, for
  // ~4 s). Allocates.
  Vf1000Device(const Vf1000DeviceConfig& config, DeviceStart start, Time now);
  // The INTERBUS face of an existing drive (which another face may serve too); config.pd and
  // config.storing are the drive's and not used. Allocates.
  Vf1000Device(const Vf1000DeviceConfig& config, std::shared_ptr<vf1000::Drive> drive, Time now);
  // A copy is an independent inverter: the face with a copy of its drive.
  Vf1000Device(const Vf1000Device& other);
  Vf1000Device& operator=(const Vf1000Device&) = delete;
  ~Vf1000Device() override;
  [[nodiscard]] std::unique_ptr<DeviceEmulator> clone() const override {
    return std::make_unique<Vf1000Device>(*this);
  }

  // One 8.2 ms sample: reads the three words the master wrote (as the bus last delivered them),
  // writes the three words the master reads. No allocation, no exceptions.
  void sample(std::span<const Word> m2s, std::span<Word> s2m, Time now);
  void sample(const EmulatorIo& io, Time now) override { sample(io.pd_in, io.pd_out, now); }
  // The words are formed in every sample anyway (the communication word answers in it).
  void sample_deferred(std::span<const Word> m2s, Time now) override {
    std::array<Word, kWords> words{};
    sample(m2s, words, now);
  }
  // The words the device shows now.
  void output(std::span<Word> s2m) const override { drive_->output(s2m); }

  // A valid data cycle reached the device (the process-data watchdog is fed by every one).
  void bus_cycle(Time now) override;
  // Switched off and on: initialising again, parameters from EEPROM, power-on bit set.
  void power_cycle(Time now) override;
  // How many times RESET FAULT made the inverter perform its software reset (5.2.1).
  [[nodiscard]] std::uint32_t software_resets() const { return drive_->software_resets(); }
  // A KEYPAD plugged in or pulled (7.1: it slows the parameter channel).
  void set_keypad(bool plugged) { config_.keypad = plugged; }
  [[nodiscard]] bool keypad() const { return config_.keypad; }
  // A device fault (e.g. overcurrent) present or gone.
  void set_fault(bool present) override { drive_->set_fault(present, last_sample_); }
  // Plant and fault events (plant_event.hpp): the core's, once for every face.
  bool apply_event(const PlantEvent& e, Time now) override;

  // The bus shows a module error for this device (initialisation, 6.1); meanwhile its bus
  // interface still takes the master's words, and it acts on the newest ones once it is ready.
  // INTERBUS manual 6.1: also while a SMARTCARD is read or written ("bus operation is disabled"; VF-E21).
  [[nodiscard]] bool module_error(Time now) const override {
    return drive_->initialising(now) || drive_->card_busy(now);
  }
  [[nodiscard]] bool takes_words_in_module_error() const override { return true; }
  [[nodiscard]] drivecom::State state() const override { return drive_->state(); }
  [[nodiscard]] double frequency_hz() const { return drive_->frequency_hz(); }
  [[nodiscard]] double actual() const override { return drive_->frequency_hz(); }
  // Recorded as `init: operational` once 85-SIOF has been read clear, else `init: power-on`.
  [[nodiscard]] DeviceStart trace_start() const override {
    return drive_->siof() == 0 ? DeviceStart::operational : DeviceStart::initialised;
  }
  [[nodiscard]] double setpoint_hz() const { return drive_->pd().setpoint_hz(); }
  [[nodiscard]] Word status_word() const { return drive_->pd().status_word(); }
  [[nodiscard]] bool watchdog_tripped() const override { return drive_->interbus_watchdog_tripped(); }
  [[nodiscard]] std::optional<int> error_number() const override {
    return drive_->e_ibs() ? std::optional<int>(vf1000::kWatchdogError) : std::nullopt;
  }
  // A recording's `! write` events: the LUSTBUS face's changes (the communication word's are in
  // these words); and their replay, through the drive's checks as a value transfer has them.
  void record_changes(bool on) override { drive_->journal().enable(on); }
  std::size_t take_changes(std::span<drive::ParameterChange> out) override { return drive_->journal().take(out); }
  std::string write_parameter(std::uint16_t number, std::int64_t value, Time now) override;
  [[nodiscard]] const vf1000_channel::Server& channel() const { return server_; }
  [[nodiscard]] vf1000_channel::Server& channel() { return server_; }
  [[nodiscard]] const drivecom::SampleResult& last_sample() const { return drive_->pd().last_sample(); }
  // The drive behind this face.
  [[nodiscard]] const vf1000::Drive& drive() const { return *drive_; }
  [[nodiscard]] vf1000::Drive& drive() { return *drive_; }
  [[nodiscard]] const std::shared_ptr<vf1000::Drive>& shared_drive() const { return drive_; }

 private:
  Word channel_word(Word from_master, Time now);
  bool sync(Time now);
  void reset_channel(Time now);

  Vf1000DeviceConfig config_;
  std::shared_ptr<vf1000::Drive> drive_;
  vf1000_channel::Server server_;
  std::uint32_t seen_starts_ = 0;  // the drive's starts() the channel last followed
  Time last_sample_{0};
  // Parameter channel timing: the inverter takes `pending_` more samples for the word it saw.
  int pending_ = 0;
  int hold_ = 0;          // samples the last answer is still held back (EEPROM write)
  Word taken_ = 0;        // the master word the last channel step answered
  Word shown_ = 0x0000;   // the communication word on the bus
  Word held_answer_ = 0;  // an answer waiting for hold_ to run out
};

namespace vf1000 {
// The inverter its configuration describes (descriptor.hpp), started as `start` at `now`, with
// 906-IB-WD and 907-IBCOD as the settings give them.
std::unique_ptr<DeviceEmulator> make_emulator(const Configuration& config, DeviceStart start, Time now);
}  // namespace vf1000

}  // namespace ibs::devices
