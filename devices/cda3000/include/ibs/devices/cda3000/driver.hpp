// The master driver of CDA3000 drives on one CANLust bus (CANLust manual): the logon list (5.5.4),
// System Start / Stop (5.2), one DRIVECOM sequencer of drivecom/ per drive (5.4.2), references in
// Hz scaled as each drive's 492-CACNF lays them out, control telegrams often enough for the
// drives' 574-CAWDG, and the parameter client of the core (a queue, one request per drive at a
// time, a timeout per request) behind checks against the CDA3000 parameter table.
//
//   Driver d({.drives = {{.address = 1}, {.address = 2}}});
//   d.receive(frame, now);                 // every frame from the bus
//   d.cycle(now);                          // once per master cycle
//   while (auto f = d.take_frame()) bus.send(*f);
//   d.system_start(now); d.request(1, drivecom::Target::enabled, now); d.set_reference_hz(1, 20.5);
//
// The sequencers step in System Start only: in System Logon and Stop the drives store what they
// are sent (5.2), so the sequencers' clock stands still and their control words are sent as
// presets, executed by every drive at the next System Start (decision D30). Before the driver's
// own first Start or Stop it sends no control telegram at all.
//
// receive, cycle, take_frame and next_deadline allocate nothing, throw nothing and lock nothing
// (pinned by Cda3000DriverAlloc.CycleAllocatesNothing); the constructor allocates and throws
// std::invalid_argument for a bad configuration, naming the drive and the setting.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/canlust/master.hpp"
#include "ibs/devices/cda3000/parameters.hpp"
#include "ibs/drivecom/sequencer.hpp"
#include "ibs/base/time.hpp"

namespace ibs::devices::cda3000 {

struct DriveSettings {
  canlust::Address address = 0;
  std::uint8_t cacnf = 2;           // the drive's 492-CACNF: 1..3 DRIVECOM, 4 EasyDrive (set_easydrive)
  double max_reference_hz = 400.0;  // references beyond +-this are refused
};

struct DriverConfig {
  canlust::IdentifierMap ids{};
  std::vector<DriveSettings> drives;
  // Control telegrams go out when the word or the reference changes, and at least this often in
  // System Start, so that 574-CAWDG (up to 255 ms) sees them (decision D30). 100 drives at
  // 500 kbit/s: one control telegram each 50 ms is about 46 % bus load.
  Duration control_period = 50ms;
  // The drives' 575-CASCY: a transition shows at the next status telegram, so every transition
  // timeout is at least two status periods and a control period (plus 20 ms).
  Duration status_period = 80ms;
  drivecom::SequencerConfig sequencer = drivecom::SequencerConfig::defaults();
  canlust::ClientConfig client{};
  // A configured drive that logs on after System Start (it was switched on later, or had a mains
  // reset) is in System Logon until the next Start: broadcast Start again (decision D31). Logons
  // up to `late_logon_grace` after a Start may have been sent before the drive got it.
  bool restart_late_logons = true;
  Duration late_logon_grace = 20ms;
};

enum class SystemPhase : std::uint8_t { logon, started, stopped };
std::string_view to_string(SystemPhase p);

enum class ReferenceError : std::uint8_t { none, unknown_drive, not_finite, above_limit, does_not_fit };
std::string_view to_string(ReferenceError e);

// Why a parameter request was not submitted; the drive was asked nothing.
enum class ParameterError : std::uint8_t {
  none,
  unknown_drive,      // the address is not a configured drive
  unknown_parameter,  // not in the CDA3000 table (the raw client of parameters() can still ask)
  read_only,
  string_parameter,   // a STRING: read() reads it as text, write_text() writes it
  not_a_string,       // write_text() on a value parameter
  value,              // the value is refused by the table (value_check says why)
  text_too_long,      // more than 99 characters (4.1.1)
  queue_full,
};
std::string_view to_string(ParameterError e);

struct ParameterSubmission {
  canlust::RequestId id = 0;
  ParameterError error = ParameterError::none;
  ValueCheck value_check = ValueCheck::ok;
  explicit operator bool() const { return error == ParameterError::none; }
};
// "574-CAWDG: 300 ms is above the maximum 255 ms" (allocates: for reports).
std::string describe(const ParameterSubmission& s, std::uint16_t number, std::uint32_t value = 0);

// The driver's view of one drive.
struct DriveReport {
  canlust::Address address = 0;
  bool logged_on = false;
  bool has_status = false;
  ibs::Word status_word = 0;
  std::optional<drivecom::State> state;  // nullopt for an EasyDrive drive (its own bits)
  bool easydrive = false;
  double actual_hz = 0.0;
  double reference_hz = 0.0;
  drivecom::Report sequencer{};
  std::uint32_t errors = 0;  // error telegrams received
};

class Driver {
 public:
  explicit Driver(const DriverConfig& config);

  void receive(const canlust::CanFrame& f, Time now);
  // One master cycle: late logons, the sequencers on the drives' last status words, and the
  // control telegrams that are due.
  void cycle(Time now);
  bool take_frame(canlust::CanFrame& out) { return master_.take_frame(out); }
  std::optional<canlust::CanFrame> take_frame() { return master_.take_frame(); }
  // Time::min() when a frame waits or a status arrived since the last cycle.
  [[nodiscard]] Time next_deadline() const;

  // 5.5.4: the broadcasts (queued; sent by take_frame()).
  void system_start(Time now);
  void system_stop(Time now);
  [[nodiscard]] SystemPhase phase() const { return phase_; }
  // Addresses in the order of their first logon (configured or not).
  [[nodiscard]] std::span<const canlust::Address> logon_order() const { return master_.logon_order(); }
  [[nodiscard]] bool all_logged_on() const;

  // DRIVECOM: false when `a` is not a configured DRIVECOM drive.
  bool request(canlust::Address a, drivecom::Target t, Time now);
  // EasyDrive (492-CACNF = 4, descriptor.hpp `easydrive`): the direct-control bits sent from now
  // on, as given - the driver adds nothing (no start, no reset of its own). False when `a` is not
  // an EasyDrive drive.
  bool set_easydrive(canlust::Address a, ibs::Word bits);
  bool emergency_stop(canlust::Address a, Time now);
  bool block_power(canlust::Address a, Time now);
  // The reference in Hz, sent with the next control telegram; checked against max_reference_hz
  // and the drive's layout (Int16Q0: whole Hz).
  ReferenceError set_reference_hz(canlust::Address a, double hz);

  [[nodiscard]] bool configured(canlust::Address a) const;
  [[nodiscard]] DriveReport drive(canlust::Address a) const;
  [[nodiscard]] const drivecom::Report* sequencer_report(canlust::Address a) const;
  [[nodiscard]] std::span<const DriveSettings> drives() const { return settings_; }

  // Parameters, checked against the CDA3000 table before anything is sent: read() of a STRING
  // reads the text (mode 11), write() takes the wire image of a value (parse_value() makes one).
  ParameterSubmission read(canlust::Address a, std::uint16_t number);
  ParameterSubmission write(canlust::Address a, std::uint16_t number, std::uint32_t value);
  ParameterSubmission write_text(canlust::Address a, std::uint16_t number, std::string_view text);
  ParameterSubmission describe(canlust::Address a, std::uint16_t number, std::uint8_t item);
  canlust::ParameterClient& parameters() { return master_.parameters(); }
  [[nodiscard]] const canlust::ParameterClient& parameters() const { return master_.parameters(); }

  std::optional<canlust::ErrorEvent> take_error() { return master_.take_error(); }
  canlust::Master& master() { return master_; }
  [[nodiscard]] const canlust::Master& master() const { return master_; }

 private:
  struct Slot {
    canlust::Address address = 0;
    canlust::ProcessLayout layout{};
    double max_reference_hz = 0.0;
    drivecom::Sequencer sequencer;
    std::int32_t reference = 0;   // the wire value for the layout
    ibs::Word sent_word = 0;
    ibs::Word easy_word = 0;
    std::int32_t sent_reference = 0;
    bool sent = false;
    Time next_send{};
  };
  [[nodiscard]] Time sequencer_time(Time now) const;
  Slot* slot(canlust::Address a);
  [[nodiscard]] const Slot* slot(canlust::Address a) const;
  ParameterSubmission submit(canlust::Address a, const canlust::Request& r);

  DriverConfig config_;
  std::vector<DriveSettings> settings_;
  canlust::Master master_;
  std::vector<Slot> slots_;
  std::vector<std::int16_t> slot_of_;  // address -> index into slots_, -1: not configured
  SystemPhase phase_ = SystemPhase::logon;
  Time started_at_ = Time::min();      // the last Start broadcast
  // The sequencers' clock: runs in System Start only.
  Time seq_now_{};
  Time last_cycle_{};
  bool cycled_ = false;
  bool fresh_status_ = false;
};

}  // namespace ibs::devices::cda3000
