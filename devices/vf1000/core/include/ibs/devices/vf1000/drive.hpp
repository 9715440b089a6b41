// The SMARTDRIVE VF1000 itself, on no bus (../shared/design.md, "One drive, many faces"): the one
// parameter store (RAM and EEPROM) with the drive's write rules, 71-PROG and the time storing
// takes; 85-SIOF with its power-on bit; the process-data model (DRIVECOM and ramp, pd_device.hpp);
// the external fault; power-on, the software reset and its self-test; both of the drive's
// monitors, the INTERBUS watchdog 906/907 and the serial watchdog 84-SIOT; the mirrored and
// actual values (901, 905, 911, 912, 11-STAT, 12). Its faces -- the INTERBUS communication word
// (device.hpp) and LUSTBUS (lustbus_device.hpp) -- keep only protocol state and call it; several
// faces may serve one drive at once. Everything after construction is on the cycle path: no
// allocation, no exception, time passed in.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/drive/parameter_journal.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/devices/plant_event.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/devices/vf1000/pd_device.hpp"
#include "ibs/drive/parameter_access.hpp"
#include "ibs/interbus/device_start.hpp"

namespace ibs::devices::vf1000 {

// How long storing takes: the drive's time, which each face expresses in its own units (the
// INTERBUS face in extra 8.2 ms samples before its ACK, the LUSTBUS face in reaction time).
struct StoringTimes {
  // LUSTBUS manual 10 exception 4: a changed EEPROM value adds about 120 ms (two bytes) or 60 ms (one
  // byte); INTERBUS manual 7.1 agrees for the two-byte case: 250 ms instead of 124 (erratum VF-E12).
  Duration eeprom_two_bytes = std::chrono::milliseconds(120);
  Duration eeprom_one_byte = std::chrono::milliseconds(60);
  // LUSTBUS manual 10 exception 1: 71-PROG = 1 answers once every parameter is initialised, "up to 10
  // seconds"; 1.5 s here (LB-D18), over either bus (VF-E11).
  Duration factory_defaults = std::chrono::milliseconds(1500);
};

struct DriveConfig {
  // Ramp, stop ramp, 6.1's initialisation time after power-on and the self-test after a software
  // reset (reset_time, D13).
  Vf1000PdConfig pd{};
  StoringTimes storing{};
  // The inverter's software: the INTERBUS package, whose factory values are INTERBUS manual 3.1.1's
  // (1-MODE 4, 2-CSEL 5, 4-FSSEL 25), or the standard one of a drive on LUSTBUS alone (LUSTBUS manual,
  // 4.1; standalone_parameters(), VF-E20).
  bool interbus_software = true;
};

// The faces a drive can be reached through.
enum class Face : std::uint8_t { interbus, serial };

// 11-STAT as read (LB-D19, chosen): 01H ready, 02H power stage on, 04H counter-clockwise, 80H
// error; 8.1.1: the VALUE 000FH written resets a fault.
inline constexpr Word kStatReady = 0x01;
inline constexpr Word kStatRunning = 0x02;
inline constexpr Word kStatCounterClockwise = 0x04;
inline constexpr Word kStatError = 0x80;
inline constexpr Word kStatReset = 0x000F;
// LUSTBUS manual 4: "from 2400 Baud to 9600 Baud for frequency Inverters" (81-SIOC, in baud: LB-E18).
inline constexpr std::uint32_t kHighestBaud = 9600;

class Drive final : public drive::ParameterAccess {
 public:
  // Allocates (the store). `start` as the emulators take it: power_on (initialising for the
  // init time, power-on bit), initialised (ready, power-on bit still set), operational (85-SIOF
  // read), fault (operational, in FAULT).
  Drive(const DriveConfig& config, DeviceStart start, Time now);
  // A copy is an independent drive with the same state and no faces (a face that is copied
  // attaches itself to its copy).
  Drive(const Drive& other) = default;
  Drive& operator=(const Drive&) = delete;
  ~Drive() override = default;

  // --- The parameters (drive::ParameterAccess: what every face serves) ------------------------
  [[nodiscard]] const drive::ParameterTable& table() const override { return params_.table(); }
  // 11-STAT and 12 are formed from the drive's state when read (LUSTBUS manual 8.1.1, 6.1.1.1); every
  // other value comes from the store.
  [[nodiscard]] Word read(std::size_t slot) const override;
  [[nodiscard]] std::uint8_t siof() const override { return params_.siof(); }
  void raise_siof(std::uint8_t bits) override {
    unsettle();
    params_.raise_siof(bits);
  }
  void clear_siof(std::uint8_t bits) override {
    unsettle();
    params_.clear_siof(bits);
  }
  // drive::check_write, and 11-STAT takes only 000FH (8.1.1; anything else is 80H, LB-D19).
  [[nodiscard]] drive::WriteCheck check_write(const drive::ParameterInfo* p, Word raw,
                                              bool power_stage_enabled) const override;
  // A checked value takes effect: into RAM/EEPROM (4.1.3.3), 71-PROG = 1 loads the factory
  // defaults (10 exception 1), 11-STAT = 000FH resets a fault (8.1.1), 84-SIOT restarts the
  // serial watchdog; the effect says how long storing takes.
  drive::WriteEffect write(std::size_t slot, Word raw, bool power_stage_enabled, Time now) override;
  void set(std::size_t slot, Word raw) override {
    unsettle();
    params_.set(slot, raw);
  }

  // The one store, for the faces and tests (its address is the same through every face).
  [[nodiscard]] const drive::ParameterStore& store() const { return params_.store(); }
  // The changes the faces' channels made (parameter_journal.hpp): the LUSTBUS face notes its own;
  // the communication word's are in the INTERBUS words themselves.
  [[nodiscard]] drive::ParameterJournal& journal() { return journal_; }
  [[nodiscard]] const drive::ParameterInfo* find(std::uint16_t number) const {
    return params_.table().find(number);
  }
  // By number, the store's RAM value (value()) and as a read returns it (reading(): 11-STAT and
  // 12 formed now); 0 for a number the table lacks.
  [[nodiscard]] Word value(std::uint16_t number) const;
  [[nodiscard]] Word reading(std::uint16_t number) const;
  [[nodiscard]] Word eeprom_value(std::uint16_t number) const;
  bool set_value(std::uint16_t number, Word raw) {
    unsettle();
    return params_.set_value(number, raw);
  }
  // A read of 85-SIOF: the bits, which the read erases (LUSTBUS manual 9.2; INTERBUS manual 4.1.4).
  std::uint8_t read_siof();

  // --- Faces ----------------------------------------------------------------------------------
  void attach(Face f);
  void detach(Face f);
  [[nodiscard]] bool attached(Face f) const {
    return (f == Face::interbus ? faces_.interbus : faces_.serial) > 0;
  }
  // LUSTBUS manual 7.1: with 1-MODE = 0 and 2-CSEL = 3 the serial interface controls (3-CNTL, and
  // 5-FSSIO with 4-FSSEL = 8); it can only where a serial face is attached. Otherwise the
  // INTERBUS words control (INTERBUS manual 6.1: INTERBUS operation).
  [[nodiscard]] bool serial_has_control() const;
  // INTERBUS manual 6.1: during operation on the INTERBUS (an INTERBUS face attached and 1-MODE = 4, the
  // factory value) the serial interface cannot be used: the LUSTBUS face hears nothing (VF-E16).
  [[nodiscard]] bool serial_locked() const;

  // --- Time -----------------------------------------------------------------------------------
  // Time passes (a face calls it before it acts). While an INTERBUS face is attached its samples
  // are the drive's (sample() below); otherwise the drive runs its own 8.2 ms samples up to
  // `now` with the serial interface's inputs. Either way: the end of a self-test, the serial
  // watchdog. A second call at the time the drive was last advanced to, with nothing changed
  // since, has nothing to do and returns at once (every other mutator below unsettles the drive;
  // serial_telegram() at that time keeps it settled, see drive.cpp).
  void advance(Time now);
  // advance() without that shortcut: the general path, which the comparison test
  // (Vf1000DriveShortcuts.*) runs against it.
  void advance_fully(Time now);
  // A valid INTERBUS data cycle reached the drive at `now` (906-IB-WD is fed by every one).
  void interbus_cycle(Time now);
  // A valid LUSTBUS telegram reached the drive at `now` (84-SIOT is fed by every one, 5.2).
  void serial_telegram(Time now);
  // The INTERBUS face's sample, in two halves around its channel step: first the monitors and
  // the fault input, then one 8.2 ms sample of the process data with the master's words (or the
  // serial inputs when the serial interface controls), `comm` as word 3 of the answer.
  void begin_sample(Time now);
  void sample(std::span<const Word> m2s, std::span<Word> s2m, Time now, std::optional<Word> comm);
  // The words the drive shows now.
  void output(std::span<Word> s2m) const { pd_.output(s2m); }

  // --- Events ---------------------------------------------------------------------------------
  // Switched off and on: initialising for the init time, EEPROM values back, power-on bit.
  void power_cycle(Time now);
  // A new start without the initialisation time (the LUSTBUS face's restart).
  void restart(Time now);
  // A device fault (e.g. overcurrent) present or gone; `cause` the error number (00H..0EH, seed
  // 001 4.1.3.3) it shows, nullopt for a generic external fault.
  void set_fault(bool present, Time now, std::optional<int> cause = std::nullopt);
  [[nodiscard]] std::optional<int> fault_cause() const { return fault_cause_; }
  // Mains lost: the inverter is switched off (docs/errata.md VF-E17: the seeds name no
  // undervoltage error; LUSTBUS manual 9.2 names a power failure as a new start): a module error on
  // INTERBUS, no answer on LUSTBUS, until the mains return, which is a power-on (6.1's
  // initialisation, the power-on bit).
  void mains_off(Time now);
  void mains_on(Time now);
  [[nodiscard]] bool powered() const { return powered_; }
  // A SMARTCARD read or written for `how_long` from `now`: meanwhile bus operation is disabled
  // (INTERBUS manual 6.1: a module error on INTERBUS, no words taken; LUSTBUS manual 10 exception 2: no
  // LUSTBUS communication), decision VF-E21.
  void smartcard(Duration how_long, Time now);
  [[nodiscard]] bool card_busy(Time now) const { return now < card_until_; }
  // A terminal's level (docs/errata.md VF-E22). An input (S1IND, S2IND, STR, STL) is wired high
  // or low; an output (S1OUT, S2OUT) is set to the level its programmed function gives -- INTERBUS manual
  // 5.2.2: "status of output S2OUT / S1OUT, dependent on programmed function", a function no seed
  // gives, so the event states the level. The outputs show in status word bits 14 (S2OUT) and 15
  // (S1OUT) from the next sample, on INTERBUS and in 911-IBSTA (which LUSTBUS, reaching parameters
  // 00..99 only, cannot read: LUSTBUS manual 2.4.1).
  void set_terminal(vf1000::Terminal t, bool high);
  // The level recorded for the terminal; an output is low while the inverter has no mains.
  [[nodiscard]] bool terminal(vf1000::Terminal t) const;
  // INTERBUS manual 5.2.1: control word bit 12 / 13 "activates the parameter-set function of input
  // S2IND / S1IND". Active while the inverter is powered and the terminal is high or the bit is
  // set in the control word of the last sample (the INTERBUS master's; the serial interface's
  // sets neither: the bus stands in for the terminal, as bits 14 / 15 do for STL / STR); false for
  // the other terminals. What the function does the seeds do
  // not give: nothing else follows from it (VF-E22).
  [[nodiscard]] bool input_function_active(vf1000::Terminal input) const;
  // A plant or fault event (plant_event.hpp) by the calls above (an input: set_terminal by the
  // index of kTerminalNames); false for one the inverter does not take (a load: DriveFacts::events
  // says why).
  bool apply(const PlantEvent& e, Time now);

  // --- State ----------------------------------------------------------------------------------
  // Counts every new start (power cycle, restart, software reset): a face that sees it change
  // drops its unfinished telegram.
  [[nodiscard]] std::uint32_t starts() const { return starts_; }
  // How many times a fault reset made the inverter perform its software reset (5.2.1, 8.1.1).
  [[nodiscard]] std::uint32_t software_resets() const { return software_resets_; }
  // Initialising or in the self-test: the bus shows a module error (6.1), LUSTBUS is deaf (8.1.1).
  [[nodiscard]] bool initialising(Time now) const { return now < ready_at_; }
  [[nodiscard]] Time ready_at() const { return ready_at_; }
  // In a start whose end advance()/begin_sample() has not yet seen.
  [[nodiscard]] bool starting() const { return starting_; }
  [[nodiscard]] const Vf1000PdDevice& pd() const { return pd_; }
  [[nodiscard]] drivecom::State state() const { return pd_.state(); }
  [[nodiscard]] double frequency_hz() const { return pd_.frequency_hz(); }
  // The power stage runs (11-STAT 02H; EEPROM values refused, LUSTBUS manual 3): DRIVECOM's power stage
  // states, but not while the motor is shut down at a reference of 0 Hz (INTERBUS manual 5.2.3).
  [[nodiscard]] bool power_stage_enabled() const { return pd_.power_stage_on(); }
  [[nodiscard]] Word status() const;  // 11-STAT
  [[nodiscard]] bool external_fault() const { return external_fault_; }
  // 906/907: the INTERBUS watchdog ran out (and has not seen data since); E-IBS latched.
  [[nodiscard]] bool interbus_watchdog_tripped() const { return ib_tripped_; }
  [[nodiscard]] bool e_ibs() const { return ib_fault_; }
  // 84-SIOT ran out (5.2): the error state until a software reset.
  [[nodiscard]] bool serial_watchdog_fault() const { return serial_fault_; }
  [[nodiscard]] const DriveConfig& config() const { return config_; }

 private:
  void software_reset(Word control, Time now);
  void new_start(Time now, Duration init);
  void finish_start(Time now);
  void run_interbus_watchdog(Time now);
  bool check_serial_watchdog(Time now);
  void apply_parameters();
  void mirror(Word control, Word actual);
  [[nodiscard]] Word serial_control_word() const;
  [[nodiscard]] Word serial_reference() const;
  void own_sample(Duration dt, Time now);
  void after_sample(Word control, Word actual, Time now);
  void sample_now(Time now);
  [[nodiscard]] Duration storing_time(const drive::ParameterInfo& p, bool eeprom_changed,
                                      bool defaults) const;

  // The store's slots of the parameters every sample reads or mirrors, found once with the table
  // (-1: the table lacks it), so that a sample looks none up by number.
  struct SampleSlots {
    int ib_wd = -1;
    int ibcod = -1;
    int icntl = -1;
    int ibsta = -1;
    int fdriv = -1;
    int fist = -1;
  };
  [[nodiscard]] Word slot_value(int slot, Word absent) const {
    return slot < 0 ? absent : params_.store().value(static_cast<std::size_t>(slot));
  }
  void set_slot(int slot, Word raw) {
    if (slot >= 0) params_.set(static_cast<std::size_t>(slot), raw);
  }

  DriveConfig config_;
  drive::StoredParameters params_;
  drive::ParameterJournal journal_;
  SampleSlots slots_;
  Vf1000PdDevice pd_;
  Time ready_at_{0};
  bool starting_ = false;
  std::uint32_t starts_ = 0;
  std::uint32_t software_resets_ = 0;
  bool external_fault_ = false;
  std::optional<int> fault_cause_;
  bool powered_ = true;
  Time card_until_{0};  // the SMARTCARD operation ends
  // 906/907.
  bool ib_armed_ = false;
  Time ib_last_cycle_{0};
  bool ib_tripped_ = false;
  bool ib_fault_ = false;
  // 84-SIOT.
  Time serial_last_{0};
  bool serial_fault_ = false;
  // The drive's own sampling, while no INTERBUS face samples it.
  Time sample_time_{0};
  Word last_control_ = 0;  // the control word of the last sample
  // Control bits 12 / 13 (S2IND / S1IND) of the last sample since the last new start.
  Word input_bits_ = 0;
  // The terminals' levels, by vf1000::Terminal.
  std::array<bool, vf1000::kTerminalCount> terminals_{};
  // advance() ran to `to` and no mutator has run since (`on`). Not copied: a copy, which has no
  // faces, advances on its own.
  struct Settled {
    bool on = false;
    Time to{};
    Settled() = default;
    Settled(const Settled&) {}
    Settled& operator=(const Settled&) { return *this; }
  };
  void unsettle() { settled_.on = false; }
  Settled settled_;
  // The faces attached; a copy of the drive has none.
  struct Faces {
    int interbus = 0;
    int serial = 0;
    Faces() = default;
    Faces(const Faces&) {}
    Faces& operator=(const Faces&) { return *this; }
  };
  Faces faces_;
};

}  // namespace ibs::devices::vf1000
