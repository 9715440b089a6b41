// The plain drive: one Store behind a dictionary and the rules the LUST family's parameters
// follow on every bus, with nothing of a motor behind them. What a protocol server serves when it
// is given no drive of its own (its tests, fuzz targets, benchmarks; the communication word's
// own-table mode), and the parameter half a new drive starts from ("add a drive"). The rules:
//
// - 85-SIOF/SERR, where the dictionary has it (Role::error_flags): power-on sets its power-on bit;
//   while any bit is set every write is refused `latched`, entering nothing (LUSTBUS manual 9.2, 6;
//   INTERBUS manual 4.1.4); a refused write enters its refusal's bit; a read of it clears what it
//   returned. Reads enter nothing (6.1 note). A dictionary without it keeps no flags (CANLust).
// - Writes: read-only and RAM actual values refused; an EEPROM value only with the power stage
//   disabled, an EEPROM/RAM variable into RAM alone while it is enabled (INTERBUS manual 4.1.3.2-3,
//   VF-E18); the value checked against type, min, max and (choices_only) its choices; the answer
//   waits for the EEPROM (LUSTBUS manual 3: "until the parameter value is stored", per byte).
// - PROG (Role::load_defaults) = 1: every factory default, 85 keeping its bits (LUSTBUS manual 10
//   exception 1); SAVE (Role::save) = 1: the flash values kept (CANLust manual 3.5.1). Both are
//   commands: they read their default again afterwards.
// - SLOAD (Role::download), LUSTBUS manual 11.4: -1 at standstill opens a download (the data set is
//   snapshot); meanwhile values of the data set are taken untested into RAM and any other write is
//   acknowledged and dropped; -2 ends it: SLOAD reads -1 while the set is tested, then 0 (the set
//   in EEPROM) or the number of the first implausible parameter (the old set restored).
//
// Cycle path after construction: no allocation, no exception.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "ibs/od/served.hpp"
#include "ibs/od/store.hpp"

namespace ibs::od {

// How long the drive takes (each zero by default: answered at once).
struct StoredServedTiming {
  Duration eeprom_per_byte{};   // a changed EEPROM value, per byte of its type (VF1000: 60 ms)
  Duration factory_defaults{};  // PROG = 1 ("can take up to 10 seconds", LUSTBUS manual 10)
  Duration save{};              // SAVE = 1 ("a few hundred milliseconds", CANLust manual 3.5.1)
  Duration download_check{};    // SLOAD = -2 until the test has ended (LUSTBUS manual 11.4 step 3)
};

struct StoredServedConfig {
  std::span<const DefaultOverride> defaults{};  // another factory default for some entries
  StoredServedTiming timing{};
};

class StoredServed final : public ServedParameters {
 public:
  // SLOAD's handshake values (LUSTBUS manual 11.4).
  static constexpr std::int64_t kDownloadBegin = -1;
  static constexpr std::int64_t kDownloadEnd = -2;

  // A drive just powered on: the factory defaults, 85 = its power-on bit. Allocates (the store);
  // an overlay Store::validate refuses throws std::invalid_argument (embedded: aborts).
  explicit StoredServed(const Dictionary& d, const StoredServedConfig& config = {});

  // ---- ServedParameters ---------------------------------------------------------------------
  [[nodiscard]] const Dictionary& dictionary() const override { return store_.dictionary(); }
  void advance(Time now) override {
    if (download_ == Download::testing && now >= download_done_at_) finish_download();
  }
  Reading read(Slot s, Time now) override;
  [[nodiscard]] Raw peek(Slot s) const override { return s < store_.size() ? store_.ram(s) : 0; }
  [[nodiscard]] Raw factory_default(Slot s) const override {
    return s < store_.size() ? store_.default_raw(s) : 0;
  }
  [[nodiscard]] Refusal check(Slot s, std::optional<Raw> r, Time now) const override;
  Answer write(Slot s, Raw r, Time now) override;
  Answer refuse(Refusal r) override;
  [[nodiscard]] std::uint8_t error_flags() const override {
    return flags_slot_ == kNoSlot ? 0 : static_cast<std::uint8_t>(store_.ram(flags_slot_));
  }
  void raise_error_flags(std::uint8_t bits) override;
  void clear_error_flags(std::uint8_t bits) override;
  [[nodiscard]] bool fault() const override { return fault_; }
  TextAnswer read_text(Slot s, std::span<char> out, Time now) override;
  Answer write_text(Slot s, std::string_view text, Time now) override;

  // ---- the drive around it ------------------------------------------------------------------
  // Power-on: kept values back (Store::power_on), 85 = the power-on bit alone, a download
  // forgotten.
  void power_on();
  // Whether the power stage runs: EEPROM values wait, SLOAD -1 is refused (the drive's own state;
  // the channel's own-table mode passes on what its process data say).
  void set_power_stage(bool enabled) { power_stage_ = enabled; }
  [[nodiscard]] bool power_stage() const { return power_stage_; }
  void set_fault(bool fault) { fault_ = fault; }
  // 11.4: from SLOAD = -1 until the test has ended.
  [[nodiscard]] bool downloading() const { return download_ != Download::idle; }

  [[nodiscard]] const Store& store() const { return store_; }
  Store& store() { return store_; }
  [[nodiscard]] const StoredServedTiming& timing() const { return timing_; }

 private:
  enum class Download : std::uint8_t { idle, receiving, testing };
  Answer refused(Refusal r);
  Answer download(Slot s, Raw r, Time now);
  void finish_download();
  [[nodiscard]] Refusal access(const Entry& e, Time now) const;
  [[nodiscard]] Refusal value_check(const Entry& e, Raw r, Time now) const;

  Store store_;
  StoredServedTiming timing_;
  Slot flags_slot_;
  Slot sload_slot_;
  bool power_stage_ = false;
  bool fault_ = false;
  Download download_ = Download::idle;
  Time download_done_at_{};
};

}  // namespace ibs::od
