#include "ibs/sim/scenario_file.hpp"

#include <filesystem>

#include "canlust_reader.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim {

namespace {

AnyScenario read_any(const std::string& text, detail::Format format, const std::string& path) {
  const detail::Node root =
      format == detail::Format::json ? detail::json_tree(text, path) : detail::toml_tree(text, path);
  if (canlust::is_canlust_tree(root)) {
    canlust::Scenario s = canlust::read_tree(root, path);
    if (s.name.empty()) s.name = std::filesystem::path(path).stem().string();
    return s;
  }
  // The INTERBUS schema, as parse_scenario_toml / parse_scenario_json apply it.
  detail::SourceMap lines;
  Scenario s = detail::read_tree(root, format, path, lines);
  detail::validate(s, lines, path);
  return s;
}

}  // namespace

AnyScenario load_any_scenario(const std::string& path) {
  const detail::ScenarioText file = detail::read_scenario_file(path);
  return read_any(file.text, file.format, path);
}

AnyScenario load_any_scenario_text(const std::string& text, ScenarioFormat format, const std::string& name) {
  return read_any(text, format == ScenarioFormat::json ? detail::Format::json : detail::Format::toml, name);
}

}  // namespace ibs::sim
