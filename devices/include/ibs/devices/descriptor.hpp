// What a drive kind is, as the project's drive-neutral parts need to know it: its descriptor.
// Each drive's wing implements one (devices/<drive>/descriptor.hpp) and the registry lists them
// (registry.hpp); the simulator, the scenario reader, the command line and the replay adapters ask
// the descriptor and never name a concrete drive. Everything here is configuration-time work: it
// may allocate, and reports refused settings as a SettingsRefusal (or, where exceptions are on,
// also as a SettingsError). The embedded build (IBS_EMBEDDED), which has no traces, leaves out
// the trace part.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibs/devices/driver.hpp"
#include "ibs/devices/plant_event.hpp"
#include "ibs/devices/settings.hpp"
#include "ibs/base/error.hpp"
#include "ibs/interbus/id_code.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"

#if !IBS_EMBEDDED
#include "ibs/interbus/replay.hpp"
#include "ibs/interbus/trace.hpp"
#endif
#if IBS_EXCEPTIONS
#include <stdexcept>
#endif

namespace ibs::devices {

// The settings a scenario, a trace header or the command line gives one device: the bus side and
// the bus watchdog every drive has (watchdog_ms is the VF1000's 906-IB-WD and the MC6000's
// 409-BUTWD; watchdog_reaction a drive's reaction to it where it has a choice), and the drive's
// own settings by name, which its wing declares (DriveFacts::settings, settings.hpp) and reads.
struct DeviceSettings {
  interbus::BusKind bus = interbus::BusKind::remote;
  std::optional<int> watchdog_ms;
  std::optional<int> watchdog_reaction;
  SettingValues drive;

  friend bool operator==(const DeviceSettings&, const DeviceSettings&) = default;
};

// A setting the drive refuses: the Error (ErrorCode::setting_*, or layout_* for an MC6000
// layout) and the setting it is about. `setting` names it as the files do ("bus", "watchdog_ms",
// "watchdog_reaction" or a declared setting's name), `fallback` the one to point at when
// the first is not in the file, so that a reader can name the line. No error: the settings suit.
struct SettingsRefusal : Error {
  SettingsRefusal() = default;
  SettingsRefusal(Error e, std::string_view setting_name, std::string_view fallback_name = {})
      : Error(std::move(e)), setting(setting_name), fallback(fallback_name) {}

  std::string_view setting;
  std::string_view fallback;
};

#if IBS_EXCEPTIONS
// The same refusal thrown: what() is the message, setting() and fallback() as the refusal's.
class SettingsError : public std::invalid_argument {
 public:
  SettingsError(const std::string& what, std::string_view setting, std::string_view fallback = {})
      : std::invalid_argument(what), setting_(setting), fallback_(fallback) {}
  explicit SettingsError(const SettingsRefusal& r)
      : SettingsError(r.message, r.setting, r.fallback) {}
  [[nodiscard]] std::string_view setting() const { return setting_; }
  [[nodiscard]] std::string_view fallback() const { return fallback_; }

 private:
  std::string_view setting_;
  std::string_view fallback_;
};
#endif

// One device as its settings place it on the bus.
struct Configuration {
  DeviceSettings settings;
  interbus::IdCode id_code{};
  interbus::BusKind bus = interbus::BusKind::remote;
  bool exchanges_data = true;  // false: on the ring, but no data reach the drive (MC6000 SUPI 0)
  std::size_t pd_words = 0;    // process-data words of its slot each way
  std::size_t pcp_words = 0;   // PCP channel words each way

  // The process-data words the drive really exchanges.
  [[nodiscard]] std::size_t exchanged_pd_words() const { return exchanges_data ? pd_words : 0; }
};

// What a timeline or a request needs of a device, and may find missing.
enum class Capability : std::uint8_t { control_word, parameter_channel, reference };

// One word of a device's process data as `ibs layout` describes it.
struct WordMeaning {
  int word = 1;      // 1-based, as the manuals count
  std::string role;  // machine-readable: control_word, reference_q16_high, ...
  std::string meaning;
};
// A setting as a report shows it: a number or a text.
struct ReportedSetting {
  std::string key;
  std::optional<int> number;
  std::string text;
};
struct LayoutDescription {
  std::string title;
  std::vector<ReportedSetting> settings;  // in the order a report lists them
  bool exchanges_data = true;
  std::vector<WordMeaning> out_words;  // master -> device
  std::vector<WordMeaning> in_words;   // device -> master
  std::string pcp;
};
// One ring position of `ibs timing`.
struct RingEntry {
  interbus::IdCode id_code{};
  interbus::BusKind bus = interbus::BusKind::remote;
  std::vector<ReportedSetting> settings;
  std::string note;  // appended to the ring's line, e.g. "405-SUPI = 0: no data exchange"
};

// The plain facts of a drive kind; the words quoted in messages are the manuals'.
struct DriveFacts {
  std::string_view name;     // "vf1000": scenario `type`, trace `device`, command-line name
  std::string_view title;    // "VF1000"
  std::string_view article;  // "a" ("a VF1000") or "an" ("an MC6000")
  std::string_view unit;     // of the reference and the actual value: "Hz", "rpm"
  Duration sample_period{0};
  // The scenario timeline's reference action ("speed", "frequency") and its range.
  std::string_view reference_action;
  double reference_min = 0.0;
  double reference_max = 0.0;
  std::string_view reference_range;  // "-32768..32767 rpm"
  // Parameter numbers a request may name: 0..max_parameter.
  int max_parameter = 0;
  std::string_view parameter_range;  // ", LUSTBUS manual 2.4.2" (after "0..999")
  // Raw values a parameter write may carry.
  double write_min = 0.0;
  double write_max = 0.0;
  std::string_view write_range;  // " (-32768..65535, 16 bits)"
  // What the run summary says when the drive's watchdog error appears.
  std::string_view watchdog_error;
  // How `ibs timing` takes the drive: "vf1000", "mc6000:SUPI[:local|remote]".
  std::string_view timing_syntax;
  // The parameter channel's trace words besides `words: pd` (comm, pcp), if the drive has one,
  // and how a message names it ("the communication word", "PCP").
#if !IBS_EMBEDDED
  std::optional<trace::WordsKind> channel_words;
#endif
  std::string_view channel_name;
  // The drive's own settings (settings.hpp), in the order files and tables list them.
  std::span<const SettingSpec> settings{};
  // The plant and fault events it takes (plant_event.hpp): its error list, inputs, load.
  EventFacts events{};
};

class DriveDescriptor {
 public:
  explicit DriveDescriptor(const DriveFacts& facts) : facts_(facts) {}
  virtual ~DriveDescriptor() = default;
  DriveDescriptor(const DriveDescriptor&) = delete;
  DriveDescriptor& operator=(const DriveDescriptor&) = delete;

  [[nodiscard]] const DriveFacts& facts() const { return facts_; }
  [[nodiscard]] std::string_view name() const { return facts_.name; }
  // The drive's own settings, and one of them by name (nullptr: the drive has no such setting).
  [[nodiscard]] std::span<const SettingSpec> settings() const { return facts_.settings; }
  [[nodiscard]] const SettingSpec* setting(std::string_view name) const { return find_setting(settings(), name); }

  // --- configuration -------------------------------------------------------------------------
  // Where the settings place the device on the bus; refuses a bus side or a layout the drive
  // refuses.
  [[nodiscard]] virtual Expected<Configuration, SettingsRefusal> try_configure(
      const DeviceSettings& s) const = 0;
  // Refuses a watchdog setting out of the drive's range (and a watchdog_reaction the drive does
  // not take), and a value of its own settings the manual's words say more about than
  // check_settings does (registry.hpp). A setting another kind declares is check_settings'.
  [[nodiscard]] virtual SettingsRefusal validate_watchdog(const DeviceSettings& s) const = 0;
#if IBS_EXCEPTIONS
  // try_configure and validate_watchdog, throwing SettingsError for what they refuse.
  [[nodiscard]] Configuration configure(const DeviceSettings& s) const;
  void check_watchdog(const DeviceSettings& s) const;
#endif
  // Why the configured device lacks a capability ("has no PCP channel (405-SUPI 12)"), nullopt
  // when it has it.
  [[nodiscard]] virtual std::optional<std::string> lacks(Capability c, const Configuration& config) const = 0;

  // --- the master side -----------------------------------------------------------------------
  // For a configuration try_configure gave: an MC6000 configuration whose settings it refuses
  // throws SettingsError (in the embedded build: aborts).
  [[nodiscard]] virtual std::unique_ptr<DeviceDriver> make_driver(const Configuration& config) const = 0;
  // Control and status words in words, the drive's own bits included.
  [[nodiscard]] virtual std::string explain_control(Word control, Word previous) const = 0;
  [[nodiscard]] virtual std::string explain_status(Word status) const = 0;

#if !IBS_EMBEDDED
  // --- traces (../shared/specs/trace-format.md) -------------------------------------------------
  // The settings a trace header gives; the headers a recording of the device writes.
  [[nodiscard]] virtual DeviceSettings trace_settings(const trace::Header& h) const = 0;
  virtual void write_trace_settings(const Configuration& config, trace::Header& h) const = 0;
  // `words: pd`: the master side (its timers run `step` per step: the trace's step-time) and the
  // explainer for the configured device.
  [[nodiscard]] virtual std::unique_ptr<trace::MasterSide> make_pd_master(const Configuration& config,
                                                                          Duration step) const = 0;
  [[nodiscard]] virtual std::unique_ptr<trace::Explainer> make_pd_explainer(const Configuration& config) const = 0;
  // The parameter channel's words (facts().channel_words): what the channel cannot serve of a
  // header (its words, its configuration, a request it cannot carry), thrown as
  // std::invalid_argument -- the trace validation asks it (trace_adapters.hpp) -- then both sides
  // and the explainer, which throw the same for such a header.
  virtual void check_channel_trace(const trace::Header& h) const = 0;
  [[nodiscard]] virtual std::unique_ptr<trace::DeviceSide> make_channel_device(const trace::Header& h) const = 0;
  [[nodiscard]] virtual std::unique_ptr<trace::MasterSide> make_channel_master(const trace::Header& h) const = 0;
  [[nodiscard]] virtual std::unique_ptr<trace::Explainer> make_channel_explainer(const trace::Header& h) const = 0;
  // A `! write PNR VALUE` event against the drive's table (a parameter it has, that a channel may
  // write, a value of its type and range; 85-SIOF/SERR takes its 8 bits): nullopt when the table
  // takes it -- the replay's drive may still refuse it in the state it is then in -- else why not.
  [[nodiscard]] virtual std::optional<std::string> check_trace_write(std::uint16_t number, std::int64_t value) const {
    (void)number;
    (void)value;
    return std::nullopt;
  }
#endif

  // --- the command line ------------------------------------------------------------------------
  // `ibs layout`: a refusal of the options given (nullopt: they suit the drive), then the words.
  // `given`: the declared settings the options gave; `bus`: whether --bus was given.
  [[nodiscard]] virtual std::optional<std::string> check_layout_options(const SettingValues& given, bool bus) const = 0;
  [[nodiscard]] virtual LayoutDescription layout(const Configuration& config) const = 0;
  // `ibs timing`: the fields after the name in NAME[:FIELD...], or the refusal of them. ring_spec
  // writes the argument that stands for a device of these settings ("mc6000:11").
  [[nodiscard]] virtual Expected<RingEntry, SettingsRefusal> try_ring_entry(
      std::span<const std::string_view> fields) const = 0;
  [[nodiscard]] virtual std::string ring_spec(const DeviceSettings& s) const = 0;
#if IBS_EXCEPTIONS
  // try_ring_entry, throwing SettingsError for what it refuses.
  [[nodiscard]] RingEntry ring_entry(std::span<const std::string_view> fields) const;
#endif

 private:
  DriveFacts facts_;
};

}  // namespace ibs::devices
