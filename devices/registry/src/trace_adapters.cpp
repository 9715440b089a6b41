#include "ibs/devices/trace_adapters.hpp"

#include <algorithm>
#include <charconv>
#include <optional>
#include <stdexcept>
#include <vector>
#include <string>

#include "ibs/base/time_text.hpp"
#include "ibs/devices/registry.hpp"
#include "ibs/drivecom/sequencer.hpp"

namespace ibs::devices {

namespace {

using trace::Header;
using trace::Request;
using trace::TraceError;
using trace::WordsKind;

// The drive the header names, its target checked: what every adapter starts from.
const DriveKind& kind_of(const trace::Trace& t) {
  const Header& h = t.header;
  const DriveKind* k = find_drive_kind(h.device);
  if (k == nullptr) {
    throw TraceError(t.file, h.lines.device,
                     "device: '" + h.device + "' is not one of " + drive_kind_names(", ", ", "));
  }
  if (h.request && h.request->kind == Request::Kind::state && !drivecom::target_named(h.request->target)) {
    std::string targets;
    for (const std::string_view key : drivecom::kTargetKeys) targets += (targets.empty() ? "" : ", ") + std::string(key);
    throw TraceError(t.file, h.lines.request,
                     "request: state target '" + h.request->target + "' is not one of " + targets);
  }
  return *k;
}

// The header's line a setting was given on; a refused setting is reported there, falling back to
// the other setting's line and then to the device line.
std::size_t line_of(const Header& h, std::string_view setting) {
  if (setting == "watchdog_ms") return h.lines.watchdog_ms;
  if (const trace::DeviceSetting* d = h.device_setting(setting)) return d->line;
  const trace::HeaderSetting* s = h.setting(setting);
  return s != nullptr ? s->line : 0;
}

// The bus watchdog's reaction (DeviceSettings::watchdog_reaction), which every trace may name and
// the drive's wing judges (validate_watchdog).
constexpr std::string_view kWatchdogReaction = "watchdog_reaction";

// A declared setting with a trace header of its own (`# supi: 11`, registry.cpp's vocabulary):
// the integers that place a device on the ring.
bool own_header(const SettingSpec& spec) {
  return spec.kind == SettingKind::integer && uses(spec.faces, SettingFace::interbus);
}

// A setting's value in the scenario's syntax (without quotes), and back.
std::string setting_text(const SettingSpec& spec, std::int64_t v) {
  switch (spec.kind) {
    case SettingKind::integer: return std::to_string(v);
    case SettingKind::boolean: return v != 0 ? "true" : "false";
    case SettingKind::duration: return format_time(Duration{v});
    case SettingKind::choice:
      if (v >= 0 && static_cast<std::size_t>(v) < spec.choices.size()) return std::string(spec.choices[static_cast<std::size_t>(v)]);
      return std::to_string(v);
  }
  return std::to_string(v);
}

std::optional<std::int64_t> parse_whole(std::string_view text) {
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return v;
}

// Reads `setting: NAME VALUE`'s value by the declaration's type; throws TraceError on its line.
std::int64_t setting_value(const trace::Trace& t, const trace::DeviceSetting& d, const SettingSpec& spec) {
  const auto refuse = [&](const std::string& expected) -> std::int64_t {
    throw TraceError(t.file, d.line, "setting: " + d.name + ": '" + d.value + "' is not " + expected);
  };
  switch (spec.kind) {
    case SettingKind::integer:
      if (const auto v = parse_whole(d.value)) return *v;
      return refuse("an integer (" + std::string(spec.range) + ")");
    case SettingKind::boolean:
      if (d.value == "true" || d.value == "false") return d.value == "true" ? 1 : 0;
      return refuse("true or false");
    case SettingKind::duration:
      try {
        return parse_time(d.value).count();
      } catch (const std::invalid_argument& e) {
        return refuse(std::string("a time (") + e.what() + ")");
      }
    case SettingKind::choice:
      for (std::size_t i = 0; i < spec.choices.size(); ++i) {
        if (spec.choices[i] == d.value) return static_cast<std::int64_t>(i);
      }
      return refuse("one of its choices");
  }
  return refuse("a value of its type");
}

// The settings the header gives the device: the wing's own with their own headers (supi, ibcnf),
// the bus watchdog every drive has (`watchdog_ms`; its range and "off" are the wing's,
// validate_watchdog) and the `setting:` headers (the watchdog's reaction, the drive's other
// declared settings). A name the drive does not take is refused on its line here; a value out
// of its range by the checks of configuration_of.
DeviceSettings settings_of(const trace::Trace& t, const DriveKind& k) {
  DeviceSettings s = k->trace_settings(t.header);
  s.watchdog_ms = t.header.watchdog_ms;
  for (const trace::DeviceSetting& d : t.header.device_settings) {
    if (d.name == kWatchdogReaction) {
      const auto v = parse_whole(d.value);
      if (!v || *v < 0 || *v > 255) {
        throw TraceError(t.file, d.line, "setting: watchdog_reaction: '" + d.value + "' is not an integer 0..255");
      }
      s.watchdog_reaction = static_cast<int>(*v);
      continue;
    }
    if (const auto refusal = refuse_setting_name(k, d.name)) throw TraceError(t.file, d.line, "setting: " + refusal->message);
    const SettingSpec& spec = *k->setting(d.name);
    if (own_header(spec)) {
      throw TraceError(t.file, d.line, "setting: '" + d.name + "' has a header of its own: `# " + d.name + ": " + d.value + "`");
    }
    s.drive.set(spec.name, spec.kind, setting_value(t, d, spec));
  }
  return s;
}

Configuration configuration_of(const trace::Trace& t, const DriveKind& k) {
  const Header& h = t.header;
  // A setting the kind does not declare, on its line (a VF1000 has no 405-SUPI, INTERBUS manual 3.1.2).
  for (const trace::HeaderSetting& s : h.settings) {
    if (const auto refusal = refuse_setting_name(k, s.key)) {
      throw TraceError(t.file, s.line != 0 ? s.line : h.lines.device, refusal->message);
    }
  }
  try {
    const DeviceSettings settings = settings_of(t, k);
    k->check_watchdog(settings);
    Configuration c = k->configure(settings);
    // What the wing's own checks leave, against its declarations.
    ibs::detail::require<SettingsError>(check_settings(k, settings.drive));
    return c;
  } catch (const SettingsError& e) {
    const std::size_t first = line_of(h, e.setting());
    const std::size_t second = line_of(h, e.fallback());
    throw TraceError(t.file, first != 0 ? first : (second != 0 ? second : h.lines.device), e.what());
  }
}

void require_state_request(const trace::Trace& t) {
  const Header& h = t.header;
  if (h.request && h.request->kind != Request::Kind::state) {
    throw TraceError(t.file, h.lines.request,
                     "request: '" + to_string(*h.request) +
                         "' is a parameter request; a words: pd trace takes 'state TARGET' "
                         "(parameter requests go in words: comm or words: pcp traces)");
  }
}

// A device as the simulator runs it, one sample per row, `step-time` apart (by default its own
// sample period): a row is a sample after a valid bus cycle, which feeds the bus watchdog; a step
// of `! no-data N` is a sample without one, with the words the device last took -- what the
// simulator does for a corrupted cycle or a lost device (sim/simulator_cycle.cpp: no
// bus_cycle(), the master's words not copied). Recorded simulator traces replay unchanged.
class EmulatedDeviceSide final : public trace::DeviceSide {
 public:
  EmulatedDeviceSide(std::string file, std::size_t words, Duration period, std::unique_ptr<DeviceEmulator> device)
      : file_(std::move(file)), words_(words), period_(period), device_(std::move(device)), taken_(words, Word{0}) {}
  std::size_t m2s_words() const override { return words_; }
  std::size_t s2m_words() const override { return words_; }
  void initial(std::span<Word> s2m) override { device_->output(s2m); }
  void step(std::span<const Word> m2s, std::span<Word> s2m) override {
    now_ += period_;
    std::copy(m2s.begin(), m2s.end(), taken_.begin());
    device_->bus_cycle(now_);
    device_->sample({taken_, s2m, {}, {}}, now_);
  }
  void step_without_data(std::span<Word> s2m) override {
    now_ += period_;
    device_->sample({taken_, s2m, {}, {}}, now_);
  }
  // The device faults a recording injects, the steps without data and the parameters another
  // channel wrote (trace-format.md, "Events"); a write the drive refuses is an error on its line.
  bool supports(trace::Event::Kind) const override { return true; }
  void apply(const trace::Event& e) override {
    if (e.kind == trace::Event::Kind::no_data) return;  // replay_device runs step_without_data()
    if (e.kind == trace::Event::Kind::write) {
      const std::string why = device_->write_parameter(e.parameter, e.value, now_);
      if (!why.empty()) {
        throw TraceError(file_, e.line, "write " + std::to_string(e.parameter) + " " + std::to_string(e.value) + ": " + why);
      }
      return;
    }
    device_->set_fault(e.kind == trace::Event::Kind::fault);
  }

 private:
  std::string file_;
  std::size_t words_;
  Duration period_;
  std::unique_ptr<DeviceEmulator> device_;
  std::vector<Word> taken_;  // the master's words as the last valid step delivered them
  Time now_{0};
};

// The drive's parameter channel, if the header's words are its.
bool is_channel(const Header& h, const DriveKind& k) { return k->facts().channel_words == h.words; }

[[noreturn]] void unsupported(const trace::Trace& t) {
  const Header& h = t.header;
  std::string why;
  for (const DriveKind& other : drive_kinds()) {
    if (other->name() != h.device && other->facts().channel_words == h.words) {
      why = " (" + std::string(other->facts().channel_name) + " is the " + std::string(other->facts().title) + "'s)";
      break;
    }
  }
  throw TraceError(t.file, h.lines.words,
                   "words: " + std::string(to_string(h.words)) + " is not served for device " + h.device + why);
}

// The channel adapters report a header they cannot serve with std::invalid_argument; the user
// gets it as FILE:LINE naming the request (or the words header).
template <typename F>
auto channel_adapter(const trace::Trace& t, F make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    const auto& l = t.header.lines;
    throw TraceError(t.file, l.request != 0 ? l.request : l.words, e.what());
  }
}

// The rows' word counts against what the trace's kind exchanges.
void check_counts(const trace::Trace& t, std::size_t m2s_words, std::size_t s2m_words) {
  for (const trace::Row& r : t.rows) {
    if (r.gap) continue;
    if (r.m2s.size() != m2s_words || r.s2m.size() != s2m_words) {
      throw TraceError(t.file, r.line,
                       "this " + t.header.device + " with words: " + std::string(to_string(t.header.words)) +
                           " exchanges " + std::to_string(m2s_words) + " m2s and " + std::to_string(s2m_words) +
                           " s2m words per row; the row has " + std::to_string(r.m2s.size()) + " and " +
                           std::to_string(r.s2m.size()));
    }
  }
}

// The step time of the device's model without a `step-time` header: one sample of its period.
Duration pd_step(const trace::Trace& t, const DriveKind& k) {
  return t.header.step_time.value_or(k->facts().sample_period);
}

}  // namespace

void validate_trace(const trace::Trace& t) {
  const Header& h = t.header;
  // The header's own lines first (drive, target, settings, request), then what ties it to the
  // rows (request-at, outcome; trace::validate) and the rows themselves.
  const DriveKind& k = kind_of(t);
  if (h.words == WordsKind::pd) {
    const Configuration c = configuration_of(t, k);
    require_state_request(t);
    trace::validate(t);
    // The device model acts on every event (trace-format.md, "Events"); a write must suit the
    // drive's table (its state at that step the replay judges).
    for (const trace::Row& r : t.rows) {
      for (const trace::Event& ev : r.events_before) {
        if (ev.kind != trace::Event::Kind::write) continue;
        if (const auto why = k->check_trace_write(ev.parameter, ev.value)) throw TraceError(t.file, ev.line, "write: " + *why);
      }
    }
    check_counts(t, c.pd_words, c.pd_words);
    return;
  }
  if (!is_channel(h, k)) unsupported(t);
  channel_adapter(t, [&] {
    k->check_channel_trace(h);
    return 0;
  });
  // The emulated side of a channel trace is the parameter channel alone: no drive to fault, no
  // bus watchdog to set or to run out.
  if (h.watchdog_ms) {
    throw TraceError(t.file, h.lines.watchdog_ms,
                     "watchdog_ms: a words: " + std::string(to_string(h.words)) +
                         " trace emulates the parameter channel alone, which has no bus watchdog; the "
                         "watchdog belongs to words: pd traces");
  }
  for (const trace::Row& r : t.rows) {
    for (const trace::Event& ev : r.events_before) {
      throw TraceError(t.file, ev.line,
                       "event '" + std::string(to_string(ev.kind)) + "': the emulated " + h.device +
                           " with words: " + std::string(to_string(h.words)) +
                           " is its parameter channel alone and cannot act on it (events go in words: pd traces)");
    }
  }
  trace::validate(t);
  const auto explainer = k->make_channel_explainer(h);
  check_counts(t, explainer->m2s_words(), explainer->s2m_words());
}

std::unique_ptr<trace::DeviceSide> make_device_side(const trace::Trace& t) {
  validate_trace(t);
  const Header& h = t.header;
  const DriveKind& k = kind_of(t);
  if (h.words == WordsKind::pd) {
    const Configuration c = configuration_of(t, k);
    return std::make_unique<EmulatedDeviceSide>(t.file, c.pd_words, pd_step(t, k), k.make_emulator(c, h.init, Time{0}));
  }
  return channel_adapter(t, [&] { return k->make_channel_device(h); });
}

std::unique_ptr<trace::MasterSide> make_master_side(const trace::Trace& t) {
  validate_trace(t);
  const Header& h = t.header;
  const DriveKind& k = kind_of(t);
  if (h.words == WordsKind::pd) return k->make_pd_master(configuration_of(t, k), pd_step(t, k));
  return channel_adapter(t, [&] { return k->make_channel_master(h); });
}

std::unique_ptr<trace::Explainer> make_explainer(const trace::Trace& t) {
  validate_trace(t);
  const Header& h = t.header;
  const DriveKind& k = kind_of(t);
  if (h.words == WordsKind::pd) return k->make_pd_explainer(configuration_of(t, k));
  return channel_adapter(t, [&] { return k->make_channel_explainer(h); });
}

void write_device_settings(const DriveKind& kind, const DeviceSettings& settings, trace::Header& h) {
  if (settings.watchdog_reaction) h.set_device_setting(kWatchdogReaction, std::to_string(*settings.watchdog_reaction));
  for (const SettingSpec& spec : kind->settings()) {
    if (own_header(spec) || !settings.drive.given(spec.name)) continue;
    const std::int64_t v = settings.drive.value(spec);
    if (v != spec.fallback) h.set_device_setting(spec.name, setting_text(spec, v));
  }
}

trace::Trace parse_trace(std::string_view text, const std::string& file) {
  return trace::parse(text, file, trace_vocabulary());
}

trace::Trace load_trace(const std::string& path) { return trace::load(path, trace_vocabulary()); }

}  // namespace ibs::devices
