// A drive's own settings, declared by its wing (issue 22, item 4): every setting a scenario, a
// trace header or the command line may give one device of a kind -- beyond the bus side and the
// watchdog every drive has (DeviceSettings) -- is a SettingSpec in the wing's list
// (DriveFacts::settings). The floors and the tools read and check the values only through these
// declarations (name, type, range, default, unit, manual section, faces), so none of them names
// a drive's setting, and a drive's setting is never a field of a union of all drives. The values
// travel as SettingValues, (name, value) pairs; the wing reads its own through the typed reads at
// configuration time, never on the cycle path. Configuration-time code: it may allocate.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/base/time.hpp"

namespace ibs::devices {

// What a setting's value is. Values are held as std::int64_t: integer as is, boolean 0/1,
// duration in Duration ticks (ns), choice the index into SettingSpec::choices.
enum class SettingKind : std::uint8_t { integer, boolean, duration, choice };
std::string_view to_string(SettingKind k);  // "integer", "boolean", "time", "choice"

// The bus faces a setting changes the drive on (a bitmask of these).
enum class SettingFace : std::uint8_t { interbus = 1, lustbus = 2, dfs1 = 4, canlust = 8 };
constexpr std::uint8_t operator|(SettingFace a, SettingFace b) {
  return static_cast<std::uint8_t>(static_cast<std::uint8_t>(a) | static_cast<std::uint8_t>(b));
}
constexpr bool uses(std::uint8_t faces, SettingFace f) { return (faces & static_cast<std::uint8_t>(f)) != 0; }

struct SettingSpec {
  std::string_view name;  // as files and the command line give it
  SettingKind kind = SettingKind::integer;
  std::int64_t min = 0;  // the accepted range, both ends included (boolean: 0..1)
  std::int64_t max = 0;
  std::int64_t fallback = 0;  // the value when none is given
  std::string_view unit;      // of an integer ("ms"); empty for none
  std::string_view parameter;  // the manual's name for it ("406-IBCNF"); empty when it has none
  std::string_view seed;       // where the manual defines it ("INTERBUS manual 3.2.3")
  std::uint8_t faces = 0;      // SettingFace bits
  std::string_view meaning;    // one line for the docs' tables and the command line's help
  // The range as messages and the docs write it ("0..12"; "above 0 s, at most 60 s").
  std::string_view range;
  // What a device of another kind says when given it: "{a}" stands for that kind with its
  // article ("a VF1000"), "{the}" for it with "the".
  std::string_view elsewhere;
  // It decides the device's place and words on the INTERBUS ring (its ID code and layout): the
  // scenario writer writes it even at its default, and `ibs layout` takes it as an option.
  bool places_device = false;
  std::span<const std::string_view> choices{};  // choice: the names, by index
};

// The settings of a kind by name; nullptr for none.
inline const SettingSpec* find_setting(std::span<const SettingSpec> specs, std::string_view name) {
  const auto it = std::find_if(specs.begin(), specs.end(), [name](const SettingSpec& s) { return s.name == name; });
  return it == specs.end() ? nullptr : &*it;
}

struct SettingValue {
  std::string name;
  SettingKind kind = SettingKind::integer;
  std::int64_t value = 0;

  friend bool operator==(const SettingValue&, const SettingValue&) = default;
};

// The settings given one device, by name (kept sorted, so that equal sets compare equal). Which
// names and values a kind accepts is its declarations' business (check_settings, descriptor.hpp).
class SettingValues {
 public:
  void set(std::string_view name, SettingKind kind, std::int64_t value) {
    const auto it = std::lower_bound(values_.begin(), values_.end(), name,
                                     [](const SettingValue& v, std::string_view n) { return v.name < n; });
    if (it != values_.end() && it->name == name) {
      it->kind = kind;
      it->value = value;
    } else {
      values_.insert(it, SettingValue{std::string(name), kind, value});
    }
  }
  void set_integer(std::string_view name, std::int64_t v) { set(name, SettingKind::integer, v); }
  void set_boolean(std::string_view name, bool v) { set(name, SettingKind::boolean, v ? 1 : 0); }
  void set_duration(std::string_view name, Duration v) { set(name, SettingKind::duration, v.count()); }
  void erase(std::string_view name) {
    std::erase_if(values_, [name](const SettingValue& v) { return v.name == name; });
  }

  [[nodiscard]] const SettingValue* find(std::string_view name) const {
    for (const SettingValue& v : values_) {
      if (v.name == name) return &v;
    }
    return nullptr;
  }
  [[nodiscard]] bool given(std::string_view name) const { return find(name) != nullptr; }
  [[nodiscard]] bool empty() const { return values_.empty(); }
  [[nodiscard]] std::span<const SettingValue> all() const { return values_; }

  // The wing's typed reads: the value given, or the declaration's fallback. A value of another
  // type than the declaration's never gets here (check_settings refuses it); it reads as given.
  [[nodiscard]] std::int64_t value(const SettingSpec& spec) const {
    const SettingValue* v = find(spec.name);
    return v == nullptr ? spec.fallback : v->value;
  }
  [[nodiscard]] int integer(const SettingSpec& spec) const { return static_cast<int>(value(spec)); }
  [[nodiscard]] bool boolean(const SettingSpec& spec) const { return value(spec) != 0; }
  [[nodiscard]] Duration duration(const SettingSpec& spec) const { return Duration{value(spec)}; }

  friend bool operator==(const SettingValues&, const SettingValues&) = default;

 private:
  std::vector<SettingValue> values_;
};

}  // namespace ibs::devices
