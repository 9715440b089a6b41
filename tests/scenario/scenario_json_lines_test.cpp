// Lines in JSON come from a position-tracking SAX pass (scenario_json.cpp); these pin the cases
// where a naive count would be off: values on the line after their key, numbers that end a line
// (the lexer reads one character ahead), CRLF, escaped newlines. Syntax errors of both formats
// name their line too.
#include <gtest/gtest.h>

#include <string>

#include "ibs/sim/scenario.hpp"
#include "scenario_errors.hpp"

namespace ibs::sim::test {
namespace {

const std::string kDevice = " \"device\": [{\"name\": \"m\", \"type\": \"mc6000\"}],\n";

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

TEST(ScenarioJsonLines, ValueOnTheLineAfterItsKey) {
  EXPECT_EQ(json_error("{\"name\":\n\n 5,\n" + kDevice + " \"duration\": \"1 s\"}"),
            at_json(3, "'name' must be a string, not an integer"));
  // The unknown key is reported on the key's line, not the value's.
  EXPECT_EQ(json_error("{\"nmae\":\n \"x\",\n" + kDevice + " \"duration\": \"1 s\"}"),
            at_json(1, "unknown key 'nmae' at the top level (did you mean 'name'?)"));
}

TEST(ScenarioJsonLines, NumberAtTheEndOfALine) {
  // The lexer has read the newline after 13 when the value arrives.
  EXPECT_EQ(
      json_error("{\"duration\": \"1 s\",\n \"device\": [{\"name\": \"m\", \"type\": \"mc6000\",\n"
                 " \"supi\": 13\n}]}"),
      at_json(3, "device 'm': 405-SUPI = 13 is out of range (0..12, INTERBUS manual 3.2.2)"));
  EXPECT_EQ(
      json_error("{\"duration\": \"1 s\",\n \"device\": [{\"name\": \"m\", \"type\": \"mc6000\",\n"
                 " \"supi\": 13\n\n\n}]}"),
      at_json(3, "device 'm': 405-SUPI = 13 is out of range (0..12, INTERBUS manual 3.2.2)"));
  EXPECT_EQ(
      json_error("{\"duration\": \"1 s\",\n \"device\": [{\"name\": \"m\", \"type\": \"mc6000\",\n"
                 " \"supi\": -13.5\n}]}"),
      at_json(3, "'supi' must be an integer, not a fractional number"));
  EXPECT_EQ(
      json_error("{\"duration\": \"1 s\",\n \"device\": [{\"name\": \"m\", \"type\": \"mc6000\",\n"
                 " \"initialised\": null\n}]}"),
      at_json(3, "'initialised' must be true or false, not null"));
}

TEST(ScenarioJsonLines, CrLfAndTabs) {
  EXPECT_EQ(
      json_error("{\r\n\t\"duration\": \"1 s\",\r\n" + kDevice + "\r\n\t\"name\":\t\r\n\t7\r\n}"),
      at_json(6, "'name' must be a string, not an integer"));
  EXPECT_EQ(toml_error("duration = \"1 s\"\r\n\r\nname = 7\r\n[[device]]\r\nname = \"m\"\r\n"
                       "type = \"mc6000\"\r\n"),
            at_toml(3, "'name' must be a string, not an integer"));
}

TEST(ScenarioJsonLines, EscapedNewlinesAreNotLines) {
  const std::string device = " \"device\": [{\"name\": \"m\", \"type\": \"mc6000\"}]}";
  EXPECT_EQ(json_error("{\"name\": \"a\\nb\\nc\", \"duration\": 1,\n" + device),
            at_json(1,
                    "'duration' must be a time string with a unit, e.g. \"250 ms\", not an "
                    "integer"));
  // Names may not hold control characters at all; the line is still the string's.
  EXPECT_EQ(json_error("{\"name\": \"a\\nb\\nc\", \"duration\": \"1 s\",\n" + device),
            at_json(1, "'name' must not hold control characters"));
}

TEST(ScenarioJsonLines, MultiLineTomlStrings) {
  EXPECT_EQ(toml_error("name = \"\"\"\nfirst\nsecond\n\"\"\"\nduration = 1\n"),
            at_toml(5,
                    "'duration' must be a time string with a unit, e.g. \"250 ms\", not an "
                    "integer"));
}

TEST(ScenarioJsonLines, EntrySourceLines) {
  const Scenario s =
      parse_scenario_json("{\"duration\": \"1 s\",\n" + kDevice +
                              " \"timeline\": [\n"
                              "  {\"at\": \"0 s\", \"device\": \"m\", \"state\": \"on\"},\n"
                              "\n"
                              "  {\n"
                              "   \"at\": \"1 s\", \"device\": \"m\", \"state\": \"ready\"}\n"
                              " ]}",
                          "lines.json");
  ASSERT_EQ(s.timeline.size(), 2U);
  EXPECT_EQ(s.timeline[0].source_line, 4U);
  EXPECT_EQ(s.timeline[1].source_line, 6U);
}

TEST(ScenarioSyntax, TomlSyntaxErrorsNameTheirLine) {
  EXPECT_TRUE(
      starts_with(toml_error("duration = \"1 s\"\nname = \n"), "s.toml:2: TOML syntax error: "))
      << toml_error("duration = \"1 s\"\nname = \n");
  EXPECT_TRUE(starts_with(toml_error("duration = \"1 s\"\n\nduration = \"2 s\"\n"),
                          "s.toml:3: TOML syntax error: "));
  EXPECT_TRUE(starts_with(toml_error("duration = \"1 s\"\nname = \"abc\n"),
                          "s.toml:2: TOML syntax error: "));
  EXPECT_TRUE(starts_with(toml_error("[bus]\n[bus]\n"), "s.toml:2: TOML syntax error: "));
}

TEST(ScenarioSyntax, JsonSyntaxErrorsNameTheirLine) {
  EXPECT_EQ(json_error(""), at_json(1,
                                    "JSON syntax error: syntax error while parsing value - "
                                    "unexpected end of input; expected '[', '{', or a literal"));
  EXPECT_TRUE(
      starts_with(json_error("{\"duration\": \"1 s\",\n}"), "s.json:2: JSON syntax error: "));
  EXPECT_TRUE(starts_with(json_error("{\"duration\": \"1 s\"\n \"name\": \"x\"}"),
                          "s.json:2: JSON syntax error: "));
  EXPECT_TRUE(starts_with(json_error("{\"duration\": \"1 s\",\n \"name\": \"abc\n\"}"),
                          "s.json:2: JSON syntax error: "));
  EXPECT_TRUE(
      starts_with(json_error("{\"duration\": \"1 s\"}\n\nx"), "s.json:3: JSON syntax error: "));
  EXPECT_TRUE(starts_with(json_error("{\"name\": \"\xff\"}"), "s.json:1: JSON syntax error: "));
  EXPECT_EQ(json_error("{\n\"duration\": 1e400}"),
            at_json(2, "JSON syntax error: number overflow parsing '1e400'"));
  // No trace of nlohmann's own prefix and position.
  EXPECT_EQ(json_error("{\"duration\": \"1 s\",\n}").find("[json.exception"), std::string::npos);
  EXPECT_EQ(json_error("{\"duration\": \"1 s\",\n}").find("column"), std::string::npos);
}

TEST(ScenarioSyntax, JsonDuplicateKeysAreRefused) {
  EXPECT_EQ(json_error("{\"duration\": \"1 s\",\n \"duration\": \"2 s\"}"),
            at_json(2, "duplicate key 'duration' (first on line 1)"));
  EXPECT_EQ(
      json_error("{\"duration\": \"1 s\",\n \"device\": [{\"name\": \"m\",\n\n \"name\": \"n\"}]}"),
      at_json(4, "duplicate key 'name' (first on line 2)"));
}

TEST(ScenarioSyntax, JsonIntegersBeyondInt64) {
  EXPECT_EQ(
      json_error("{\"duration\": \"1 s\",\n \"random_faults\": {\"seed\": 18446744073709551615}}"),
      at_json(2, "the integer 18446744073709551615 is too large (at most 2^63-1)"));
}

TEST(ScenarioSyntax, NestingIsBounded) {
  const std::string deep_json = "{\"x\": " + std::string(100, '[') + std::string(100, ']') + "}";
  EXPECT_EQ(json_error(deep_json), at_json(1, "values nested too deeply"));
  const std::string deep_toml = "x = " + std::string(100, '[') + std::string(100, ']') + "\n";
  EXPECT_EQ(toml_error(deep_toml), at_toml(1, "values nested too deeply"));
}

}  // namespace
}  // namespace ibs::sim::test
