// The VF1000 in the fault campaign (devices/campaign_profile.hpp, docs/robustness.md "Fault
// campaign"): four inverters, one for each 907-IBCOD reaction; the parameter model from the table
// (parameters.hpp); 71-PROG as the LUSTBUS manual describes it; 906-IB-WD in 50 ms steps (INTERBUS manual 4.1.1).
#include "ibs/devices/vf1000/campaign_profile.hpp"

#include <algorithm>

#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/devices/vf1000/device.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/vf1000_channel/client.hpp"

namespace ibs::devices::vf1000 {

namespace {

void add(std::vector<std::int64_t>& set, std::int64_t v) {
  if (std::find(set.begin(), set.end(), v) == set.end()) set.push_back(v);
}

const Vf1000Device& inverter(const DeviceEmulator& e) { return dynamic_cast<const Vf1000Device&>(e); }

class Profile final : public CampaignProfile {
 public:
  [[nodiscard]] std::string_view kind() const override { return kName; }

  [[nodiscard]] std::vector<CampaignRingDevice> ring(CampaignRandom& rng) const override {
    // 906-IB-WD up to 100, 200 and 400 ms, and off (65535).
    const std::vector<int> ibwd = {100, 200, 400, 65535};
    std::vector<CampaignRingDevice> ring;
    for (int v = 0; v < 4; ++v) {
      CampaignRingDevice c;
      c.name = "vf" + std::to_string(v + 1);
      c.phase = rng.between(Duration{0}, kSamplePeriod - Duration{1});
      c.jitter = rng.pick(std::vector<Duration>{0us, 100us, 400us});
      c.initialised = !rng.chance(0.25);
      const int max = ibwd[static_cast<std::size_t>(v)];
      c.settings.watchdog_ms = max == 65535 ? 65535 : static_cast<int>(rng.uniform(8, max));
      c.settings.watchdog_reaction = v % 4;  // 0 none, 1 E-IBS, 2 BLOCK POWER, 3 EMERGENCY STOP
      ring.push_back(std::move(c));
    }
    return ring;
  }

  [[nodiscard]] CampaignDevice device(const CampaignRingDevice& c, const DeviceEmulator& /*emulator*/,
                                      CampaignRandom& rng) const override {
    const DeviceSettings& s = c.settings;
    CampaignDevice d;
    d.period = kSamplePeriod;
    d.has_channel = true;  // the communication word
    d.has_pd = true;
    d.watchdog_parameter = pnr::kIbWd;
    d.description = "VF1000, 906-IB-WD " + std::to_string(*s.watchdog_ms) + " ms, 907-IBCOD " +
                    std::to_string(*s.watchdog_reaction);
    for (const drive::ParameterInfo& p : parameters()) {
      CampaignParam m;
      m.number = p.number;
      const drive::Storage st = drive::storage(p.category);
      m.eeprom = st == drive::Storage::eeprom || st == drive::Storage::eeprom_ram;
      m.eeprom_ram = st == drive::Storage::eeprom_ram;
      m.factory = p.default_value;
      m.initial = p.number == pnr::kIbWd ? *s.watchdog_ms : p.number == pnr::kIbcod ? *s.watchdog_reaction
                                                                                    : p.default_value;
      m.min = p.min;
      m.max = p.max;
      m.eeprom_save = Duration{0};  // the inverter's store takes the EEPROM copy with the value
      // 901-ICNTL and 905-FDRIV are the control word and the reference, which the process data
      // write too (INTERBUS manual 4.1.1): not the parameter channel's alone. 11-STAT reads the drive's
      // status and takes only the reset 000FH (LUSTBUS manual 8.1.1), over the communication word too
      // (docs/errata.md VF-E14).
      const bool mirrored = p.number == pnr::kIcntl || p.number == pnr::kFdriv || p.number == pnr::kStat;
      m.role = (!drive::writable(p.category) || mirrored) ? CampaignRole::device_owned
               : p.number == pnr::kProg                   ? CampaignRole::command
                                                          : CampaignRole::normal;
      d.params.push_back(m);
      d.readable.push_back(p.number);
      if (m.role != CampaignRole::normal) continue;
      CampaignWrites w;
      w.number = p.number;
      w.in_range = {p.default_value, p.min, p.max};
      for (int k = 0; k < 2; ++k) add(w.in_range, rng.uniform(p.min, p.max));
      // Watchdog times the campaign's outages (550 ms) exceed, and off.
      if (p.number == pnr::kIbWd) w.in_range = {100, 200, 400, 65535, m.initial};
      // Out of range, as far as the communication word's 16 bits carry it.
      if (p.max < 0xFFFF) w.out_of_range.push_back(p.max + 1);
      if (p.type == drive::DataType::usign8 || p.type == drive::DataType::binary8) w.out_of_range.push_back(0x1FF);
      if (p.min > 0) w.out_of_range.push_back(p.min - 1);
      d.writes.push_back(std::move(w));
    }
    return d;
  }

  [[nodiscard]] std::int64_t watchdog_ms(std::int64_t raw) const override {
    const auto m = ib_wd_monitoring_time(static_cast<Word>(raw));
    return m ? m->count() : 0;
  }

  [[nodiscard]] Duration request_timeout(ParamOp /*op*/, std::uint16_t /*number*/,
                                         std::int64_t /*value*/) const override {
    return vf1000_channel::ClientConfig{}.timeout;  // per transaction, whatever it is
  }

  // A description scan holds the communication word up to 490 ms (INTERBUS manual 7.1).
  [[nodiscard]] double describe_share() const override { return 0.02; }

  [[nodiscard]] std::pair<std::int64_t, std::int64_t> reference_range() const override { return {-60, 60}; }

  [[nodiscard]] std::optional<CampaignFactoryDefaults> factory_defaults() const override {
    // 71-PROG: 1 loads the factory defaults (LUSTBUS manual 10).
    return CampaignFactoryDefaults{pnr::kProg, "71-PROG", {}, 0.0};
  }

  // RESET FAULT boots the inverter (INTERBUS manual 5.2.1): its store as after a power cycle.
  [[nodiscard]] std::uint32_t software_resets(const DeviceEmulator& emulator) const override {
    return inverter(emulator).software_resets();
  }

  void read_store(const DeviceEmulator& emulator, std::vector<CampaignStoreEntry>& out) const override {
    const Drive& d = inverter(emulator).drive();
    for (const drive::ParameterInfo& p : parameters()) {
      const int slot = d.table().slot(p.number);
      if (slot < 0) continue;
      out.push_back({p.number, d.store().value(static_cast<std::size_t>(slot)),
                     std::optional<std::int64_t>(d.store().eeprom_value(static_cast<std::size_t>(slot)))});
    }
  }
};

}  // namespace

const CampaignProfile& campaign_profile() {
  static const Profile p;
  return p;
}

}  // namespace ibs::devices::vf1000
