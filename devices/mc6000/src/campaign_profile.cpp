// The MC6000 in the fault campaign (devices/campaign_profile.hpp, docs/robustness.md "Fault
// campaign"): servos with PCP channels of 1, 2 and 4 words and several 405-SUPI / 406-IBCNF, two
// without PCP; the parameter model from the table (parameters.hpp); 4-PROG, 80-SLOAD and 85-SERR as
// LUSTBUS manual describes them; 409-BUTWD in ms.
#include "ibs/devices/mc6000/campaign_profile.hpp"

#include <algorithm>
#include <chrono>

#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/mc6000/drive_parameters.hpp"
#include "ibs/devices/mc6000/driver.hpp"
#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/settings.hpp"
#include "ibs/devices/mc6000/service.hpp"
#include "ibs/pcp/client.hpp"
#include "ibs/pcp/data_types.hpp"
#include "ibs/pcp/parameter_store.hpp"

namespace ibs::devices::mc6000 {

namespace {

// The PCP client's timeout per confirmation (docs/pcp.md).
const Duration kPcpTimeout = pcp::ClientConfig{}.request_timeout;

void add(std::vector<std::int64_t>& set, std::int64_t v) {
  if (std::find(set.begin(), set.end(), v) == set.end()) set.push_back(v);
}

const Mc6000Device& servo(const DeviceEmulator& e) { return dynamic_cast<const Mc6000Device&>(e); }

class Profile final : public CampaignProfile {
 public:
  [[nodiscard]] std::string_view kind() const override { return kName; }

  [[nodiscard]] std::vector<CampaignRingDevice> ring(CampaignRandom& rng) const override {
    struct Mc {
      const char* name;
      int supi, ibcnf;
      std::vector<int> butwd;
    };
    // PCP over 4 words (SUPI 3), 2 words (SUPI 2, 6, 9), 1 word (SUPI 5, 8, 11); two servos
    // without PCP (SUPI 10, 12), one of them stepped a cycle at a time (no jitter).
    const std::vector<Mc> mcs = {
        {"mc4a", 3, 0, {0, 50, 120}},   {"mc4b", 3, 0, {0, 80}},       {"mc4c", 3, 0, {40, 150}},
        {"mc2a", 9, 1, {30, 60, 100}},  {"mc2b", 6, 0, {0, 100}},      {"mc2c", 9, 0, {50, 200}},
        {"mc2d", 2, 0, {0, 60}},        {"mc1a", 11, 2, {30, 50}},     {"mc1b", 11, 3, {0, 200}},
        {"mc1c", 8, 1, {40, 120}},      {"mc1d", 5, 0, {0, 80}},       {"mcpd", 12, 2, {25, 40, 250}},
        {"mcpd2", 10, 3, {20, 100}},
    };
    std::vector<CampaignRingDevice> ring;
    for (const auto& m : mcs) {
      CampaignRingDevice c;
      c.name = m.name;
      set_layout(c.settings, m.supi, m.ibcnf);
      c.settings.bus = rng.chance(0.3) ? interbus::BusKind::local : interbus::BusKind::remote;
      c.phase = rng.between(Duration{0}, kSamplePeriod - Duration{1});
      c.jitter = std::string(m.name) == "mcpd" ? Duration{0} : rng.pick(std::vector<Duration>{0us, 20us, 50us, 100us});
      c.initialised = !rng.chance(0.2);
      c.settings.watchdog_ms = rng.pick(m.butwd);
      ring.push_back(std::move(c));
    }
    return ring;
  }

  [[nodiscard]] CampaignDevice device(const CampaignRingDevice& c, const DeviceEmulator& emulator,
                                      CampaignRandom& rng) const override {
    const Layout& l = servo(emulator).layout();
    const DeviceSettings& s = c.settings;
    CampaignDevice d;
    d.period = kSamplePeriod;
    d.has_channel = l.pcp_words > 0;
    d.has_pd = l.pd_words > 0;
    d.description = "MC6000 SUPI " + std::to_string(supi_of(s)) + " / IBCNF " + std::to_string(ibcnf_of(s)) + ", " +
                    std::to_string(l.pd_words) + " process-data word(s), " +
                    (d.has_channel ? "PCP " + std::to_string(l.pcp_words) + " word(s)" : std::string("no PCP")) +
                    ", " + (s.bus == interbus::BusKind::local ? "local" : "remote") + " bus, 409-BUTWD " +
                    std::to_string(*s.watchdog_ms) + " ms";
    if (!d.has_channel) {
      // Without PCP nobody can change 409-BUTWD: the servo monitors with its configured time.
      d.watchdog_fixed_ms = *s.watchdog_ms;
      return d;
    }
    d.watchdog_parameter = kButwd;
    // INTERBUS manual 3.2.2 / 3.2.3: SUPI 0..12, IBCNF 0..3 (4, LISIM, the project does not support).
    d.layout = {{kSupi, "405-SUPI", supi_of(s), 0, kSupiMax},
                {kIbcnf, "406-IBCNF", ibcnf_of(s), 0, static_cast<int>(Ibcnf::speed_torque)}};
    for (const pcp::ParameterInfo& p : kParameters) {
      CampaignParam m;
      m.number = p.number;
      m.eeprom = p.category == pcp::Category::eeprom;
      m.factory = p.default_value;
      m.initial = p.number == kSupi ? supi_of(s) : p.number == kIbcnf ? ibcnf_of(s) : p.number == kButwd ? *s.watchdog_ms
                                                                                                 : p.default_value;
      m.min = p.min;
      m.max = p.max;
      // The servo saves a written EEPROM value at 15 ms a byte (docs/pcp.md), from its next
      // sample on.
      m.eeprom_save = std::chrono::milliseconds(15) * static_cast<std::int64_t>(pcp::size_of(p.type)) +
                      kSamplePeriod + 2 * c.jitter;
      m.card_writeable = card_writeable(p.number);
      // 15-PLRDY reads the servo's READY mode, which a changed InitControl parameter (300-CFCON)
      // ends and a start, 4-PROG = 1 or an accepted download sets (MC-D11): the servo's, not a
      // value the oracle models. Neither it nor an InitControl parameter is written at random, so
      // that the servos stay engageable for the state commands.
      m.role = !p.writable() || p.number == kPlrdy ? CampaignRole::device_owned
               : p.number == kProg     ? CampaignRole::command
               : p.number == kSload    ? CampaignRole::download
                                       : CampaignRole::normal;
      d.params.push_back(m);
      d.readable.push_back(p.number);
      // 405/406 are written only by the layout script (CampaignDevice::layout). The error
      // reactions 510..512 (MC-D7) keep their factory STOP: the campaign's outages trip the bus
      // watchdog, and its oracle expects the reset of 5.1.2 to end that fault, which LOCK and RESET
      // do not (a power-on, a boot).
      if (m.role != CampaignRole::normal || p.number == kSupi || p.number == kIbcnf || p.number == kReop1 ||
          p.number == kResio || p.number == kRedev || (p.attributes & pcp::kAttrInitControl) != 0) {
        continue;
      }
      CampaignWrites w;
      w.number = p.number;
      w.in_range = {p.default_value, p.min, p.max};
      for (int k = 0; k < 3; ++k) add(w.in_range, rng.uniform(p.min, p.max));
      // Watchdog times the campaign's outages (550 ms) always exceed.
      if (p.number == kButwd) w.in_range = {0, 40, 100, 250, m.initial};
      // 81-SBAUD takes the rates of the LUSTBUS manual 4 in baud (LB-E18), no number between them.
      if (p.number == kParamSbaud) w.in_range = {2400, 4800, 9600, 19200, 38400, 57600};
      for (const std::int64_t v : {p.min - 1, p.max + 1}) w.out_of_range.push_back(v);
      d.writes.push_back(std::move(w));
    }
    return d;
  }

  [[nodiscard]] std::int64_t watchdog_ms(std::int64_t raw) const override { return raw; }

  [[nodiscard]] Duration request_timeout(ParamOp op, std::uint16_t number, std::int64_t value) const override {
    // An Initiate and the request itself, each with the PCP client's timeout; a write of
    // 4-PROG = 1 waits for the factory defaults (LUSTBUS manual 10: up to 10 s).
    const bool factory_defaults = op == ParamOp::write && number == kProg && value == kProgFactoryDefaults;
    return kPcpTimeout + (factory_defaults ? Mc6000Driver::kFactoryDefaultsTimeout : kPcpTimeout);
  }

  [[nodiscard]] double describe_share() const override { return 0.06; }

  [[nodiscard]] std::pair<std::int64_t, std::int64_t> reference_range() const override { return {-3000, 3000}; }

  [[nodiscard]] std::optional<CampaignFactoryDefaults> factory_defaults() const override {
    // 4-PROG: 1 loads the factory defaults (LUSTBUS manual 10); 111 activates a baud rate (11.5).
    return CampaignFactoryDefaults{kProg, "4-PROG", {0, kProgActivateBaudrate}, 0.3};
  }

  [[nodiscard]] std::optional<CampaignDownload> download() const override {
    // LUSTBUS manual 11.4; the dataset check after SLOAD = -2 takes the drive's time on every bus
    // (docs/errata.md MC-D2).
    return CampaignDownload{kSload, "80-SLOAD", DriveTiming{}.download_check, "LUSTBUS manual 11.4: secured until it ends"};
  }

  // A refused PCP write sets 85-SERR, which refuses every further write until it is read
  // (LUSTBUS manual 9.2); a power-on sets its power-on bit.
  [[nodiscard]] std::optional<std::uint16_t> write_error_register() const override { return kSerr; }

  [[nodiscard]] bool layout_mismatch(const DeviceEmulator& emulator) const override {
    return servo(emulator).configuration_mismatch();
  }

  void read_store(const DeviceEmulator& emulator, std::vector<CampaignStoreEntry>& out) const override {
    const Mc6000Device& d = servo(emulator);
    if (d.pcp() == nullptr) return;
    const pcp::ParameterStore& ps = d.drive().store();
    for (const pcp::ParameterInfo& p : kParameters) {
      const auto v = ps.get(p.number);
      const auto e = ps.eeprom(p.number);
      CampaignStoreEntry entry{p.number, v ? pcp::signed_raw(*v) : 0, std::nullopt};
      if (e) entry.eeprom = pcp::signed_raw(*e);
      out.push_back(entry);
    }
  }

  void restore_layout(DeviceEmulator& emulator, const CampaignRingDevice& c) const override {
    // At the keypad: 405/406 back to the ring's configuration, in RAM and EEPROM.
    DriveParameters& ps = dynamic_cast<Mc6000Device&>(emulator).drive().parameters();
    for (const auto& [number, v] : {std::pair<std::uint16_t, int>{kSupi, supi_of(c.settings)}, {kIbcnf, ibcnf_of(c.settings)}}) {
      ps.preset(number, v);
    }
  }
};

}  // namespace

const CampaignProfile& campaign_profile() {
  static const Profile p;
  return p;
}

}  // namespace ibs::devices::mc6000
