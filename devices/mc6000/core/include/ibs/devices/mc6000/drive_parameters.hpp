// The MC6000's parameter memory and its rules, written once for every bus (docs/architecture.md,
// "One drive, many faces"): the one store (RAM, the EEPROM copy, and the dataset a rejected
// download brings back), the write checks, the 85-SERR latch with its power-on bit (LUSTBUS manual 6
// and 9.2), the EEPROM save in the background (3, 10.2.2: 15 ms per byte, "EEPROM busy"), 4-PROG
// (10 exception 1: factory defaults; 11.5: 111 activates 81-SBAUD), 15-PLRDY and READY mode (seed
// 001, 4.2; the attributes InitControl and NoInit of the LUSTBUS manual 11.2.1: MC-D11) and
// the 80-SLOAD download of the CardWriteable parameters (LUSTBUS manual 11.4).
//
// It knows no bus: a face turns its telegram or PDU into number + raw value and the refusal back
// into its answer (LUSTBUS NAK, PCP error class/code). Part of the drive core (drive.hpp), kept
// without the plant so that the `words: pcp` replay adapter of the master library serves it too.
// Every access is on the cycle path: no allocation, no exceptions, time passed in.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/base/time.hpp"
#include "ibs/drive/parameter_journal.hpp"
#include "ibs/drive/siof.hpp"
#include "ibs/pcp/data_types.hpp"
#include "ibs/pcp/parameter_store.hpp"
#include "ibs/pcp/parameters.hpp"

namespace ibs::devices::mc6000 {

// Why the drive refused a write. Each refusal but `latched` enters its bit in 85-SERR (9.2).
enum class Refusal : std::uint8_t {
  none,
  latched,       // a bit of 85-SERR is set: "all further SELECT-telegrams are rejected" (9.2)
  no_parameter,  // 20H
  read_only,     // 40H: a RAM actual value, or an address that only reads
  not_now,       // 40H: 80-SLOAD while running, -2 without -1, any write during the check (11.4)
  eeprom_busy,   // 04H: the last EEPROM value is still being saved (3)
  bad_value,     // 80H: the bus's value is no value of the type
  too_high,      // 80H: above max, or an 80-SLOAD value the host may not write (11.4: -1, -2)
  too_low,       // 80H
};
// The 85-SERR bit a refusal enters (0 for none and latched).
std::uint8_t serr_bit(Refusal r);

struct WriteResult {
  Refusal refusal = Refusal::none;
  // How long the drive works on an accepted write before it can confirm it (4-PROG = 1).
  Duration busy_for = Duration::zero();
  // The write reset a reaction-5 error and the servo boots at once (LUSTBUS manual 8.1.2): the
  // answer "under certain circumstances, is not sent in full".
  bool restarted = false;
  [[nodiscard]] bool ok() const { return refusal == Refusal::none; }
};

// The drive's own timing, the same whichever bus asks (docs/errata.md MC-D1, MC-D2).
struct DriveTiming {
  // LUSTBUS manual 3 and 10.2.2: "To save a byte in EEPROM, the servocontroller needs 15 ms".
  Duration eeprom_per_byte = std::chrono::milliseconds(15);
  // LUSTBUS manual 10 exception 1: 4-PROG = 1 answers once every parameter is reset, which "can take
  // up to 10 seconds": the drive takes nearly all of it, so that a master's timeout is tested,
  // and its answer still arrives within the 10 s on either bus (MC-D1).
  Duration factory_defaults = std::chrono::milliseconds(9900);
  // LUSTBUS manual 11.4 steps 3-4: the plausibility test and save after 80-SLOAD = -2; the seed gives
  // no time, only the host's 10 s timeout (MC-D2).
  Duration download_check = std::chrono::milliseconds(200);
};

struct DriveParametersConfig {
  std::span<const pcp::ParameterInfo> table;          // the wing's (parameters.hpp)
  bool (*card_writeable)(std::uint16_t) = nullptr;    // 11.4; nullptr: none is
  DriveTiming timing{};
};

class DriveParameters {
 public:
  // Every value at its default, 85-SERR = the power-on bit. Throws std::invalid_argument for a
  // table pcp::ParameterStore refuses (configuration time).
  explicit DriveParameters(const DriveParametersConfig& config);

  // The one store every face reads and writes.
  [[nodiscard]] const pcp::ParameterStore& store() const { return store_; }
  [[nodiscard]] std::span<const pcp::ParameterInfo> table() const { return store_.table(); }
  [[nodiscard]] const DriveTiming& timing() const { return timing_; }

  // Time passes: an EEPROM save ends, the download test ends (11.4). Inline: a sample with neither
  // pending (nearly every one) costs two compares, not a call.
  void advance(Time now) {
    if (eeprom_pending_ || download_ == Download::testing) advance_pending(now);
  }

  // A read: the RAM value; reading 85-SERR clears it (6, 9.2). nullopt: no such parameter (a
  // read error enters nothing, 6.1 note).
  std::optional<pcp::Value> read(Time now, std::uint16_t number);
  // The value as it stands, without acting.
  [[nodiscard]] std::optional<pcp::Value> value(std::uint16_t number) const { return store_.get(number); }
  [[nodiscard]] std::uint32_t raw(std::uint16_t number) const;
  [[nodiscard]] std::optional<pcp::Value> eeprom(std::uint16_t number) const { return store_.eeprom(number); }

  // A write of `raw` (nullopt: the bus's value was no value of the type) with the drive's power
  // stage on or off (`running`: 80-SLOAD only at standstill, 11.4).
  WriteResult write(Time now, std::uint16_t number, std::optional<std::uint32_t> raw, bool running);
  // A write the face refused before it reached a parameter (a PCP subindex, a LUSTBUS CODE that
  // only reads): refused as `latched` while 85-SERR holds a bit, else enters the refusal's bit.
  WriteResult refuse(Refusal r);
  // A cause the drive enters by itself (watchdog 02H, checksum 08H: 9.2).
  void set_serr(drive::SiofBit b);
  [[nodiscard]] std::uint8_t serr() const { return static_cast<std::uint8_t>(raw(kSerrNumber)); }

  // A value the drive sets itself (readings such as 77-SPEED, 408-IBSTA): RAM only, no checks.
  void set_reading(std::uint16_t number, std::uint32_t raw) { store_.set(number, raw); }
  // The servo as configured: RAM and EEPROM (configuration time, or a tool's preset).
  bool preset(std::uint16_t number, std::int64_t value);

  // Power on: RAM from EEPROM, RAM values to their defaults, an unfinished EEPROM save lost, the
  // download forgotten, 85-SERR = the power-on bit (6).
  void power_on(Time now);

  [[nodiscard]] bool eeprom_busy(Time now) const { return now < eeprom_busy_until_; }
  [[nodiscard]] Time eeprom_busy_until() const { return eeprom_busy_until_; }
  [[nodiscard]] std::uint32_t eeprom_saves() const { return eeprom_saves_; }
  // 11.4: from 80-SLOAD = -1 until the test has ended the servo is "secured against being engaged".
  [[nodiscard]] bool downloading() const { return download_ != Download::idle; }
  [[nodiscard]] bool download_testing() const { return download_ == Download::testing; }
  // How many times 15-PLRDY = 1 asked for a controller recalculation (INTERBUS manual 4.2).
  [[nodiscard]] std::uint32_t plrdy_requests() const { return plrdy_requests_; }
  // READY mode (INTERBUS manual 4.2; MC-D11): the controller is calculated for the parameters as they
  // stand -- after a start, 4-PROG = 1, an accepted download or 15-PLRDY = 1; not after a changed
  // InitControl parameter (LUSTBUS manual 11.2.1) or 15-PLRDY = 0. 15-PLRDY reads it.
  [[nodiscard]] bool ready_mode() const { return raw(kPlrdyNumber) == 1; }
  // The servo may not be engaged: during a download (11.4) or out of READY mode (MC-D11).
  [[nodiscard]] bool engage_locked() const { return downloading() || !ready_mode(); }
  // How many times 4-PROG = 111 asked to activate 81-SBAUD (11.5; the serial face acts on it).
  [[nodiscard]] std::uint32_t baud_activations() const { return baud_activations_; }

 private:
  static constexpr std::uint16_t kSerrNumber = drive::kSiofNumber;
  static constexpr std::uint16_t kPlrdyNumber = 15;  // parameters.hpp's kPlrdy (INTERBUS manual 4.2)
  enum class Download : std::uint8_t { idle, receiving, testing };
  void advance_pending(Time now);  // advance() with an EEPROM save or a download test pending
  WriteResult refused(Refusal r);
  void finish_download();

  pcp::ParameterStore store_;
  bool (*card_writeable_)(std::uint16_t);
  DriveTiming timing_;
  std::array<std::uint32_t, pcp::kMaxParameters> saved_{};  // 11.4: the old dataset
  bool eeprom_pending_ = false;
  std::uint16_t eeprom_number_ = 0;
  std::uint32_t eeprom_value_ = 0;
  Time eeprom_busy_until_{};
  Download download_ = Download::idle;
  Time download_done_at_{};
  std::uint32_t eeprom_saves_ = 0;
  std::uint32_t plrdy_requests_ = 0;
  std::uint32_t baud_activations_ = 0;
};

// What a face reaches: the whole drive (drive.hpp: the face's accesses also act on the servo --
// 416-SCTL1's reset bit, 84-SWDGT, the readings), or its parameters alone (ParametersOnly).
class DriveAccess {
 public:
  virtual ~DriveAccess() = default;
  virtual void advance(Time now) = 0;
  virtual std::optional<pcp::Value> read(Time now, std::uint16_t number) = 0;
  virtual WriteResult write(Time now, std::uint16_t number, std::optional<std::uint32_t> raw) = 0;
  virtual WriteResult refuse(Refusal r) = 0;
  [[nodiscard]] virtual const DriveParameters& parameters() const = 0;
  // The drive is in FAULT or FAULT RESPONSE ACTIVE (PCP Status: physical status 1).
  [[nodiscard]] virtual bool fault() const = 0;
  // Where a channel notes the changes it made (parameter_journal.hpp); nullptr: nobody records them.
  virtual drive::ParameterJournal* changes() { return nullptr; }
};

// The parameters without a servo behind them: the `words: pcp` replay adapter and the PCP tests,
// with the power stage and the fault given from outside.
class ParametersOnly final : public DriveAccess {
 public:
  explicit ParametersOnly(const DriveParametersConfig& config) : params_(config) {}
  void advance(Time now) override { params_.advance(now); }
  std::optional<pcp::Value> read(Time now, std::uint16_t number) override { return params_.read(now, number); }
  WriteResult write(Time now, std::uint16_t number, std::optional<std::uint32_t> raw) override {
    return params_.write(now, number, raw, running_);
  }
  WriteResult refuse(Refusal r) override { return params_.refuse(r); }
  [[nodiscard]] const DriveParameters& parameters() const override { return params_; }
  [[nodiscard]] bool fault() const override { return fault_; }

  [[nodiscard]] DriveParameters& parameters() { return params_; }
  void set_running(bool running) { running_ = running; }
  void set_fault(bool fault) { fault_ = fault; }

 private:
  DriveParameters params_;
  bool running_ = false;
  bool fault_ = false;
};

}  // namespace ibs::devices::mc6000
