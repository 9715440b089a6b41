// docs/scenarios.md's table of device keys against the drives' declarations (devices/settings.hpp):
// every setting a wing declares appears with its type, default, drive and range, and the table
// lists no drive setting that no wing declares.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "ibs/devices/registry.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::sim {
namespace {

struct Row {
  std::string type, fallback, applies, meaning;
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(' ');
  const auto e = s.find_last_not_of(' ');
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// The rows of the table under "## `[[device]]`", by key.
std::map<std::string, Row> device_table() {
  std::ifstream in(std::string(IBS_SOURCE_DIR) + "/docs/scenarios.md");
  std::map<std::string, Row> rows;
  std::string line;
  bool in_section = false;
  while (std::getline(in, line)) {
    if (line.starts_with("## ")) in_section = line == "## `[[device]]`";
    if (!in_section || !line.starts_with("| `")) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(1));
    std::string cell;
    while (std::getline(ss, cell, '|')) cells.push_back(trim(cell));
    if (cells.size() < 5) continue;
    const std::string key = cells[0].substr(1, cells[0].size() - 2);  // without the backquotes
    rows[key] = {cells[1], cells[2], cells[3], cells[4]};
  }
  return rows;
}

std::string type_word(devices::SettingKind k) {
  switch (k) {
    case devices::SettingKind::integer: return "integer";
    case devices::SettingKind::boolean: return "bool";
    case devices::SettingKind::duration: return "time";
    case devices::SettingKind::choice: return "choice";
  }
  return "?";
}

std::string default_text(const devices::SettingSpec& s) {
  switch (s.kind) {
    case devices::SettingKind::integer: return std::to_string(s.fallback);
    case devices::SettingKind::boolean: return s.fallback != 0 ? "`true`" : "`false`";
    case devices::SettingKind::duration: return "`\"" + format_time(Duration{s.fallback}) + "\"`";
    case devices::SettingKind::choice: return "`\"" + std::string(s.choices[static_cast<std::size_t>(s.fallback)]) + "\"`";
  }
  return "?";
}

TEST(ScenarioSettingsDocs, EveryDeclaredSettingIsInTheDeviceTable) {
  const auto rows = device_table();
  ASSERT_GE(rows.size(), 8U) << "the table of docs/scenarios.md was not found";
  for (const devices::DriveKind& k : devices::drive_kinds()) {
    for (const devices::SettingSpec& s : k->settings()) {
      if (!devices::uses(s.faces, devices::SettingFace::interbus)) continue;  // not a scenario key
      SCOPED_TRACE(std::string(k->name()) + " " + std::string(s.name));
      const auto row = rows.find(std::string(s.name));
      ASSERT_NE(row, rows.end());
      EXPECT_EQ(row->second.type, type_word(s.kind));
      EXPECT_EQ(row->second.fallback, default_text(s));
      EXPECT_EQ(row->second.applies, k->facts().title);
      if (s.kind != devices::SettingKind::boolean) {
        EXPECT_NE(row->second.meaning.find(std::string(s.range)), std::string::npos) << row->second.meaning;
      }
      if (!s.parameter.empty()) {
        EXPECT_NE(row->second.meaning.find(std::string(s.parameter)), std::string::npos) << row->second.meaning;
      }
    }
  }
}

TEST(ScenarioSettingsDocs, TheTableNamesNoUndeclaredDriveSetting) {
  // The keys every device has (the scenario reader's own, not a drive's declarations).
  const std::vector<std::string> generic = {"name",        "type",        "bus", "phase", "jitter", "initialised",
                                            "watchdog_ms", "watchdog_reaction", "lustbus"};
  const auto declared = devices::declared_setting_names();
  for (const auto& [key, row] : device_table()) {
    const bool known = std::find(generic.begin(), generic.end(), key) != generic.end() ||
                       std::find(declared.begin(), declared.end(), key) != declared.end();
    EXPECT_TRUE(known) << "docs/scenarios.md lists '" << key << "', which no drive declares";
  }
}

}  // namespace
}  // namespace ibs::sim
