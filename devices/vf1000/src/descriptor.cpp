#include "ibs/devices/vf1000/descriptor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "ibs/devices/vf1000/channel.hpp"
#include "ibs/devices/vf1000/driver.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/devices/vf1000/settings.hpp"
#include "ibs/drivecom/control_word.hpp"
#include "ibs/vf1000_channel/comm_word.hpp"

#if !IBS_EMBEDDED
#include "ibs/devices/vf1000/pd_trace.hpp"
#include "ibs/vf1000_channel/trace_adapters.hpp"
#endif

namespace ibs::devices::vf1000 {

std::string explain_control_word(Word control, Word previous) {
  std::string s = drivecom::explain_control_word(control, previous);
  const auto b = decode_control_bits(control);
  if (!b.ramp_enable) s += ", ramp disabled (stop function)";
  if (b.ramp_enable && !b.ramp_run) s += ", ramp held";
  if (b.ramp_enable && !b.ramp_follow) s += ", ramp to 0 Hz";
  if (b.s2ind) s += ", S2IND";
  if (b.s1ind) s += ", S1IND";
  if (b.stl) s += ", STL";
  if (b.str) s += ", STR";
  if (bit(control, 11)) s += ", bit 11 (unoccupied) set";
  return s;
}

std::string explain_status_word(Word status) { return drivecom::explain_status_word(status, kStatusBits); }

namespace {

// 906-IB-WD runs 8..65535 ms, the maximum switching monitoring off; 907-IBCOD 0..3 (4.1.1).
constexpr int kMinWatchdogMs = 8;
constexpr int kMaxWatchdogMs = 0xFFFF;
constexpr int kMaxWatchdogReaction = 3;
// The reference word: 0.05 Hz per bit, an absolute value (5.2.3).
constexpr double kMaxFrequencyHz = 65535 * kHzPerBit;

// The inverter's error numbers: INTERBUS manual 4.1.3.3, "valid error codes are 00H-0EH; no error
// corresponds to value 0FH" (LUSTBUS manual 3, PT_VF_ERROR, agrees); the only one the seeds name is 12,
// E-IBS (INTERBUS manual 4.1.1, 907-IBCOD = 1).
constexpr ErrorCause kErrors[] = {{kWatchdogError, "E-IBS"}};

constexpr DriveFacts kFacts{
    .name = kName,
    .title = "VF1000",
    .article = "a",
    .unit = "Hz",
    .sample_period = kSamplePeriod,
    .reference_action = "frequency",
    .reference_min = -kMaxFrequencyHz,
    .reference_max = kMaxFrequencyHz,
    .reference_range = "-3276.75..3276.75 Hz, 0.05 Hz per bit",
    // Parameter numbers: 10 bits, the low byte and bits 0-1 of the control byte (4.1.2.1).
    .max_parameter = vf1000_channel::kMaxParameterNumber,
    .parameter_range = ", 10-bit PNR, INTERBUS manual 4.1.2.1",
    // A parameter is one 16-bit word, written as -32768..65535 (two's complement or unsigned).
    .write_min = -32768.0,
    .write_max = 65535.0,
    .write_range = " (-32768..65535, 16 bits)",
    .watchdog_error = "error 12 (E-IBS): process-data watchdog 906-IB-WD ran out",
    .timing_syntax = kName,
#if !IBS_EMBEDDED
    .channel_words = trace::WordsKind::comm,
#endif
    .channel_name = "the communication word",
    .settings = kSettings,
    .events =
        {
            .min_error = 0,
            .max_error = 14,
            .errors = kErrors,
            .error_source = "INTERBUS manual 4.1.3.3: 00H..0EH",
            // Its terminals (INTERBUS manual 5.2.1, 5.2.2; docs/errata.md VF-E22): the inputs, and the
            // outputs S1OUT / S2OUT set to the level their programmed function gives.
            .inputs = kTerminalNames,
            .no_inputs = {},
            .load_unit = {},
            .no_load = "the VF1000 is an inverter without a motor model here: its frequency follows the ramp, "
                       "whatever the load (docs/errata.md VF-E17)",
            // LUSTBUS manual 10 exception 2: "up to 10 seconds, depending on the device".
            .card_max_s = 10.0,
            .card_source = "LUSTBUS manual 10 exception 2, INTERBUS manual 6.1",
            .no_card = {},
            .option_card = {},
            .option_source = {},
            .no_option = "its INTERBUS operation is a modified software package, not a card it detects (INTERBUS manual "
                         "3.1.1); no seed gives a withdrawal an effect",
        },
};

SettingsRefusal refuse(ErrorCode code, std::string message, std::string_view setting) {
  return {{code, std::move(message)}, setting};
}

class Descriptor final : public DriveDescriptor {
 public:
  Descriptor() : DriveDescriptor(kFacts) {}

  Expected<Configuration, SettingsRefusal> try_configure(const DeviceSettings& s) const override {
    if (s.bus == interbus::BusKind::local) {
      return refuse(ErrorCode::setting_bus_refused,
                    "a VF1000 is always a remote bus device (INTERBUS manual 1.3)", "bus");
    }
    return Configuration{s, interbus::IdCode{kIdCode}, interbus::BusKind::remote, true, kWords, 0};
  }

  SettingsRefusal validate_watchdog(const DeviceSettings& s) const override {
    if (s.watchdog_ms && (*s.watchdog_ms < kMinWatchdogMs || *s.watchdog_ms > kMaxWatchdogMs)) {
      return refuse(ErrorCode::setting_out_of_range,
                    "'watchdog_ms' = " + std::to_string(*s.watchdog_ms) + " is out of range (" +
                        std::to_string(kMinWatchdogMs) + ".." + std::to_string(kMaxWatchdogMs) +
                        ", 906-IB-WD)",
                    "watchdog_ms");
    }
    if (s.watchdog_reaction && (*s.watchdog_reaction < 0 || *s.watchdog_reaction > kMaxWatchdogReaction)) {
      return refuse(ErrorCode::setting_out_of_range,
                    "'watchdog_reaction' = " + std::to_string(*s.watchdog_reaction) +
                        " is out of range (0..3, 907-IBCOD)",
                    "watchdog_reaction");
    }
    if (s.drive.given(kResetTimeSetting.name)) {
      const Duration reset = s.drive.duration(kResetTimeSetting);
      if (reset < Duration{kResetTimeSetting.min} || reset > Duration{kResetTimeSetting.max}) {
        return refuse(ErrorCode::setting_out_of_range,
                      "'" + std::string(kResetTimeSetting.name) + "' must be " +
                          std::string(kResetTimeSetting.range) + " (the self-test after RESET FAULT)",
                      kResetTimeSetting.name);
      }
    }
    return {};
  }

  std::optional<std::string> lacks(Capability, const Configuration&) const override { return std::nullopt; }

  std::unique_ptr<DeviceDriver> make_driver(const Configuration&) const override {
    return std::make_unique<Vf1000Driver>();
  }
  std::string explain_control(Word control, Word previous) const override {
    return explain_control_word(control, previous);
  }
  std::string explain_status(Word status) const override { return explain_status_word(status); }

#if !IBS_EMBEDDED
  DeviceSettings trace_settings(const trace::Header&) const override { return {}; }
  void write_trace_settings(const Configuration&, trace::Header&) const override {}
  std::unique_ptr<trace::MasterSide> make_pd_master(const Configuration&, Duration step) const override {
    return vf1000::make_pd_master(step);
  }
  std::unique_ptr<trace::Explainer> make_pd_explainer(const Configuration&) const override {
    return vf1000::make_pd_explainer();
  }
  void check_channel_trace(const trace::Header& h) const override { vf1000_channel::check_comm_trace(h); }
  std::unique_ptr<trace::DeviceSide> make_channel_device(const trace::Header& h) const override {
    return vf1000_channel::make_comm_device_side(h, parameters(), server_config());
  }
  std::unique_ptr<trace::MasterSide> make_channel_master(const trace::Header& h) const override {
    return vf1000_channel::make_comm_master_side(h);
  }
  std::unique_ptr<trace::Explainer> make_channel_explainer(const trace::Header&) const override {
    return vf1000_channel::make_comm_explainer();
  }
  std::optional<std::string> check_trace_write(std::uint16_t number, std::int64_t value) const override {
    const auto table = parameters();
    const auto p = std::find_if(table.begin(), table.end(), [number](const drive::ParameterInfo& i) { return i.number == number; });
    if (p == table.end()) return "parameter " + std::to_string(number) + " is not in the VF1000's table";
    if (value < 0 || value > (number == pnr::kSiof ? 0xFF : 0xFFFF)) {
      return std::to_string(number) + "-" + std::string(p->name) + ": " + std::to_string(value) + " is not a value of it (" +
             (number == pnr::kSiof ? "8 bits" : "a 16-bit word") + ")";
    }
    if (number == pnr::kSiof) return std::nullopt;  // the bits a channel's requests left
    const drive::WriteCheck c = drive::check_write(&*p, static_cast<Word>(value), false);
    if (c == drive::WriteCheck::ok) return std::nullopt;
    return std::to_string(number) + "-" + std::string(p->name) + " = " + std::to_string(value) + ": " +
           std::string(drive::to_string(c));
  }
#endif

  std::optional<std::string> check_layout_options(const SettingValues& given, bool bus) const override {
    if (given.empty() && !bus) return std::nullopt;
    return "--supi, --ibcnf and --bus apply to the mc6000 only; the VF1000 always reports 33BH on the "
           "remote bus (INTERBUS manual 3.1.2)";
  }

  LayoutDescription layout(const Configuration&) const override {
    LayoutDescription r;
    r.title = "VF1000 frequency inverter: three words, ID code 33BH (INTERBUS manual 3.1.2)";
    r.out_words = {
        {1, "control_word", "control word, DRIVECOM Profile 20 (INTERBUS manual 5.2.1)"},
        {2, "frequency_reference",
         "frequency reference, 0.05 Hz per bit, absolute value; the direction comes from control "
         "word bits 14 STL / 15 STR (INTERBUS manual 5.2.3)"},
        {3, "communication_word",
         "communication word to the inverter: the parameter channel (INTERBUS manual 4.1.2.1)"},
    };
    r.in_words = {
        {1, "status_word", "status word, DRIVECOM Profile 20 (INTERBUS manual 5.2.2)"},
        {2, "actual_frequency",
         "actual frequency, 0.05 Hz per bit, signed (modelling choice: the manual does not define "
         "this word)"},
        {3, "communication_word", "communication word from the inverter (INTERBUS manual 4.1.2.2)"},
    };
    r.pcp = "none: parameters travel in the communication word (word 3)";
    return r;
  }

  Expected<RingEntry, SettingsRefusal> try_ring_entry(
      std::span<const std::string_view> fields) const override {
    if (!fields.empty()) {
      return refuse(ErrorCode::setting_too_many_fields,
                    "the VF1000 takes no settings (it always reports 33BH, 3 words on the remote "
                    "bus, INTERBUS manual 3.1.2)",
                    "");
    }
    return RingEntry{interbus::IdCode{kIdCode}, interbus::BusKind::remote, {}, ""};
  }
  std::string ring_spec(const DeviceSettings&) const override { return std::string(kName); }
};

}  // namespace

const DriveDescriptor& descriptor() {
  static const Descriptor d;
  return d;
}

}  // namespace ibs::devices::vf1000
