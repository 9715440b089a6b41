// The MC6000 drive core: the servo itself, knowing no bus (docs/architecture.md, "One drive, many
// faces"). It owns the parameters (drive_parameters.hpp: the one store, 85-SERR, EEPROM, 4-PROG,
// 80-SLOAD), the DRIVECOM device machine with the servo plant (Mc6000PdDevice), the external
// fault, each error's programmed reaction and the fault reset (LUSTBUS manual 8, 8.1.2; MC-D7), the
// digital inputs and outputs (INTERBUS manual 5.3.1, 5.3.2), the bus watchdog 409-BUTWD (INTERBUS manual,
// 3.2.4: error 16 E-OP1 at location 1) and the serial watchdog 84-SWDGT (LUSTBUS manual 5.2), and the
// readings every face shows (77-SPEED, 408-IBSTA).
//
// Faces are thin: the INTERBUS face (device.hpp) decodes its SUPI/IBCNF words and runs PCP, the
// LUSTBUS face (lustbus_device.hpp) parses telegrams; both read and write through this object and
// tell it only "a valid cycle / telegram arrived at t". Who samples and who controls when both
// serve one core (docs/errata.md MC-D4): an INTERBUS face samples the drive every 1 ms; without
// one the drive samples itself up to the time of each telegram. 402-CLSEL = SIO puts control on
// the serial interface (416-SCTL1, 428-RSIO over 417..420) when a serial face serves the drive,
// any other location the fieldbus's control word and reference (LUSTBUS manual 7.2; INTERBUS manual 3.2.1:
// OPT1 for INTERBUS); a drive with the fieldbus face alone follows the fieldbus whatever 402 says.
//
// The cycle path (sample, advance, read, write) allocates nothing, throws nothing, reads no clock.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/devices/mc6000/drive_parameters.hpp"
#include "ibs/drive/parameter_journal.hpp"
#include "ibs/devices/plant_event.hpp"
#include "ibs/devices/mc6000/pd_device.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/interbus/device_start.hpp"

namespace ibs::devices::mc6000 {

// LUSTBUS manual 8: "The error reaction of the MasterControl servocontroller is programmable, in five
// steps, for every error"; 8.1.2 names step 5, RESET. What steps 1-4 do, and which parameter
// programs which error (510-REOP1, 511-RESIO, 512-REDEV), are decisions (docs/errata.md MC-D7).
enum class ErrorReaction : std::uint8_t {
  warn = 1,   // status word bit 7 "alarm" (INTERBUS manual 5.1.3) while it lasts; the drive runs on
  stop = 2,   // FAULT RESPONSE ACTIVE, braking to standstill, then FAULT (13, 14); the factory value
  off = 3,    // the power stage off at once: FAULT in the same sample, the motor coasts
  lock = 4,   // as off, and the fault reset does not end it: only a power-on does
  reset = 5,  // as off, and the fault reset boots the servo (8.1.2): power-on bit, ACK cut
};
// What a fault reset did.
enum class ResetOutcome : std::uint8_t {
  cleared,   // latched causes cleared; DRIVECOM's RESET FAULT edge in the next sample
  ignored,   // a reaction-4 error holds the servo: nothing happened
  rebooted,  // a reaction-5 error: the servo boots (NOT READY, 85-SERR = the power-on bit)
};

struct DriveConfig {
  DriveTiming timing{};
  Mc6000PdConfig pd{};  // plant and limits (the layout is the INTERBUS face's)
};

class Drive final : public DriveAccess {
 public:
  // The servo started as `start` at `now`: power_on (NOT READY first, 85-SERR power-on bit),
  // initialised (START-UP INHIBIT, power-on bit), operational (START-UP INHIBIT, 85-SERR read),
  // fault (FAULT).
  explicit Drive(const DriveConfig& config = {}, DeviceStart start = DeviceStart::operational, Time now = {});

  // Parameter access, the same for every face.
  void advance(Time now) override;
  std::optional<pcp::Value> read(Time now, std::uint16_t number) override;
  WriteResult write(Time now, std::uint16_t number, std::optional<std::uint32_t> raw) override;
  WriteResult refuse(Refusal r) override { return params_.refuse(r); }
  [[nodiscard]] const DriveParameters& parameters() const override { return params_; }
  [[nodiscard]] bool fault() const override;
  [[nodiscard]] DriveParameters& parameters() { return params_; }
  // The one parameter store (RAM and EEPROM) every face serves.
  [[nodiscard]] const pcp::ParameterStore& store() const { return params_.store(); }
  // 85-SERR's bits (LUSTBUS manual 9.2).
  [[nodiscard]] std::uint8_t siof() const { return params_.serr(); }
  // The changes the faces' channels made (parameter_journal.hpp): the PCP face and the LUSTBUS
  // face note theirs; a recording of the process-data words takes them.
  [[nodiscard]] drive::ParameterJournal& journal() { return journal_; }
  drive::ParameterJournal* changes() override { return &journal_; }

  // The fieldbus face. From the first call of set_fieldbus_sampling(true) the face's samples are
  // the drive's 1 ms samples (INTERBUS manual 7.2).
  void set_fieldbus_sampling(bool on) { fieldbus_sampling_ = on; }
  [[nodiscard]] bool fieldbus_sampling() const { return fieldbus_sampling_; }
  // A valid data cycle reached the servo: "the watchdog is triggered with every INTERBUS cycle".
  void fieldbus_cycle(Time now);
  // `count` samples at first, first + period, ... with the fieldbus's control word and reference
  // (used while the control location is the fieldbus).
  void sample(Time first, Duration period, std::uint32_t count, Word control, double reference_rpm);

  // A sample in which the fieldbus face has no process data for the drive (SUPI 0, a layout of
  // PCP words only: INTERBUS manual 3.2.2): the watchdogs are looked at, DRIVECOM does not move.
  void watch(Time now);

  // The serial face: it serves the drive (from then on 402-CLSEL = SIO gives it the control),
  // a valid telegram (5.2: resets the watchdog), a wrong BCC (9.2 bit 3).
  void set_serial_face(bool on) { serial_face_ = on; }
  void serial_telegram(Time now);
  void serial_checksum_error() { params_.set_serr(drive::SiofBit::checksum); }

  // Fault reset (LUSTBUS manual 8.1.2: 416-SCTL1 bit 7; INTERBUS manual 5.1.2: control word bit 7; each
  // from the interface that has the control location, which the faces ask first): latched
  // fault causes whose condition is gone are cleared (the serial watchdog's time starts again),
  // and the DRIVECOM machine gets its RESET FAULT edge in the next sample, whichever interface
  // has the control location.
  // With the errors' programmed reactions (ErrorReaction): a reaction-4 error ignores the reset,
  // a reaction-5 error in FAULT makes it a boot (8.1.2).
  ResetOutcome fault_reset(Time now);
  // A device fault present or gone; `cause` the error number it shows (nullopt: a generic
  // external fault, no number).
  void set_external_fault(bool present, std::optional<int> cause = std::nullopt) {
    external_fault_ = present;
    fault_cause_ = present ? cause : std::nullopt;
  }
  [[nodiscard]] std::optional<int> fault_cause() const { return fault_cause_; }
  // A load torque in Nm on the shaft, positive opposing positive speed (plant.hpp).
  void set_load_torque(double nm) {
    load_nm_ = nm;
    pd_.set_load_torque(nm);
  }
  [[nodiscard]] double load_torque() const { return load_nm_; }
  // Switched off and on.
  void power_on(Time now);
  // Mains lost: the servo is switched off (docs/errata.md MC-D6: the seeds name no undervoltage
  // error; LUSTBUS manual 9.2 names a power failure as a new start): it neither samples nor answers
  // until the mains return, which is a power-on.
  void mains_off(Time now);
  void mains_on(Time now);
  [[nodiscard]] bool powered() const { return powered_; }
  // Counts the boots a reaction-5 reset caused: the INTERBUS card boots with the servo (PCP).
  [[nodiscard]] std::uint32_t reboots() const { return reboots_; }
  // LUSTBUS manual 8.1.2: "the connection ... is broken for the duration of the boot-up" after a
  // reaction-5 reset: the serial interface hears nothing until the self-test is done.
  [[nodiscard]] bool booting(Time now) const { return now < boot_until_; }
  // The reaction the parameters program for the errors present now, the most severe of them
  // (nullopt: none present), and the one the servo holds to since the last reset or power-on.
  [[nodiscard]] std::optional<ErrorReaction> present_reaction() const;
  [[nodiscard]] std::optional<ErrorReaction> held_reaction() const { return held_; }
  // The digital outputs OS00 (0) and OS01 (1): INTERBUS manual 5.3.1, control word bits 14 and 15
  // "control the reference state of output OS00/OS01 directly" when 445-FOS00 / 446-FOS01 =
  // ROPT1 -- the option's (INTERBUS's) control word, whichever interface has the control location.
  [[nodiscard]] bool digital_output(std::size_t output) const;
  // The digital inputs IS00 (0) and IS01 (1): INTERBUS manual 5.3.2, status word bits 14 and 15
  // reflect them when 439-FIS00 / 440-FIS01 = ROPT1; the seeds give them no other effect.
  void set_input(std::size_t input, bool high);
  [[nodiscard]] bool input(std::size_t input) const { return input < 2 && inputs_[input]; }
  // A SMARTCARD read into the servo or written from it for `how_long` from `now` (LUSTBUS manual 10
  // exception 2: "no communications with the device via the LUSTBUS", "up to 10 seconds";
  // docs/errata.md MC-D9): meanwhile the serial interface hears nothing and the INTERBUS face
  // takes no words (a module error); the servo runs on as last commanded and keeps its values;
  // the silence it makes itself is counted by neither watchdog. A power-on or the mains' loss
  // ends it.
  void smartcard(Duration how_long, Time now);
  [[nodiscard]] bool card_busy(Time now) const { return now < card_until_; }
  // The INTERBUS card (INTERBUS manual 3.2.1): "detects the INTERBUS card automatically on power-on";
  // the first power-on that finds it sets 3.2.1's values, the first one after its withdrawal the
  // factory defaults (kOptionDefaults, RAM and EEPROM; MC-D10). It serves from the power-on that
  // detected it until it is pulled out.
  void withdraw_interbus_card() { card_fitted_ = false; }
  void insert_interbus_card() { card_fitted_ = true; }
  [[nodiscard]] bool interbus_card_fitted() const { return card_fitted_; }
  [[nodiscard]] bool interbus_card_serving() const { return card_fitted_ && card_detected_; }
  // A plant or fault event (plant_event.hpp) by the calls above (power_cycle: power_on).
  bool apply(const PlantEvent& e, Time now);

  // Readings.
  [[nodiscard]] drivecom::State state() const { return pd_.state(); }
  [[nodiscard]] bool running() const { return pd_.state() == drivecom::State::enabled; }
  [[nodiscard]] double actual_rpm() const { return pd_.actual_rpm(); }
  [[nodiscard]] double reference_rpm() const { return pd_.reference_rpm(); }
  [[nodiscard]] double torque_nm() const { return pd_.torque_nm(); }
  [[nodiscard]] double torque_percent() const { return pd_.torque_percent(); }
  // DRIVECOM's status word with the inputs' bits 14 and 15 (INTERBUS manual 5.3.2).
  [[nodiscard]] Word status_word() const;
  [[nodiscard]] const drivecom::SampleResult& last_sample() const { return pd_.last_sample(); }
  // The speed reference of the serial control location: 428-RSIO once per selector 417..420 that
  // says RSIO (7.2.1); RCON and the option give 0 here.
  [[nodiscard]] double serial_reference_rpm() const;
  [[nodiscard]] bool serial_control() const;
  [[nodiscard]] bool bus_watchdog_fault() const { return bus_fault_; }
  [[nodiscard]] bool serial_watchdog_fault() const { return serial_fault_; }
  [[nodiscard]] std::uint32_t recalculations() const { return params_.plrdy_requests(); }
  // INTERBUS manual 4.2: the servo's READY mode, which 15-PLRDY reads; out of it ENABLE stops in ON
  // (DriveParameters::ready_mode, MC-D11).
  [[nodiscard]] bool ready_mode() const { return params_.ready_mode(); }

 private:
  void sample_one(Time now, Word control, double reference_rpm);
  // The reaction programmed for each present error, into the DRIVECOM machine (ErrorReaction).
  void apply_reactions();
  [[nodiscard]] ErrorReaction reaction_of(std::uint16_t number) const;
  // The fieldbus's control word as DRIVECOM gets it: RESET FAULT masked while a reaction-4 error
  // holds the servo.
  [[nodiscard]] Word fieldbus_word(Word control) const;
  void reboot(Time now);
  void clear_bus_fault(bool expired);
  // The reaction of each error present now (nullopt where it is not): the device fault, the bus
  // watchdog while it has run out, the serial watchdog until its reset.
  [[nodiscard]] std::array<std::optional<ErrorReaction>, 3> present_errors() const;
  void serial_samples(std::uint32_t count, Duration dt);
  void check_serial_watchdog(Time now);
  [[nodiscard]] Word serial_word() const;
  [[nodiscard]] Duration bus_watchdog() const;
  void refresh_readings();
  // The time a watchdog counts its silence from: the last cycle or telegram, or the end of a
  // SMARTCARD operation after it (now while one runs).
  [[nodiscard]] Time quiet_since(Time last, Time now) const { return std::max(last, std::min(card_until_, now)); }
  // 3.2.1: the card found or missed at power-on.
  void detect_interbus_card();
  void set_option_defaults(bool with_card);

  DriveParameters params_;
  drive::ParameterJournal journal_;
  Mc6000PdDevice pd_;
  bool fieldbus_sampling_ = false;
  bool serial_face_ = false;
  bool armed_ = false;
  Time last_cycle_{};
  bool bus_fault_ = false;
  bool bus_expired_ = false;  // 409-BUTWD has run out and no cycle came since
  Time last_telegram_{};
  bool serial_fault_ = false;
  bool external_fault_ = false;
  std::optional<int> fault_cause_;
  double load_nm_ = 0.0;
  bool powered_ = true;
  bool inputs_[2] = {false, false};
  bool reset_pending_ = false;
  Time sampled_until_{};
  std::optional<ErrorReaction> held_;
  std::uint32_t reboots_ = 0;
  Duration boot_time_{};
  Time boot_until_{};
  Word fieldbus_control_ = 0;  // the last control word of the fieldbus (outputs, 5.3.1)
  Time card_until_ = Time::min();  // the SMARTCARD operation ends
  bool card_fitted_ = true;        // the INTERBUS card is in the slot ...
  bool card_detected_ = true;      // ... and was there at the last power-on
};

}  // namespace ibs::devices::mc6000
