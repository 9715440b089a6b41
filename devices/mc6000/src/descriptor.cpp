#include "ibs/devices/mc6000/descriptor.hpp"

#include <algorithm>
#include <charconv>

#include "ibs/devices/mc6000/driver.hpp"
#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/settings.hpp"
#include "ibs/drivecom/control_word.hpp"
#include "ibs/pcp/parameter_store.hpp"
#include "ibs/pcp/parameters.hpp"

#if !IBS_EMBEDDED
#include "ibs/devices/mc6000/pcp_trace.hpp"
#include "ibs/devices/mc6000/pd_trace.hpp"
#endif

namespace ibs::devices::mc6000 {

std::string explain_control_word(Word control, Word previous) {
  std::string s = drivecom::explain_control_word(control, previous);
  const auto b = decode_control_bits(control);
  if (b.os00) s += ", OS00";
  if (b.os01) s += ", OS01";
  if ((control & kControlBitsWithoutFunction) != 0) s += ", bits without function set";
  return s;
}

std::string explain_status_word(Word status) { return drivecom::explain_status_word(status, kStatusBits); }

namespace {

// 409-BUTWD in ms, 0 = off (3.2.4), an Unsigned 16.
constexpr int kMaxWatchdogMs = 0xFFFF;

// The servo's error numbers: one byte (LUSTBUS manual 3, PT_MC_ERROR: "Error number 1 Byte"); the one
// the seeds name is 16, E-OP1 (INTERBUS manual 3.2.4). Its inputs IS00 and IS01 (INTERBUS manual 5.3.2) and a
// load torque on its plant (plant.hpp, Nm).
constexpr ErrorCause kErrors[] = {{kWatchdogError, "E-OP1"}};
constexpr std::string_view kInputs[] = {"IS00", "IS01"};

constexpr DriveFacts kFacts{
    .name = kName,
    .title = "MC6000",
    .article = "an",
    .unit = "rpm",
    .sample_period = kSamplePeriod,
    // The reference: rpm, a signed 16-bit word or Q16 in 32 bits (3.2.3, 5.3.4).
    .reference_action = "speed",
    .reference_min = -32768.0,
    .reference_max = 32767.0,
    .reference_range = "-32768..32767 rpm",
    // Parameter numbers: 0..999 (LUSTBUS manual 2.4.2); PCP index = number + 5C00H (INTERBUS manual 4.2).
    .max_parameter = pcp::kMaxParameterNumber,
    .parameter_range = ", LUSTBUS manual 2.4.2",
    // A PCP value is up to 32 bits, written as a signed or unsigned number.
    .write_min = -2147483648.0,
    .write_max = 4294967295.0,
    .write_range = " (-2^31..2^32-1, 32 bits)",
    .watchdog_error = "error 16 (E-OP1), location 1: bus watchdog 409-BUTWD ran out",
    .timing_syntax = "mc6000:SUPI[:local|remote]",
#if !IBS_EMBEDDED
    .channel_words = trace::WordsKind::pcp,
#endif
    .channel_name = "PCP",
    .settings = kSettings,
    .events =
        {
            .min_error = 0,
            .max_error = 255,
            .errors = kErrors,
            .error_source = "LUSTBUS manual 3: one byte",
            .inputs = kInputs,
            .no_inputs = {},
            .load_unit = "Nm",
            .no_load = {},
            // LUSTBUS manual 10 exception 2: "up to 10 seconds, depending on the device" (MC-D9).
            .card_max_s = 10.0,
            .card_source = "LUSTBUS manual 10 exception 2",
            .no_card = {},
            // INTERBUS manual 3.2.1: its factory defaults back at the next power-up (MC-D10).
            .option_card = "INTERBUS card",
            .option_source = "INTERBUS manual 3.2.1",
            .no_option = {},
        },
};

// The layout of the settings; the refusal names 405-SUPI or 406-IBCNF (the other as fallback).
Expected<Layout, SettingsRefusal> try_layout_of(const DeviceSettings& s) {
  const int supi = supi_of(s);
  Expected<Layout> l = try_make_layout(supi, ibcnf_of(s), s.bus);
  if (l) return std::move(l).value();
  // 405-SUPI is checked first (try_make_layout): only its own range makes a refusal about it.
  const bool about_supi = l.error().code == ErrorCode::layout_setting_out_of_range &&
                          (supi < 0 || supi > kSupiMax);
  const std::string_view first = about_supi ? kSupiSetting.name : kIbcnfSetting.name;
  return SettingsRefusal(l.error(), first, about_supi ? kIbcnfSetting.name : kSupiSetting.name);
}

// The layout of a configuration try_configure gave: other settings throw SettingsError or, in the
// embedded build, abort.
Layout layout_of(const DeviceSettings& s) {
  Expected<Layout, SettingsRefusal> l = try_layout_of(s);
#if IBS_EXCEPTIONS
  detail::require<SettingsError>(l.error());
#else
  if (!l) detail::abort_with(l.error());
#endif
  return std::move(l).value();
}

SettingsRefusal refuse(ErrorCode code, std::string message, std::string_view setting) {
  return {{code, std::move(message)}, setting};
}

const char* ibcnf_meaning(Ibcnf c) {
  switch (c) {
    case Ibcnf::none:
      return "no reference transfer, all actual words 0";
    case Ibcnf::word16:
      return "16-bit reference and actual";
    case Ibcnf::q16:
      return "32-bit Q16 reference and actual, high word first";
    case Ibcnf::speed_torque:
      return "32-bit Q16 speed reference; actual 16-bit speed and 16-bit torque";
    case Ibcnf::lisim:
      return "modified LISIM software";
  }
  return "?";
}

const char* bus_name(interbus::BusKind b) { return b == interbus::BusKind::local ? "local" : "remote"; }

class Descriptor final : public DriveDescriptor {
 public:
  Descriptor() : DriveDescriptor(kFacts) {}

  Expected<Configuration, SettingsRefusal> try_configure(const DeviceSettings& s) const override {
    Expected<Layout, SettingsRefusal> layout = try_layout_of(s);
    if (!layout) return layout.error();
    const Layout& l = layout.value();
    return Configuration{s,
                         interbus::IdCode{l.id_code},
                         s.bus,
                         l.exchanges_data,
                         static_cast<std::size_t>(l.pd_words),
                         static_cast<std::size_t>(l.pcp_words)};
  }

  SettingsRefusal validate_watchdog(const DeviceSettings& s) const override {
    if (s.watchdog_ms && (*s.watchdog_ms < 0 || *s.watchdog_ms > kMaxWatchdogMs)) {
      return refuse(ErrorCode::setting_out_of_range,
                    "'watchdog_ms' = " + std::to_string(*s.watchdog_ms) + " is out of range (0.." +
                        std::to_string(kMaxWatchdogMs) + ", 409-BUTWD, 0 = off)",
                    "watchdog_ms");
    }
    if (s.watchdog_reaction) {
      return refuse(
          ErrorCode::setting_of_another_drive,
          "'watchdog_reaction' is a VF1000 setting (907-IBCOD); the MC6000 always reports E-OP1 "
          "(INTERBUS manual 3.2.4)",
          "watchdog_reaction");
    }
    return {};
  }

  std::optional<std::string> lacks(Capability c, const Configuration& config) const override {
    const Layout l = layout_of(config.settings);
    const std::string supi = " (405-SUPI " + std::to_string(l.supi);
    switch (c) {
      case Capability::control_word:
        if (l.exchanges_data && l.pd_words >= 1) return std::nullopt;
        return "has no control word" + supi + (l.exchanges_data ? ": PCP only)" : ": no data exchange)");
      case Capability::parameter_channel:
        if (l.pcp_words > 0) return std::nullopt;
        return "has no PCP channel" + supi + ")";
      case Capability::reference:
        if (l.exchanges_data && l.reference_words > 0) return std::nullopt;
        return "carries no speed reference (406-IBCNF " + std::to_string(static_cast<int>(l.ibcnf)) +
               ", 405-SUPI " + std::to_string(l.supi) + ")";
    }
    return std::nullopt;
  }

  std::unique_ptr<DeviceDriver> make_driver(const Configuration& config) const override {
    return std::make_unique<Mc6000Driver>(layout_of(config.settings));
  }
  std::string explain_control(Word control, Word previous) const override {
    return explain_control_word(control, previous);
  }
  std::string explain_status(Word status) const override { return explain_status_word(status); }

#if !IBS_EMBEDDED
  DeviceSettings trace_settings(const trace::Header& h) const override {
    DeviceSettings s;
    for (const SettingSpec& spec : kSettings) {
      if (const trace::HeaderSetting* given = h.setting(spec.name)) s.drive.set_integer(spec.name, given->value);
    }
    return s;
  }
  void write_trace_settings(const Configuration& config, trace::Header& h) const override {
    for (const SettingSpec& spec : kSettings) h.set_setting(spec.name, config.settings.drive.integer(spec));
  }
  std::unique_ptr<trace::MasterSide> make_pd_master(const Configuration& config, Duration step) const override {
    return mc6000::make_pd_master(layout_of(config.settings), step);
  }
  std::unique_ptr<trace::Explainer> make_pd_explainer(const Configuration& config) const override {
    return mc6000::make_pd_explainer(layout_of(config.settings));
  }
  void check_channel_trace(const trace::Header& h) const override { check_pcp_trace(h); }
  std::unique_ptr<trace::DeviceSide> make_channel_device(const trace::Header& h) const override {
    return make_pcp_device_side(h);
  }
  std::unique_ptr<trace::MasterSide> make_channel_master(const trace::Header& h) const override {
    return make_pcp_master_side(h);
  }
  std::unique_ptr<trace::Explainer> make_channel_explainer(const trace::Header& h) const override {
    return make_pcp_explainer(h);
  }
  std::optional<std::string> check_trace_write(std::uint16_t number, std::int64_t value) const override;
#endif

  std::optional<std::string> check_layout_options(const SettingValues& given, bool) const override {
    // Both layout settings, as the servo reads both at power-on (3.2.2, 3.2.3).
    std::string needs;
    bool missing = false;
    for (const SettingSpec& spec : kSettings) {
      missing = missing || !given.given(spec.name);
      needs += std::string(needs.empty() ? "" : " and ") + "--" + std::string(spec.name) + " (" +
               std::string(spec.parameter) + ", " + std::string(spec.range) + ")";
    }
    if (!missing) return std::nullopt;
    return std::string(kName) + " needs " + needs;
  }

  LayoutDescription layout(const Configuration& config) const override;
  Expected<RingEntry, SettingsRefusal> try_ring_entry(
      std::span<const std::string_view> fields) const override;
  std::string ring_spec(const DeviceSettings& s) const override {
    return std::string(kName) + ":" + std::to_string(supi_of(s)) + (s.bus == interbus::BusKind::local ? ":local" : "");
  }
};

#if !IBS_EMBEDDED
std::optional<std::string> Descriptor::check_trace_write(std::uint16_t number, std::int64_t value) const {
  const auto table = parameters();
  const auto p = std::find_if(table.begin(), table.end(), [number](const pcp::ParameterInfo& i) { return i.number == number; });
  if (p == table.end()) return "parameter " + std::to_string(number) + " is not in the MC6000's table";
  const std::string name = std::to_string(number) + "-" + std::string(p->name);
  if (number == kSerr) {  // the bits a channel's requests left
    if (value < 0 || value > 0xFF) return name + ": " + std::to_string(value) + " is not a value of it (8 bits)";
    return std::nullopt;
  }
  if (!p->writable()) return name + " is an actual value: no channel writes it";
  const auto v = trace_raw(p->type, value);
  if (!v) return name + ": " + std::to_string(value) + " is no value of its type";
  // 80-SLOAD's handshake values (11.4) lie outside its range of answers.
  if (number != kSload && (pcp::compare(p->type, *v, pcp::ParameterStore::to_raw(*p, p->max)) > 0 ||
                           pcp::compare(p->type, *v, pcp::ParameterStore::to_raw(*p, p->min)) < 0)) {
    return name + " = " + std::to_string(value) + " is out of its range";
  }
  return std::nullopt;
}
#endif

LayoutDescription Descriptor::layout(const Configuration& config) const {
  const Layout l = layout_of(config.settings);
  LayoutDescription r;
  const std::string meaning = ibcnf_meaning(l.ibcnf);
  r.settings = {{std::string(kSupiSetting.name), l.supi, ""},
                {std::string(kIbcnfSetting.name), static_cast<int>(l.ibcnf), ""},
                {std::string(kIbcnfSetting.name) + "_meaning", std::nullopt, meaning}};
  r.exchanges_data = l.exchanges_data;
  r.title = "MC6000 servo: 405-SUPI = " + std::to_string(l.supi) + ", 406-IBCNF = " +
            std::to_string(static_cast<int>(l.ibcnf)) + " (" +
            (l.exchanges_data ? meaning : std::string("no effect without data exchange")) + "), " +
            bus_name(l.bus) + " bus";

  if (!l.exchanges_data) {
    const std::string none =
        "no data exchange: 405-SUPI = 0 reports configuration 4 and the INTERBUS card loops "
        "without exchanging data with the servo (INTERBUS manual 3.2.2)";
    r.out_words.push_back({1, "no_data", none});
    r.in_words.push_back({1, "no_data", none});
    r.pcp = "none (405-SUPI = 0)";
    return r;
  }

  const std::string unit = "torque, speed or position by the control mode (rpm in speed control)";
  const std::string q16 = "as value x 65536, signed 32-bit, high word first (INTERBUS manual 5.3.3, 5.3.4)";
  if (l.pd_words >= 1) {
    r.out_words.push_back({1, "control_word", "control word, DRIVECOM Profile 20 (INTERBUS manual 5.3.1)"});
    r.in_words.push_back({1, "status_word", "status word, DRIVECOM Profile 20 (INTERBUS manual 5.3.2)"});
  }
  switch (l.ibcnf) {
    case Ibcnf::word16:
      r.out_words.push_back({2, "reference",
                             "reference, 16-bit signed, " + unit +
                                 "; integer units (modelling choice: the manual "
                                 "gives no 16-bit scaling)"});
      r.in_words.push_back(
          {2, "actual", "actual value, 16-bit signed, " + unit + "; integer units (modelling choice)"});
      break;
    case Ibcnf::q16:
      r.out_words.push_back({2, "reference_q16_high", "reference, Q16 high word: " + unit + ", " + q16});
      r.out_words.push_back({3, "reference_q16_low", "reference, Q16 low word"});
      r.in_words.push_back({2, "actual_q16_high", "actual value, Q16 high word: " + unit + ", " + q16});
      r.in_words.push_back({3, "actual_q16_low", "actual value, Q16 low word"});
      break;
    case Ibcnf::speed_torque:
      r.out_words.push_back({2, "speed_reference_q16_high",
                             "speed reference, Q16 high word: rpm x 65536, signed 32-bit, high "
                             "word first (INTERBUS manual 3.2.3, 5.3.4)"});
      r.out_words.push_back({3, "speed_reference_q16_low", "speed reference, Q16 low word"});
      r.in_words.push_back({2, "actual_speed", "actual speed, 16-bit signed, rpm (INTERBUS manual 3.2.3)"});
      r.in_words.push_back({3, "actual_torque", "actual torque, 16-bit signed (INTERBUS manual 3.2.3)"});
      break;
    case Ibcnf::none:
    case Ibcnf::lisim:
      break;
  }
  // The process-data words 406-IBCNF leaves without a meaning.
  for (int w = 2 + l.reference_words; w <= l.pd_words; ++w) {
    r.out_words.push_back({w, "unused",
                           l.ibcnf == Ibcnf::none
                               ? "not used (406-IBCNF = 0: no reference transfer)"
                               : "not used by 406-IBCNF = " + std::to_string(static_cast<int>(l.ibcnf))});
  }
  for (int w = 2 + l.actual_words; w <= l.pd_words; ++w) {
    r.in_words.push_back({w, l.ibcnf == Ibcnf::none ? "zero" : "unused",
                          l.ibcnf == Ibcnf::none
                              ? "always 0 (406-IBCNF = 0, INTERBUS manual 3.2.3)"
                              : "not used by 406-IBCNF = " + std::to_string(static_cast<int>(l.ibcnf))});
  }
  r.pcp = l.pcp_words == 0 ? "none"
                           : std::to_string(l.pcp_words) + (l.pcp_words == 1 ? " word" : " words") +
                                 " each way, PCP 2.0 parameter channel (INTERBUS manual 3.2.2)";
  return r;
}

Expected<RingEntry, SettingsRefusal> Descriptor::try_ring_entry(
    std::span<const std::string_view> f) const {
  // SUPI[:local|remote]
  if (f.empty() || f[0].empty()) {
    return refuse(ErrorCode::setting_missing,
                  "the 405-SUPI is missing, expected mc6000:SUPI[:local|remote]", "supi");
  }
  if (f.size() > 2) {
    return refuse(ErrorCode::setting_too_many_fields,
                  "too many fields, expected mc6000:SUPI[:local|remote]", "");
  }
  int supi = -1;
  const auto r = std::from_chars(f[0].data(), f[0].data() + f[0].size(), supi);
  if (r.ec != std::errc{} || r.ptr != f[0].data() + f[0].size()) {
    return refuse(ErrorCode::setting_invalid,
                  "405-SUPI '" + std::string(f[0]) + "' is not a number", "supi");
  }
  if (supi < 0 || supi > kSupiMax) {
    return refuse(ErrorCode::layout_setting_out_of_range,
                  "405-SUPI " + std::to_string(supi) + " is out of range (0..12, INTERBUS manual 3.2.2)",
                  "supi");
  }
  interbus::BusKind bus = interbus::BusKind::remote;
  if (f.size() == 2) {
    if (f[1] == "local") {
      bus = interbus::BusKind::local;
    } else if (f[1] != "remote") {
      return refuse(ErrorCode::setting_invalid,
                    "bus '" + std::string(f[1]) + "' is neither local nor remote", "bus");
    }
  }
  // The ID code follows from 405-SUPI alone (3.2.2); 406-IBCNF changes no word count.
  const SupiRow& row = kSupiTable[static_cast<std::size_t>(supi)];
  RingEntry e;
  e.id_code = interbus::IdCode{bus == interbus::BusKind::local ? row.id_local : row.id_remote};
  e.bus = bus;
  e.settings = {{"supi", supi, ""}};
  if (supi == 0) e.note = "405-SUPI = 0: no data exchange";
  return e;
}

}  // namespace

const DriveDescriptor& descriptor() {
  static const Descriptor d;
  return d;
}

}  // namespace ibs::devices::mc6000
