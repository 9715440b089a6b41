// The inverter side of the VF1000 parameter channel (INTERBUS manual 4.1.3 and 4.1.4): one step reads
// the master's communication word and returns the inverter's. The caller decides how often the
// inverter processes the channel (the VF1000 samples every 8.2 ms and advances the channel about
// one byte every few samples, 7.1); step() itself is pure: state and inputs in, word out.
// The server keeps only the channel's protocol state. The parameters it serves are a drive's
// (drive::ParameterAccess: the drive's one store, its 85-SIOF latch, its write rules), given to it
// by reference, so that another channel of the same drive serves the same values; made from a bare
// table, it owns a drive::StoredParameters of its own (the channel's tests and fuzz target).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "ibs/drive/parameter_access.hpp"
#include "ibs/drive/parameters.hpp"
#include "ibs/base/error.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/vf1000_channel/comm_word.hpp"
#include "ibs/vf1000_channel/description.hpp"

namespace ibs::vf1000_channel {

struct ServerConfig {
  // After power-on the inverter initialises and runs its self-test for about 4 s (6.1); its word
  // carries RESET distinction bit 0 meanwhile (4.1.2.2).
  Duration init_duration = 4s;
  // The parameter whose value 1 loads every parameter's factory default (LUSTBUS manual 10, exception
  // 1: the VF1000's 71-PROG); none: the table has no such command. Used by a server that owns its
  // parameters; a drive that lends its parameters applies its own PROG.
  std::optional<std::uint16_t> factory_defaults_parameter;
};

// How the inverter is found when the server is made.
enum class ServerStart : std::uint8_t {
  power_on,     // just switched on: initialising for init_duration, then 85-SIOF power-on bit set
  initialised,  // initialisation done, power-on bit still set (trace header `init: power-on`)
  operational,  // running, 85-SIOF read and clear (trace header `init: operational`)
};

enum class ServerState : std::uint8_t {
  initialising,   // RESET distinction bit 0, the master's word is ignored (6.1)
  wait,           // wait mode: CODE 0 seen, ready for a telegram
  sending,        // value inquiry / description scan: one byte out per master toggle
  transfer_high,  // value transfer: PNR taken, waiting for DAT1
  transfer_low,   // value transfer: DAT1 taken, waiting for DAT2
  done,           // the last byte went out with ACK or NAK: waiting for CODE 0
};
std::string_view to_string(ServerState s);

// Why the inverter answered NAK.
enum class NakReason : std::uint8_t {
  unintended_control_bits,  // bits 6/7 set, or CODE changed inside a telegram (4.1.4)
  undefined_code,           // CODE 4-7 in a start word
  no_parameter,             // no parameter with that number (4.1.3.1)
  no_change,                // read-only, or EEPROM while the power stage is enabled (4.1.3.2)
  invalid_value,            // outside min/max (4.1.3.3)
  siof_pending,             // 85-SIOF <> 0: transfers refused until it is read (4.1.4, 6.1)
  after_end,                // the master toggled again after the last byte instead of CODE 0
};
std::string_view to_string(NakReason r);

// What one step did, for the caller (the device model reacts to written parameters).
struct ServerEvent {
  enum class Kind : std::uint8_t {
    none,
    initialised,       // initialisation finished this step
    value_read,        // a value inquiry's last byte went out (value = the value sent)
    value_written,     // a value transfer took effect (value = the new value)
    description_read,  // a description scan's last byte went out
    nak,               // NAK sent (reason, siof_set)
    aborted,           // CODE 0 ended an unfinished telegram; a partial transfer was discarded
  };
  Kind kind = Kind::none;
  Code code = Code::reset;
  std::uint16_t number = 0;
  Word value = 0;
  NakReason reason = NakReason::unintended_control_bits;
  std::uint8_t siof_set = 0;  // nak: 85-SIOF bits this NAK set (only value transfers set bits)
  bool eeprom_changed = false;  // value_written: the EEPROM copy took a different value (7.1: the
                                // write then takes longer)
  Duration storing{};           // value_written: how long the drive takes to store it (its model)
};

class Server {
 public:
  // Refuses a malformed table (drive::ParameterTable::validate) and one without 85-SIOF, the
  // channel's error register (ErrorCode::table_lacks_siof).
  [[nodiscard]] static Error validate(std::span<const drive::ParameterInfo> params);
  // Serves the drive's parameter table (devices/vf1000/parameters.hpp for the VF1000), one that
  // validate() accepts, with parameters of its own: otherwise it throws std::invalid_argument with
  // validate()'s message, or, in the embedded build, aborts.
  Server(const ServerConfig& config, ServerStart start, Time now,
         std::span<const drive::ParameterInfo> params);
  // Serves the parameters of a drive that owns them (its table must pass validate(), as above).
  // `drive` must outlive the server. The drive keeps its own start state (85-SIOF, values): `start`
  // sets only the channel's (initialising until now + init_duration, or in wait mode).
  Server(const ServerConfig& config, ServerStart start, Time now, drive::ParameterAccess& drive);
  // A copy of a server that owns its parameters owns a copy of them; one that serves a drive's
  // serves the same drive (rebind() moves it to another).
  Server(const Server& other);
  Server& operator=(const Server& other);
  Server(Server&&) = delete;
  Server& operator=(Server&&) = delete;
  ~Server() = default;
  // Serves another drive's parameters from now on (a copy of the drive the server belongs to).
  void rebind(drive::ParameterAccess& drive) { drive_ = &drive; }

  // One inverter processing step: reads the master's word, returns the inverter's. What the step
  // did is in last_event() until the next step. `power_stage_enabled` is the drive's state now
  // (EEPROM parameters are refused while it is).
  Word step(Word from_master, Time now, bool power_stage_enabled);
  [[nodiscard]] const ServerEvent& last_event() const { return ch_.event; }

  // Power cycle: an unfinished telegram is lost (never half-applied); RESET distinction 0 until
  // now + init_duration. Parameters the server owns power on too: RAM values return to their
  // defaults, EEPROM values stay, power-on bit set (a drive that lends its parameters does that
  // itself, and tells the server through restart()).
  void power_on(Time now) { power_on(now, config_.init_duration); }
  // The same start with another self-test time: the software reset that RESET FAULT performs
  // (INTERBUS manual 5.2.1; LUSTBUS manual 8.1.1: the link is gone during the self-test, 9.2: power-on bit).
  void power_on(Time now, Duration init);
  // The channel alone starts again: the drive's parameters are left as they are.
  void restart(Time now, Duration init);

  [[nodiscard]] ServerState state() const { return ch_.state; }
  // True while the inverter initialises (its word has RESET distinction bit 0).
  [[nodiscard]] bool initialising(Time now) const {
    return ch_.state == ServerState::initialising && now < ch_.ready_at;
  }
  [[nodiscard]] Time ready_at() const { return ch_.ready_at; }
  // The word the inverter shows now (what the last step returned).
  [[nodiscard]] Word output() const { return ch_.out; }

  [[nodiscard]] std::uint8_t siof() const { return drive_->siof(); }
  // The device sets error bits of its own (e.g. the watchdog bit 1).
  void raise_siof(std::uint8_t bits) { drive_->raise_siof(bits); }

  // The device side's access to its parameters (actual values like 911-IBSTA and 912-FIST, the
  // control word 901-ICNTL); nullopt / false for a number the table lacks. set_value bypasses the
  // channel's checks.
  [[nodiscard]] std::optional<Word> value(std::uint16_t number) const;
  bool set_value(std::uint16_t number, Word raw);

  [[nodiscard]] const drive::ParameterTable& table() const { return drive_->table(); }
  [[nodiscard]] const drive::ParameterAccess& parameters() const { return *drive_; }

 private:
  Word process(Word m, bool power_stage_enabled, Time now);
  Word start_telegram(Word m, bool power_stage_enabled);
  Word next_byte();
  Word take_high(Word m);
  Word take_low(Word m, bool power_stage_enabled, Time now);
  Word nak(NakReason reason, std::uint8_t siof_bits);
  Word send(std::uint8_t data, Flag flag);

  ServerConfig config_;
  std::optional<drive::StoredParameters> own_;  // parameters of its own, when given none
  drive::ParameterAccess* drive_ = nullptr;      // what it serves: *own_ or a drive's

  // The channel's protocol state: a copy of the server copies it whole; only what the server
  // serves (own_, drive_) needs the copy constructor's care.
  struct Channel {
    ServerState state = ServerState::initialising;
    Time ready_at{0};
    Word out = 0;
    bool toggle = false;      // toggle of the last master word taken (echoed in out)
    Code code = Code::reset;  // the running telegram
    std::uint16_t number = 0;
    std::int16_t slot = -1;   // the running telegram's parameter
    std::uint8_t index = 0;   // next byte to send
    std::uint8_t length = 0;  // bytes to send: 2 (inquiry) or 18 (description)
    std::uint8_t high = 0;    // DAT1 of a transfer, held until DAT2 completes it
    Word latched = 0;         // the value an inquiry sends, taken whole when the PNR arrives
    ServerEvent event;
  };
  Channel ch_;
};

}  // namespace ibs::vf1000_channel
