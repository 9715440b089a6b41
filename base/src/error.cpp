#include "ibs/base/error.hpp"

#include <cstdio>
#include <cstdlib>

namespace ibs {

std::string_view to_string(ErrorCode c) {
  switch (c) {
    case ErrorCode::none: return "none";
    case ErrorCode::bus_too_many_devices: return "bus_too_many_devices";
    case ErrorCode::bus_device_unnamed: return "bus_device_unnamed";
    case ErrorCode::bus_name_repeated: return "bus_name_repeated";
    case ErrorCode::bus_unknown_length_code: return "bus_unknown_length_code";
    case ErrorCode::bus_unassigned_pcp_width: return "bus_unassigned_pcp_width";
    case ErrorCode::bus_pcp_wider_than_device: return "bus_pcp_wider_than_device";
    case ErrorCode::bus_no_direction: return "bus_no_direction";
    case ErrorCode::bus_too_many_remote_devices: return "bus_too_many_remote_devices";
    case ErrorCode::bus_local_segment_too_long: return "bus_local_segment_too_long";
    case ErrorCode::bus_too_many_pcp_devices: return "bus_too_many_pcp_devices";
    case ErrorCode::bus_too_many_input_words: return "bus_too_many_input_words";
    case ErrorCode::bus_too_many_output_words: return "bus_too_many_output_words";
    case ErrorCode::table_too_large: return "table_too_large";
    case ErrorCode::table_number_out_of_range: return "table_number_out_of_range";
    case ErrorCode::table_number_repeated: return "table_number_repeated";
    case ErrorCode::table_bad_name: return "table_bad_name";
    case ErrorCode::table_bad_unit: return "table_bad_unit";
    case ErrorCode::table_limits_outside_type: return "table_limits_outside_type";
    case ErrorCode::table_min_above_max: return "table_min_above_max";
    case ErrorCode::table_default_outside_limits: return "table_default_outside_limits";
    case ErrorCode::table_scale_not_positive: return "table_scale_not_positive";
    case ErrorCode::table_lacks_siof: return "table_lacks_siof";
    case ErrorCode::table_bad_choices: return "table_bad_choices";
    case ErrorCode::table_bad_role: return "table_bad_role";
    case ErrorCode::table_bad_elements: return "table_bad_elements";
    case ErrorCode::channel_capacity_zero: return "channel_capacity_zero";
    case ErrorCode::channel_timeout_not_positive: return "channel_timeout_not_positive";
    case ErrorCode::channel_width_invalid: return "channel_width_invalid";
    case ErrorCode::channel_pdu_size_invalid: return "channel_pdu_size_invalid";
    case ErrorCode::channel_workload_out_of_range: return "channel_workload_out_of_range";
    case ErrorCode::channel_latency_invalid: return "channel_latency_invalid";
    case ErrorCode::layout_setting_out_of_range: return "layout_setting_out_of_range";
    case ErrorCode::layout_setting_unsupported: return "layout_setting_unsupported";
    case ErrorCode::layout_settings_conflict: return "layout_settings_conflict";
    case ErrorCode::setting_bus_refused: return "setting_bus_refused";
    case ErrorCode::setting_out_of_range: return "setting_out_of_range";
    case ErrorCode::setting_of_another_drive: return "setting_of_another_drive";
    case ErrorCode::setting_missing: return "setting_missing";
    case ErrorCode::setting_too_many_fields: return "setting_too_many_fields";
    case ErrorCode::setting_invalid: return "setting_invalid";
    case ErrorCode::master_driver_count: return "master_driver_count";
    case ErrorCode::master_device_outside_image: return "master_device_outside_image";
    case ErrorCode::channel_reference_invalid: return "channel_reference_invalid";
    case ErrorCode::board_call_failed: return "board_call_failed";
    case ErrorCode::board_plug_and_play: return "board_plug_and_play";
    case ErrorCode::board_configuration_mismatch: return "board_configuration_mismatch";
    case ErrorCode::board_service_refused: return "board_service_refused";
    case ErrorCode::board_no_answer: return "board_no_answer";
  }
  return "?";
}

namespace detail {

void abort_with(const Error& e) noexcept {
  const std::string_view code = to_string(e.code);
  std::fprintf(stderr, "ibs: %.*s: %s\n", static_cast<int>(code.size()), code.data(), e.message.c_str());
  std::abort();
}

void abort_expected_misuse() noexcept {
  std::fputs("ibs: Expected::value() asked of an error\n", stderr);
  std::abort();
}

}  // namespace detail

}  // namespace ibs
