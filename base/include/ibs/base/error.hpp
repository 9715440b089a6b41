// The error boundary of configuration-time code (docs/embedding.md, "An embedded build"). Every
// check a configuration must pass -- a bus configuration, an MC6000 layout, a drive's settings, a
// parameter table, a channel's or the master loop's configuration -- is made once, by a function
// that returns an Error (or an Expected) and never throws. The default build keeps its throwing API
// (make_bus_config, make_layout, the constructors, DriveDescriptor::configure ...) on top of those
// functions, with the same exception types and messages; the embedded build (-fno-exceptions
// -fno-rtti, IBS_EMBEDDED) has only the error codes. The cycle path never fails this way at all.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "ibs/base/build.hpp"

// 1 where the throwing API exists: the libraries were built with exceptions (not IBS_EMBEDDED)
// and the code including this header is compiled with them too.
#if defined(__cpp_exceptions) && !IBS_EMBEDDED
#define IBS_EXCEPTIONS 1
#else
#define IBS_EXCEPTIONS 0
#endif

namespace ibs {

// What was refused. The names say where (the prefix) and what; Error::message says it in the words
// the exception of the default build carries.
enum class ErrorCode : std::uint8_t {
  none = 0,
  // interbus::try_make_bus_config (interbus::ConfigError)
  bus_too_many_devices,         // more than 512 devices
  bus_device_unnamed,           // an empty name
  bus_name_repeated,            // a name an earlier device has
  bus_unknown_length_code,      // the ID code's length code is none INTERBUS knows
  bus_unassigned_pcp_width,     // a PCP device with the unassigned width bits 10b
  bus_pcp_wider_than_device,    // a PCP channel wider than the device's words on the ring
  bus_no_direction,             // process data without a direction
  bus_too_many_remote_devices,  // more than 254 remote-bus devices
  bus_local_segment_too_long,   // more than 63 devices in one local bus segment
  bus_too_many_pcp_devices,     // more than 62 PCP devices
  bus_too_many_input_words,     // input data beyond 256 words
  bus_too_many_output_words,    // output data beyond 256 words
  // Parameter tables: drive::ParameterTable::validate, pcp::ParameterStore::validate and the
  // servers that serve a table (std::invalid_argument)
  table_too_large,               // more rows than the table or store can index
  table_number_out_of_range,     // a number above the channel's highest
  table_number_repeated,         // a number an earlier row has
  table_bad_name,                // a name of the wrong length or with unprintable characters
  table_bad_unit,                // a unit of the wrong length or with unprintable characters
  table_limits_outside_type,     // min, max or default outside what the data type holds
  table_min_above_max,           // min above max
  table_default_outside_limits,  // the default outside min..max
  table_scale_not_positive,      // a scale of zero, below zero or NaN
  table_lacks_siof,              // no 85-SIOF, which the VF1000 channel depends on
  table_bad_choices,             // od::Dictionary: a substitution text's code or name, or none where asked
  table_bad_role,                // od::Dictionary: a PROG/SLOAD/85/SAVE entry twice or of the wrong kind
  table_bad_elements,            // od::Dictionary: an entry of no element
  // Parameter channels: vf1000_channel::Client/Server, pcp::Client/Link/Server ::validate
  // (std::invalid_argument)
  channel_capacity_zero,          // a request queue or completed ring of no entries
  channel_timeout_not_positive,   // a timeout of zero or less
  channel_width_invalid,          // a PCP channel other than 1, 2 or 4 words
  channel_pdu_size_invalid,       // KBL max PDU sizes outside 20..134 bytes
  channel_workload_out_of_range,  // a PCP server workload outside 0..1
  channel_latency_invalid,        // a PCP server latency with min below 0 or above max
  // A drive's process-data layout from its settings (e.g. devices::mc6000::try_make_layout;
  // the message, and a descriptor's refusal, name the setting)
  layout_setting_out_of_range,  // a layout setting outside its range
  layout_setting_unsupported,   // a value of a layout setting the emulated drive does not model
  layout_settings_conflict,     // two layout settings whose values do not go together
  // A drive's settings: DriveDescriptor::try_configure, validate_watchdog, try_ring_entry
  // (devices::SettingsError; the refusal names the setting)
  setting_bus_refused,       // a bus side the drive cannot be on
  setting_out_of_range,      // a number outside the drive's range
  setting_of_another_drive,  // a setting this drive kind does not have
  setting_missing,           // a field that must be given is not
  setting_too_many_fields,   // more fields than the drive takes
  setting_invalid,           // a field that is not what it must be (a number, a bus side)
  // master::MasterLoop::validate (std::invalid_argument)
  master_driver_count,          // not one driver per device
  master_device_outside_image,  // a device's words outside the process image
  // pcp::MailboxClient::validate (std::invalid_argument)
  channel_reference_invalid,  // a board's communication reference below 2
  // A controller board behind the DDI (master/ddi: ibs::master::DdiBoard)
  board_call_failed,             // a DDI call returned an error: the call and its code
  board_plug_and_play,           // the board's plug & play mode is on (2240H)
  board_configuration_mismatch,  // the board's configuration is not the master's
  board_service_refused,         // a firmware service was confirmed negatively
  board_no_answer,               // a firmware service's confirmation did not come in time
};

// The enumerator's name ("layout_setting_out_of_range"), for a log line.
std::string_view to_string(ErrorCode c);

// A refusal: its code and the message of the default build's exception (where and what). As
// std::error_code, it converts to true when it is an error:
//   if (const ibs::Error e = pcp::Client::validate(config)) report(e.message);
struct Error {
  ErrorCode code = ErrorCode::none;
  std::string message;

  [[nodiscard]] bool ok() const { return code == ErrorCode::none; }
  explicit operator bool() const { return !ok(); }
  friend bool operator==(const Error&, const Error&) = default;
};

namespace detail {
[[noreturn]] void abort_expected_misuse() noexcept;
}  // namespace detail

// A value or the error that prevented it, for the configuration-time operations that build
// something (C++20 has no std::expected). As std::expected, it converts to true when it holds
// the value:
//   auto config = descriptor.try_configure(settings);
//   if (!config) return config.error();
template <typename T, typename E = Error>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  // `error` must be an error (its code not ErrorCode::none).
  Expected(E error) : error_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  [[nodiscard]] bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }

  // The value; asking an error for it is a programming error and aborts.
  [[nodiscard]] T& value() & { return checked(value_); }
  [[nodiscard]] const T& value() const& { return checked(value_); }
  [[nodiscard]] T&& value() && { return std::move(checked(value_)); }
  T* operator->() { return &checked(value_); }
  const T* operator->() const { return &checked(value_); }

  // The error; no error (ErrorCode::none) when the result holds a value.
  [[nodiscard]] const E& error() const { return error_; }

 private:
  template <typename V>  // std::optional<T>, const or not
  static auto& checked(V& v) {
    if (!v) detail::abort_expected_misuse();
    return *v;
  }

  std::optional<T> value_;
  E error_;
};

namespace detail {

// Writes "ibs: CODE: MESSAGE" to stderr and aborts: what a constructor of the embedded build does
// with a configuration its validate() refuses.
[[noreturn]] void abort_with(const Error& e) noexcept;

// For a constructor (or a helper) whose configuration must pass a check: nothing when `e` is no
// error. Otherwise, with exceptions, throws Exception(e) when it can be made from the error,
// else Exception(e.message) -- the default build's types and messages; in the embedded build,
// where nothing throws, a configuration that its validate() refuses is a broken precondition:
// the message goes to stderr and the program aborts, rather than build an object that is wrong.
template <typename Exception, typename E>
void require(const E& e) {
  if (!e) return;
#if IBS_EXCEPTIONS
  if constexpr (std::is_constructible_v<Exception, const E&>) {
    throw Exception(e);
  } else {
    throw Exception(e.message);
  }
#else
  abort_with(e);
#endif
}

}  // namespace detail

}  // namespace ibs
