#include "ibs/devices/registry.hpp"

#include <algorithm>
#include <array>
#include <tuple>
#include <type_traits>

#include "ibs/devices/mc6000/campaign_profile.hpp"
#include "ibs/devices/mc6000/capture.hpp"
#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/vf1000/campaign_profile.hpp"
#include "ibs/devices/vf1000/capture.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/devices/vf1000/device.hpp"
#include "ibs/drivecom/sequencer.hpp"

namespace ibs::devices {

namespace {

// The one list of drive kinds, sorted by name. A new drive adds its line here.
const auto& kinds() {
  static const auto k = std::to_array<DriveKind>({
      {&mc6000::descriptor(), &mc6000::make_emulator, &mc6000::campaign_profile(), &mc6000::capture_face()},
      {&vf1000::descriptor(), &vf1000::make_emulator, &vf1000::campaign_profile(), &vf1000::capture_face()},
  });
  return k;
}

constexpr std::size_t kKindCount = std::tuple_size_v<std::remove_cvref_t<decltype(kinds())>>;

const std::array<std::string_view, kKindCount>& names() {
  static const std::array<std::string_view, kKindCount> n = [] {
    std::array<std::string_view, kKindCount> a{};
    std::transform(kinds().begin(), kinds().end(), a.begin(), [](const DriveKind& k) { return k->name(); });
    return a;
  }();
  return n;
}

}  // namespace

std::span<const DriveKind> drive_kinds() { return kinds(); }

const DriveKind* find_drive_kind(std::string_view name) {
  for (const DriveKind& k : kinds()) {
    if (k->name() == name) return &k;
  }
  return nullptr;
}

std::string drive_kind_names(std::string_view separator, std::string_view last, std::string_view quote) {
  std::string s;
  const auto n = names().size();
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) s += i + 1 == n ? last : separator;
    s += std::string(quote) + std::string(names()[i]) + std::string(quote);
  }
  return s;
}

const SettingSpec* any_declaration(std::string_view name, const DriveKind** owner) {
  for (const DriveKind& k : kinds()) {
    if (const SettingSpec* spec = k->setting(name)) {
      if (owner != nullptr) *owner = &k;
      return spec;
    }
  }
  return nullptr;
}

std::vector<std::string_view> declared_setting_names() {
  std::vector<std::string_view> out;
  for (const DriveKind& k : kinds()) {
    for (const SettingSpec& spec : k->settings()) {
      if (std::find(out.begin(), out.end(), spec.name) == out.end()) out.push_back(spec.name);
    }
  }
  return out;
}

namespace {

// "{a}" -> "a VF1000", "{the}" -> "the VF1000" in a declaration's `elsewhere`.
std::string with_kind(std::string_view text, const DriveDescriptor& k) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    if (text.substr(i).starts_with("{a}")) {
      out += std::string(k.facts().article) + " " + std::string(k.facts().title);
      i += 3;
    } else if (text.substr(i).starts_with("{the}")) {
      out += "the " + std::string(k.facts().title);
      i += 5;
    } else {
      out += text[i++];
    }
  }
  return out;
}

std::string type_words(const SettingSpec& s) {
  switch (s.kind) {
    case SettingKind::integer: return "an integer";
    case SettingKind::boolean: return "true or false";
    case SettingKind::duration: return "a time";
    case SettingKind::choice: return "one of its choices";
  }
  return "?";
}

std::string value_text(const SettingSpec& s, std::int64_t v) {
  switch (s.kind) {
    case SettingKind::integer: return std::to_string(v) + (s.unit.empty() ? "" : " " + std::string(s.unit));
    case SettingKind::boolean: return v != 0 ? "true" : "false";
    case SettingKind::duration: return std::to_string(v) + " ns";
    case SettingKind::choice:
      return v >= 0 && static_cast<std::size_t>(v) < s.choices.size() ? std::string(s.choices[static_cast<std::size_t>(v)])
                                                                        : std::to_string(v);
  }
  return "?";
}

}  // namespace

std::optional<SettingsRefusal> refuse_setting_name(const DriveKind& kind, std::string_view name) {
  if (kind->setting(name) != nullptr) return std::nullopt;
  const DriveKind* owner = nullptr;
  if (const SettingSpec* spec = any_declaration(name, &owner)) {
    return SettingsRefusal({ErrorCode::setting_of_another_drive, with_kind(spec->elsewhere, *kind)}, spec->name);
  }
  return SettingsRefusal({ErrorCode::setting_invalid, "'" + std::string(name) + "' is not a setting of " +
                                                          std::string(kind->facts().article) + " " +
                                                          std::string(kind->facts().title)},
                         "");
}

SettingsRefusal check_settings(const DriveKind& kind, const SettingValues& values) {
  for (const SettingValue& v : values.all()) {
    if (auto refusal = refuse_setting_name(kind, v.name)) return std::move(*refusal);
    const SettingSpec& spec = *kind->setting(v.name);
    if (v.kind != spec.kind) {
      return SettingsRefusal({ErrorCode::setting_invalid, "'" + v.name + "' must be " + type_words(spec)}, spec.name);
    }
    if (v.value < spec.min || v.value > spec.max) {
      std::string limit(spec.range);
      if (!spec.parameter.empty()) limit += ", " + std::string(spec.parameter);
      if (!spec.seed.empty()) limit += ", " + std::string(spec.seed);
      return SettingsRefusal({ErrorCode::setting_out_of_range,
                              "'" + v.name + "' = " + value_text(spec, v.value) + " is out of range (" + limit + ")"},
                             spec.name);
    }
  }
  return {};
}

trace::Vocabulary trace_vocabulary() {
  // The header settings: the integer settings that place a device on the ring, as the kinds
  // declare them (a trace header's value is an integer).
  static const std::vector<std::string_view> settings = [] {
    std::vector<std::string_view> out;
    for (const std::string_view name : declared_setting_names()) {
      const SettingSpec& spec = *any_declaration(name);
      if (spec.kind == SettingKind::integer && uses(spec.faces, SettingFace::interbus)) out.push_back(name);
    }
    return out;
  }();
  // `setting: NAME VALUE`: the watchdog's reaction and every other declared setting.
  static const std::vector<std::string_view> device_settings = [] {
    std::vector<std::string_view> out{"watchdog_reaction"};
    for (const std::string_view name : declared_setting_names()) {
      if (std::find(settings.begin(), settings.end(), name) == settings.end()) out.push_back(name);
    }
    return out;
  }();
  return {names(), drivecom::kTargetKeys, settings, device_settings};
}

}  // namespace ibs::devices
