// A drive's CANLust face (CANLust manual) as the registry of drive and bus lists it
// (ibs/devices/drives.hpp): the emulated drive `ibs canlust emulate` serves and `ibs run` puts on
// its virtual bus, the master-side driver the simulator runs them with, and the drive's parameter
// table as scenarios and reports name its entries. Each wing that speaks CANLust fills one of
// these in its own source (devices/<drive>/src/bus_face.cpp); this header names no drive.
//
// Configuration time (making a drive or a master, looking a parameter up, parsing and formatting
// a value) may allocate and throw. The frame path does not: CanlustDrive's receive, step,
// take_frame and next_deadline and CanlustMaster's receive, cycle, take_frame, next_deadline and
// take_error allocate nothing, throw nothing and read no clock (time is passed in) -- one virtual
// call per frame is their only cost over the wing's own types.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/canlust/data_set.hpp"
#include "ibs/canlust/data_types.hpp"
#include "ibs/canlust/errors.hpp"
#include "ibs/canlust/frame.hpp"
#include "ibs/canlust/identifiers.hpp"
#include "ibs/canlust/master.hpp"
#include "ibs/canlust/node.hpp"
#include "ibs/canlust/parameter_client.hpp"
#include "ibs/canlust/telegrams.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/drivecom/sequencer.hpp"

namespace ibs::devices {

// What `ibs canlust emulate` and a scenario's [[device]] give one emulated drive.
struct CanlustFaceOptions {
  canlust::IdentifierMap ids{};
  // The reaction programmed for the bus watchdog (CANLust manual 6.1): the drive's stored setting of its
  // response parameter (CDA3000: 525-ROP2), as a commissioning tool would have saved it.
  canlust::ErrorReaction watchdog_reaction = canlust::ErrorReaction::disable_power;
  // true: an uncommissioned drive at the connector's address (CANLust manual 2.1: 0..7); false: a
  // drive commissioned for the bus (7.1.2) at `address` with the telegram layout `cacnf`.
  bool factory = false;
  std::uint8_t address = 1;
  std::uint8_t cacnf = 2;
  // A commissioned drive's stored bus settings beyond the commissioning; nullopt: the drive's own.
  std::optional<std::uint32_t> bitrate;      // bit/s
  std::optional<std::uint16_t> watchdog_ms;  // the bus watchdog, 0 = off
  std::optional<std::uint16_t> status_ms;    // the cyclic status telegram's period
};

// A plant or fault event for an emulated drive (issue 24, the test bench): from a scenario's
// timeline or a live control channel. What each event does is the drive's (its wing cites its
// manual); the simulator and the command line name no drive. Configuration time: it may allocate.
struct CanlustEvent {
  enum class Kind : std::uint8_t { fault, mains_off, mains_on, power_cycle, load, input };
  Kind kind = Kind::fault;
  std::string cause;   // fault: the drive's error as its manual writes it ("E-OTI") or its number ("8")
  double load = 0.0;   // load: the load torque in % of the motor's rated torque
  std::string input;   // input: the terminal as the manual names it ("ENPO")
  bool level = false;  // input: true = high
};
inline std::string_view to_string(CanlustEvent::Kind k) {
  switch (k) {
    case CanlustEvent::Kind::fault: return "fault";
    case CanlustEvent::Kind::mains_off: return "mains off";
    case CanlustEvent::Kind::mains_on: return "mains on";
    case CanlustEvent::Kind::power_cycle: return "power cycle";
    case CanlustEvent::Kind::load: return "load";
    case CanlustEvent::Kind::input: return "input";
  }
  return "?";
}

// What an event did ("E-OTI (drive unit overheating): FAULT, error telegram sent"), or why the
// drive refused it (ok false).
struct CanlustEventResult {
  bool ok = true;
  std::string text;
};

// An emulated drive on a CANLust bus. Mains off until power_on().
class CanlustDrive {
 public:
  virtual ~CanlustDrive() = default;

  // Mains on, or a mains reset: the drive starts from its stored settings (a scenario's
  // fault = "mains_reset" / "mains_on"); power_off(): mains off.
  virtual void power_on(Time now) = 0;
  virtual void power_off() = 0;
  // Every frame from the bus; step(): what is due at `now` (cyclic telegrams, watchdog, delayed
  // replies, the plant); take_frame(): what the drive sends, one frame at a time.
  virtual void receive(const canlust::CanFrame& f, Time now) = 0;
  virtual void step(Time now) = 0;
  virtual std::optional<canlust::CanFrame> take_frame() = 0;
  // When step() next has something to do.
  [[nodiscard]] virtual Time next_deadline() const = 0;

  // ---- observation, for reports -------------------------------------------------------------
  [[nodiscard]] virtual canlust::Address address() const = 0;
  [[nodiscard]] virtual canlust::SystemState system_state() const = 0;
  [[nodiscard]] virtual drivecom::State state() const = 0;
  [[nodiscard]] virtual double actual_hz(Time now) const = 0;
  [[nodiscard]] virtual double reference_hz() const = 0;
  [[nodiscard]] virtual std::uint32_t watchdog_trips() const = 0;
  // A parameter's setting as the bus reads it (the wire image); nullopt for numbers it lacks.
  [[nodiscard]] virtual std::optional<std::uint32_t> value(std::uint16_t number) const = 0;

  // ---- plant and fault events (issue 24) ------------------------------------------------------
  // Applies `e` at `now`: a device fault with its cause, mains off / on, a power cycle, the load
  // torque, a digital input. Not the frame path (it may allocate for its text).
  virtual CanlustEventResult apply(const CanlustEvent& e, Time now) = 0;
};

// A parameter of the drive's table as a scenario names it.
struct CanlustParameter {
  std::uint16_t number = 0;
  std::string name;  // as reports show it: "574-CAWDG"
  bool writable = true;
  bool is_string = false;  // read and written as text
  canlust::DataType type = canlust::DataType::usign32;  // how the wire image codes the value
  bool in_data_set = false;  // a data set download may hold it ("Card Writeable")
};

struct CanlustValue {
  std::optional<std::uint32_t> wire;
  std::string error;  // why `wire` is nullopt: "574-CAWDG: 300 ms is above the maximum 255 ms"
};

// A parameter's description as the drive answers it item by item (mode 04; CANLust manual leaves the
// items to the drive, decision D10), read back by `ibs canlust describe`.
struct CanlustDescription {
  canlust::DataType type = canlust::DataType::usign32;
  std::uint32_t min = 0;  // on the wire, as `type` codes them
  std::uint32_t max = 0;
  std::uint32_t factory = 0;
  bool writable = false;
  bool flash = false;              // kept in flash (else RAM)
  bool after_mains_reset = false;  // a write acts after a mains reset
  std::string short_name;
  std::string unit;
};

// A frame in words, for the monitor and `ibs decode`: its kind and drive (nullopt: not a CANLust
// identifier on this map) and the words and values with what they mean.
struct CanlustFrameText {
  std::optional<canlust::Classified> id;
  std::string text;
};

// One drive the master drives.
struct CanlustMasterDrive {
  canlust::Address address = 0;
  std::uint8_t cacnf = 2;           // its telegram layout (1..3 DRIVECOM, 4 EasyDrive)
  double max_reference_hz = 400.0;  // references beyond +-this are refused
};

struct CanlustMasterOptions {
  canlust::IdentifierMap ids{};
  std::vector<CanlustMasterDrive> drives;
  Duration control_period = 50ms;  // control telegrams at least this often in System Start
  Duration status_period = 80ms;   // the drives' (slowest) cyclic status period
};

// A parameter request of the master: submitted (id) or refused before anything was sent (error).
struct CanlustSubmission {
  canlust::RequestId id = 0;
  std::string error;  // "574-CAWDG: 300 ms is above the maximum 255 ms"
  explicit operator bool() const { return error.empty(); }
};

// The master side of a bus of these drives: the logon list, System Start / Stop, the DRIVECOM
// sequencers (or EasyDrive bits), references in Hz and the parameter channel.
class CanlustMaster {
 public:
  virtual ~CanlustMaster() = default;

  virtual void receive(const canlust::CanFrame& f, Time now) = 0;
  // One master cycle.
  virtual void cycle(Time now) = 0;
  virtual std::optional<canlust::CanFrame> take_frame() = 0;
  [[nodiscard]] virtual Time next_deadline() const = 0;
  // The error telegrams the drives sent, one at a time.
  virtual std::optional<canlust::ErrorEvent> take_error() = 0;

  virtual void system_start(Time now) = 0;
  virtual void system_stop(Time now) = 0;
  // false: `a` is not a drive the master runs with DRIVECOM.
  virtual bool request(canlust::Address a, drivecom::Target t, Time now) = 0;
  // false: `a` is not a drive the master runs with EasyDrive bits.
  virtual bool set_easydrive(canlust::Address a, Word bits) = 0;
  // nullopt: set, sent with the next control telegram; else why it was refused.
  virtual std::optional<std::string_view> set_reference_hz(canlust::Address a, double hz) = 0;

  // A parameter's value (a STRING as text); write() takes the value as the user gives it
  // ("OPTN2", "20.5", a text) and parses it with the drive's table.
  virtual CanlustSubmission read(canlust::Address a, std::uint16_t number) = 0;
  virtual CanlustSubmission write(canlust::Address a, std::uint16_t number, std::string_view value) = 0;
  [[nodiscard]] virtual canlust::Poll poll(canlust::RequestId id) const = 0;

  // The drive's last status telegram explained; nullopt when none was received.
  [[nodiscard]] virtual std::optional<std::string> status_text(canlust::Address a) const = 0;
};

struct CanlustFace {
  // The drive as the manual names it: "CDA3000".
  std::string_view title;
  // Throws std::invalid_argument for a configuration the drive refuses.
  std::unique_ptr<CanlustDrive> (*make)(const CanlustFaceOptions& options) = nullptr;
  // Throws std::invalid_argument for a configuration the driver refuses.
  std::unique_ptr<CanlustMaster> (*make_master)(const CanlustMasterOptions& options) = nullptr;
  // By "574", "CAWDG" or "574-CAWDG" / by number; nullopt for none.
  std::optional<CanlustParameter> (*find_parameter)(std::string_view text) = nullptr;
  std::optional<CanlustParameter> (*parameter)(std::uint16_t number) = nullptr;
  // A value parameter's value from the user's text, and its wire image for reports ("20.50 Hz").
  CanlustValue (*parse_value)(std::uint16_t number, std::string_view text) = nullptr;
  std::string (*format_value)(std::uint16_t number, std::uint32_t wire) = nullptr;
  // Checks an event before a run applies it (a scenario's load, a control line): empty when the
  // drive takes it, else why not ("cause 'E-XYZ': the CDA3000's errors are 8 E-OTI, ...").
  std::string (*check_event)(const CanlustEvent& e) = nullptr;

  // ---- for the client commands (`ibs canlust read|write|describe|start|stop|monitor`, `ibs
  // decode`), which talk to a real or emulated drive over the bus --------------------------------
  // How reports name one drive of these on the bus: "CDA" in "CDA 3: ...".
  std::string_view short_title;
  // The number a value parameter's wire image stands for (sign-extended for the signed types;
  // INT32Q16 as the raw Q16), for JSON; the wire image itself for numbers not in the table.
  std::int64_t (*number_of)(std::uint16_t number, std::uint32_t wire) = nullptr;
  // How long a write of `number` may take before the drive answers; nullopt: the parameter
  // client's default. A drive that backs up or resets its settings on a write needs longer.
  std::optional<Duration> (*write_timeout)(std::uint16_t number) = nullptr;
  // The description the items of a mode-04 exchange say; nullopt when they are not this drive's.
  std::optional<CanlustDescription> (*read_description)(std::span<const std::uint32_t> items) = nullptr;
  // A DRIVECOM status word with the bits the drive adds, in words: "0237 ENABLED, remote".
  std::string (*explain_status_word)(Word status) = nullptr;
  // The frequency in Hz of a status or control telegram's value as the telegram layout codes it.
  double (*hz_from_wire)(canlust::ValueWidth width, std::int32_t raw) = nullptr;
  // A frame explained with the drive's parameter names and word meanings.
  CanlustFrameText (*explain_frame)(const canlust::CanFrame& f, const canlust::IdentifierMap& ids,
                                    const canlust::ProcessLayout& layout) = nullptr;
  // CANLust manual, "Downloading parameter data sets": the drive's handshake (`ibs canlust download`);
  // nullptr when the drive offers no download. Which parameters a set may hold:
  // CanlustParameter::in_data_set.
  const canlust::DownloadHandshake* download = nullptr;
};

}  // namespace ibs::devices
