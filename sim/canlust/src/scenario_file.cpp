#include "ibs/sim/scenario_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "canlust_reader.hpp"
#include "ibs/base/text_file.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim {

AnyScenario load_any_scenario(const std::string& path) {
  // As load_scenario (scenario.cpp): the format by the extension, in upper or lower case.
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".toml" && ext != ".json") {
    throw ScenarioError(path, 0, "unknown scenario format: the file name must end in .toml or .json");
  }
  std::string text;
  try {
    text = read_text_file(path);
  } catch (const FileReadError& e) {
    throw ScenarioError(path, 0, e.what());
  }
  const detail::Format format = ext == ".json" ? detail::Format::json : detail::Format::toml;
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

}  // namespace ibs::sim
