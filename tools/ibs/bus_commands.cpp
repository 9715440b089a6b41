// The CLI11 wiring of `ibs layout` and `ibs timing`, and the number formatting both share.
#include "bus_commands.hpp"

#include "ibs/devices/registry.hpp"

#include <CLI/CLI.hpp>
#include <array>
#include <charconv>
#include <cstdint>
#include <iostream>

namespace ibs::cli {

namespace {

// `ns` in units of 10^digits ns, exactly, trailing zeros dropped.
std::string decimal(std::int64_t ns, int digits) {
  std::int64_t scale = 1;
  for (int i = 0; i < digits; ++i) scale *= 10;
  const bool negative = ns < 0;
  const std::uint64_t mag =
      negative ? 0U - static_cast<std::uint64_t>(ns) : static_cast<std::uint64_t>(ns);
  const auto uscale = static_cast<std::uint64_t>(scale);
  std::string s = (negative ? "-" : "") + std::to_string(mag / uscale);
  std::string frac = std::to_string(mag % uscale);
  frac.insert(0, static_cast<std::size_t>(digits) - frac.size(), '0');
  while (!frac.empty() && frac.back() == '0') frac.pop_back();
  if (!frac.empty()) s += "." + frac;
  return s;
}

}  // namespace

std::string format_us(Duration d) {
  return decimal(d.count(), 3);
}
std::string format_ms(Duration d) {
  return decimal(d.count(), 6);
}

std::string format_number(double v) {
  std::array<char, 32> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return {buf.data(), r.ptr};
}

namespace {

// The drive kinds whose layout the options set (descriptor.hpp: check_layout_options).
std::string kinds_with_layout_options() {
  std::string s;
  for (const devices::DriveKind& k : devices::drive_kinds()) {
    devices::SettingValues all;
    for (const devices::SettingSpec& spec : k->settings()) {
      if (spec.places_device) all.set(spec.name, spec.kind, spec.fallback);
    }
    if (!k->check_layout_options(all, true)) s += (s.empty() ? "" : ", ") + std::string(k->name());
  }
  return s;
}

std::string timing_help() {
  std::string s;
  const auto kinds = devices::drive_kinds();
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    if (i > 0) s += i + 1 == kinds.size() ? " or " : ", ";
    s += std::string(kinds[i]->facts().timing_syntax);
  }
  std::string ring;
  for (const std::string& d : default_timing_ring()) ring += (ring.empty() ? "" : " ") + d;
  return s + ", in ring order (default: " + ring + ")";
}

}  // namespace

void add_bus_commands(CLI::App& app, BusCommandState& state) {
  const std::string layout_kinds = kinds_with_layout_options();
  LayoutOptions& lo = state.layout_options;
  state.layout = app.add_subcommand(
      "layout", "print a drive's ID code and the meaning of each process-data word");
  state.layout->add_option("DEVICE", lo.device, devices::drive_kind_names(", ", " or "))->required();
  // One option per setting a kind declares as placing the device on the ring, its range and
  // meaning from the declaration; the value's range is the drive's to judge (its words).
  for (const std::string_view name : devices::declared_setting_names()) {
    const devices::DriveKind* owner = nullptr;
    const devices::SettingSpec& spec = *devices::any_declaration(name, &owner);
    if (!spec.places_device || spec.kind != devices::SettingKind::integer) continue;
    const std::string help = (spec.parameter.empty() ? "" : std::string(spec.parameter) + ", ") +
                             std::string(spec.range) + ": " + std::string(spec.meaning) + " (" + layout_kinds + ")";
    state.layout->add_option_function<int>(
        "--" + std::string(spec.name), [&lo, name = spec.name](const int& v) { lo.settings.set_integer(name, v); },
        help);
  }
  state.layout->add_option_function<std::string>(
      "--bus", [&lo](const std::string& v) { lo.bus = v; },
      "local or remote (" + layout_kinds + "; default remote)");
  state.layout->add_flag("-j,--json", lo.json, "print JSON");

  TimingOptions& to = state.timing_options;
  state.timing = app.add_subcommand(
      "timing", "cycle time of a ring with every term, worst-case reaction and recovery time");
  state.timing->add_option("DEVICE", to.devices, timing_help());
  state.timing->add_option("--baud", to.baud, "500k (default) or 2M");
  state.timing->add_option_function<double>(
      "--sw-us", [&to](const double& v) { to.software_time_us = v; },
      "master software time SW in microseconds (default 200)");
  state.timing->add_flag("-j,--json", to.json, "print JSON");
}

std::optional<int> run_bus_commands(const BusCommandState& state, std::ostream& out,
                                    std::ostream& err) {
  if (state.layout != nullptr && state.layout->parsed()) {
    return layout_command(state.layout_options, out, err);
  }
  if (state.timing != nullptr && state.timing->parsed()) {
    return timing_command(state.timing_options, out, err);
  }
  return std::nullopt;
}

std::optional<int> run_bus_commands(const BusCommandState& state) {
  return run_bus_commands(state, std::cout, std::cerr);
}

}  // namespace ibs::cli
