// Error-test helpers: small documents in both formats whose lines are known by construction.
//
// TOML: base() is 7 lines (duration, device "m" = MC6000, device "v" = VF1000), so in device(),
// bus(), entry() and random() the body starts on line 9 (line 8 holds the table header).
// JSON: in device() the device object starts on line 4, in bus() and random() the members start
// on line 4, in entries() the first entry starts on line 5.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "ibs/sim/scenario.hpp"

namespace ibs::sim::test {

inline std::string toml_error(const std::string& text) {
  try {
    (void)parse_scenario_toml(text, "s.toml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "no error";
}

inline std::string json_error(const std::string& text) {
  try {
    (void)parse_scenario_json(text, "s.json");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "no error";
}

inline std::string at_toml(int line, const std::string& what) {
  return "s.toml:" + std::to_string(line) + ": " + what;
}
inline std::string at_json(int line, const std::string& what) {
  return "s.json:" + std::to_string(line) + ": " + what;
}

// Both documents are refused with `what` on their lines (`json_what` when the JSON message
// differs, e.g. "an object" for "a table").
inline ::testing::AssertionResult refused(const std::string& toml_text, int toml_line,
                                          const std::string& json_text, int json_line,
                                          const std::string& what,
                                          const std::string& json_what = {}) {
  const std::string want_toml = at_toml(toml_line, what);
  const std::string want_json = at_json(json_line, json_what.empty() ? what : json_what);
  const std::string got_toml = toml_error(toml_text);
  const std::string got_json = json_error(json_text);
  if (got_toml == want_toml && got_json == want_json) return ::testing::AssertionSuccess();
  auto r = ::testing::AssertionFailure();
  if (got_toml != want_toml) r << "\nTOML want: " << want_toml << "\n     got:  " << got_toml;
  if (got_json != want_json) r << "\nJSON want: " << want_json << "\n     got:  " << got_json;
  return r;
}

namespace tdoc {
inline const std::string kBase =
    "duration = \"1 s\"\n"
    "[[device]]\n"
    "name = \"m\"\n"
    "type = \"mc6000\"\n"
    "[[device]]\n"
    "name = \"v\"\n"
    "type = \"vf1000\"\n";
// Top-level keys first (line 1 on), then one MC6000 "m".
inline std::string top(const std::string& keys) {
  return keys + "[[device]]\nname = \"m\"\ntype = \"mc6000\"\n";
}
inline std::string device(const std::string& body) {
  return kBase + "[[device]]\n" + body;
}
inline std::string bus(const std::string& body) {
  return kBase + "[bus]\n" + body;
}
inline std::string random(const std::string& body) {
  return kBase + "[random_faults]\n" + body;
}
inline std::string entry(const std::string& body) {
  return kBase + "[[timeline]]\n" + body;
}
}  // namespace tdoc

namespace jdoc {
// Top-level members from line 2 on (each ending in ",\n"), then one MC6000 "m".
inline std::string top(const std::string& members) {
  return "{\n" + members + " \"device\": [{\"name\": \"m\", \"type\": \"mc6000\"}]\n}";
}
inline std::string device(const std::string& object) {
  return "{\"duration\": \"1 s\",\n"
         " \"device\": [{\"name\": \"m\", \"type\": \"mc6000\"},\n"
         "            {\"name\": \"v\", \"type\": \"vf1000\"},\n" +
         object + "]}";
}
inline std::string table(const std::string& key, const std::string& members) {
  return "{\"duration\": \"1 s\",\n"
         " \"device\": [{\"name\": \"m\", \"type\": \"mc6000\"}, {\"name\": \"v\", \"type\": "
         "\"vf1000\"}],\n"
         " \"" +
         key + "\": {\n" + members + "}}";
}
inline std::string bus(const std::string& members) {
  return table("bus", members);
}
inline std::string random(const std::string& members) {
  return table("random_faults", members);
}
inline std::string entries(const std::string& entries) {
  return "{\"duration\": \"1 s\",\n"
         " \"device\": [{\"name\": \"m\", \"type\": \"mc6000\"},\n"
         "            {\"name\": \"v\", \"type\": \"vf1000\"}],\n"
         " \"timeline\": [\n" +
         entries + "]}";
}
}  // namespace jdoc

}  // namespace ibs::sim::test
