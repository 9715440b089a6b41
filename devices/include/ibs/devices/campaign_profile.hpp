// What the fault campaign (sim/campaign.hpp, docs/robustness.md "Fault campaign") needs of a drive
// kind: its share of the campaign's ring, the model its oracle keeps of the drive's parameters
// (roles, ranges, defaults, EEPROM timing: facts from the manuals), its bus watchdog, the scripted
// parameter sequences it supports (factory defaults, a download, layout settings read at
// power-on), the time its parameter channel may take, and the few observations of its emulator
// that DeviceEmulator does not offer. Each wing implements one (devices/<drive>/src/
// campaign_profile.cpp, in its device library) and the registry hands it out with the kind
// (registry.hpp, DriveKind::campaign), so the campaign names no concrete drive.
//
// The profile tells the oracle what is right from the manuals; it reads the emulator only to
// observe it (its parameter store, its boots), never to decide what the store should hold.
// Everything here is configuration or test time: it may allocate.
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibs/base/time.hpp"
#include "ibs/devices/descriptor.hpp"
#include "ibs/devices/driver.hpp"

namespace ibs::devices {

class DeviceEmulator;

// The campaign's one seeded generator: every random choice, the profiles' included, draws from it
// in a fixed order, so that a seed gives the same run.
class CampaignRandom {
 public:
  explicit CampaignRandom(std::uint64_t seed) : rng_(seed) {}
  // lo..hi, both included.
  std::int64_t uniform(std::int64_t lo, std::int64_t hi) {
    return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng_);
  }
  // [0, 1)
  double real() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }
  bool chance(double p) { return real() < p; }
  template <typename T>
  const T& pick(const std::vector<T>& v) {
    return v[static_cast<std::size_t>(uniform(0, static_cast<std::int64_t>(v.size()) - 1))];
  }
  Duration between(Duration lo, Duration hi) { return Duration{uniform(lo.count(), hi.count())}; }

 private:
  std::mt19937_64 rng_;
};

// What a parameter is to the oracle.
enum class CampaignRole : std::uint8_t {
  normal,        // written by the master only; RAM (and EEPROM copy) checked against the model
  command,       // the PROG command: always reads its default (0); drive::kLoadDefaults loads the
                 // factory defaults (LUSTBUS manual 10)
  download,      // SLOAD (LUSTBUS manual 11.4): drive::kDownloadBegin opens a download,
                 // drive::kDownloadEnd ends it (it reads kDownloadBegin while the dataset is
                 // checked, then 0)
  device_owned,  // actual values, mirrors, error registers: not checked
};

struct CampaignParam {
  std::uint16_t number = 0;
  CampaignRole role = CampaignRole::normal;
  bool eeprom = false;       // has an EEPROM copy that power-on restores
  bool eeprom_ram = false;   // EEPROM only while the power stage is off (VF1000 category 3)
  std::int64_t initial = 0;  // RAM and EEPROM at the start (default or configured value)
  std::int64_t factory = 0;  // the factory default (the PROG command's kLoadDefaults)
  std::int64_t min = 0;      // the documented range: a write outside it must not be `written`
  std::int64_t max = 0;
  Duration eeprom_save{0};   // after a confirmed write the EEPROM copy follows within this
  // LUSTBUS manual 11.4: takes a download's value (untested; EEPROM once the dataset is accepted);
  // any other parameter's write during a download is acknowledged and dropped.
  bool card_writeable = false;
};

// The values the campaign writes to one parameter: documented ones, and ones outside the range
// that the channel can carry.
struct CampaignWrites {
  std::uint16_t number = 0;
  std::vector<std::int64_t> in_range;
  std::vector<std::int64_t> out_of_range;
};

// One parameter of the device's store as the emulator holds it.
struct CampaignStoreEntry {
  std::uint16_t number = 0;
  std::int64_t ram = 0;
  std::optional<std::int64_t> eeprom;
};

// One device of the campaign's ring, as the simulator is to place it.
struct CampaignRingDevice {
  std::string name;
  DeviceSettings settings;
  Duration phase{0};         // first sample after start
  Duration jitter{0};
  bool initialised = true;   // false: the run starts at the device's power-on
};

// A parameter the drive reads only at power-on to lay out its words on the bus: a write that
// differs from the ring's value must bring the device back with a module error after a power
// cycle, and the technician then restores it (CampaignProfile::restore_layout).
struct CampaignLayoutParameter {
  std::uint16_t number = 0;
  std::string_view label;    // "405-SUPI": counted as "<label> writes"
  std::int64_t configured = 0;  // the ring's value
  std::int64_t min = 0;      // the values the campaign writes
  std::int64_t max = 0;
};

// The device as the campaign drives and checks it.
struct CampaignDevice {
  std::string description;   // after "name: ", e.g. "VF1000, 906-IB-WD 100 ms, 907-IBCOD 1"
  Duration period{0};        // sample period
  bool has_channel = false;  // a parameter channel the campaign sends requests over
  bool has_pd = false;       // DRIVECOM through process data
  std::vector<CampaignParam> params;  // the oracle's model (empty without a channel)
  std::vector<CampaignWrites> writes; // the parameters the campaign writes at random
  std::vector<std::uint16_t> readable;
  // The bus watchdog: a parameter (raw value, CampaignProfile::watchdog_ms) or, without a
  // channel to change it, a fixed monitoring time. Neither: the device has none.
  std::uint16_t watchdog_parameter = 0;
  std::int64_t watchdog_fixed_ms = 0;
  std::vector<CampaignLayoutParameter> layout;
};

// The PROG command that loads the factory defaults, and the other values the campaign writes to
// it now and then.
struct CampaignFactoryDefaults {
  std::uint16_t parameter = 0;
  std::string_view label;                 // "71-PROG": counted as "<label> writes"
  std::vector<std::int64_t> other_values;  // written instead of kLoadDefaults, with other_chance
  double other_chance = 0.0;
};

// A parameter download through SLOAD (LUSTBUS manual 11.4; CampaignRole::download).
struct CampaignDownload {
  std::uint16_t parameter = 0;
  std::string_view label;   // "80-SLOAD"
  Duration check{0};        // after the end, the drive checks the dataset this long
  std::string_view source;  // where the drive's promise to stay disabled meanwhile is written
};

class CampaignProfile {
 public:
  virtual ~CampaignProfile() = default;
  CampaignProfile() = default;
  CampaignProfile(const CampaignProfile&) = delete;
  CampaignProfile& operator=(const CampaignProfile&) = delete;

  // The drive kind's name (DriveFacts::name).
  [[nodiscard]] virtual std::string_view kind() const = 0;
  // This kind's share of the campaign's default ring, its settings drawn from `rng`.
  [[nodiscard]] virtual std::vector<CampaignRingDevice> ring(CampaignRandom& rng) const = 0;
  // The device the simulator made of `d`: its model, the writes the campaign makes (drawn from
  // `rng`), its watchdog, its description. `emulator` only for the layout the device took.
  [[nodiscard]] virtual CampaignDevice device(const CampaignRingDevice& d, const DeviceEmulator& emulator,
                                              CampaignRandom& rng) const = 0;
  // The monitoring time in ms a raw value of CampaignDevice::watchdog_parameter stands for;
  // 0 or less: off.
  [[nodiscard]] virtual std::int64_t watchdog_ms(std::int64_t raw) const = 0;
  // The longest a request may take on the device's parameter channel, by the documented timeouts
  // of the master's client (without the campaign's margin).
  [[nodiscard]] virtual Duration request_timeout(ParamOp op, std::uint16_t number, std::int64_t value) const = 0;
  // The share of descriptions among the campaign's requests: fewer where a description keeps the
  // channel long.
  [[nodiscard]] virtual double describe_share() const = 0;
  // The reference the campaign sets now and then, in the drive's unit (DriveFacts::unit).
  [[nodiscard]] virtual std::pair<std::int64_t, std::int64_t> reference_range() const = 0;
  // The scripted sequences the drive supports.
  [[nodiscard]] virtual std::optional<CampaignFactoryDefaults> factory_defaults() const = 0;
  [[nodiscard]] virtual std::optional<CampaignDownload> download() const { return std::nullopt; }
  // A register a refused write latches, which refuses every further write until it is read; the
  // campaign reads it after every write that did not succeed and after a power cycle.
  [[nodiscard]] virtual std::optional<std::uint16_t> write_error_register() const { return std::nullopt; }

  // --- observing the emulator (what DeviceEmulator does not offer) ------------------------------
  // Boots of the drive that the master asked for (a reset from FAULT), since it was made: its
  // store comes back as after a power cycle.
  [[nodiscard]] virtual std::uint32_t software_resets(const DeviceEmulator& /*emulator*/) const { return 0; }
  // The drive's layout settings (CampaignDevice::layout) no longer fit the ring: it reports a
  // module error and takes no words.
  [[nodiscard]] virtual bool layout_mismatch(const DeviceEmulator& /*emulator*/) const { return false; }
  // The parameter store now (RAM and EEPROM copy); empty without a channel.
  virtual void read_store(const DeviceEmulator& emulator, std::vector<CampaignStoreEntry>& out) const = 0;
  // The technician sets the layout parameters back to the ring's values `d` at the drive (RAM
  // and EEPROM); the campaign then switches it off and on.
  virtual void restore_layout(DeviceEmulator& /*emulator*/, const CampaignRingDevice& /*d*/) const {}
};

}  // namespace ibs::devices
