// The VCD writer against a minimal reader of IEEE 1364-2005 section 18 written here: header
// structure, identifier codes, values at their times, only changes written, the value formats.
#include "ibs/vcd/vcd_writer.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <vector>

namespace ibs::vcd {
namespace {

// ---------------------------------------------------------------------------------------------
// A minimal VCD reader: the declaration commands, then times, $dumpvars and value changes.

struct Var {
  std::string type;
  unsigned width = 0;
  std::string id;
  std::string path;  // scopes and reference, '.'-separated
};

struct Change {
  std::int64_t time = 0;
  std::string id;
  char kind = 0;      // 's' scalar, 'b' vector, 'r' real
  std::string value;  // as written, without the kind letter
  bool in_dumpvars = false;
};

struct Dump {
  std::vector<std::string> commands;  // declaration keywords in order, "$date" .. "$enddefinitions"
  std::map<std::string, std::string> texts;  // "$date" -> its text, ...
  std::vector<Var> vars;
  std::vector<std::int64_t> times;  // every #time, in order
  std::vector<Change> changes;

  const Var& var(const std::string& path) const {
    for (const Var& v : vars) {
      if (v.path == path) return v;
    }
    throw std::runtime_error("no var " + path);
  }
  // The value of a signal at a time: its last change at or before it.
  std::string at(const std::string& path, std::int64_t t) const {
    const std::string& id = var(path).id;
    std::string v = "<none>";
    for (const Change& c : changes) {
      if (c.id == id && c.time <= t) v = c.value;
    }
    return v;
  }
  std::vector<Change> of(const std::string& path) const {
    const std::string& id = var(path).id;
    std::vector<Change> out;
    for (const Change& c : changes) {
      if (c.id == id) out.push_back(c);
    }
    return out;
  }
};

std::string text_until_end(std::istream& in) {
  std::string text;
  std::string tok;
  while (in >> tok) {
    if (tok == "$end") return text;
    if (!text.empty()) text += ' ';
    text += tok;
  }
  throw std::runtime_error("missing $end");
}

Dump parse(const std::string& vcd) {
  Dump d;
  std::istringstream in(vcd);
  std::string tok;
  std::vector<std::string> scopes;
  bool defined = false;
  while (!defined && in >> tok) {
    d.commands.push_back(tok);
    if (tok == "$date" || tok == "$version" || tok == "$comment" || tok == "$timescale") {
      d.texts[tok] = text_until_end(in);
    } else if (tok == "$scope") {
      std::string type;
      std::string name;
      std::string end;
      in >> type >> name >> end;
      if (type != "module" || end != "$end") throw std::runtime_error("bad $scope");
      scopes.push_back(name);
    } else if (tok == "$upscope") {
      in >> tok;
      if (tok != "$end" || scopes.empty()) throw std::runtime_error("bad $upscope");
      scopes.pop_back();
    } else if (tok == "$var") {
      Var v;
      std::string end;
      std::string ref;
      in >> v.type >> v.width >> v.id >> ref >> end;
      if (end != "$end") throw std::runtime_error("bad $var " + ref);
      for (const std::string& s : scopes) v.path += s + '.';
      v.path += ref;
      d.vars.push_back(v);
    } else if (tok == "$enddefinitions") {
      in >> tok;
      if (tok != "$end") throw std::runtime_error("bad $enddefinitions");
      if (!scopes.empty()) throw std::runtime_error("scope left open");
      defined = true;
    } else {
      throw std::runtime_error("unexpected declaration token " + tok);
    }
  }
  if (!defined) throw std::runtime_error("no $enddefinitions");

  std::int64_t time = -1;
  bool in_dump = false;
  while (in >> tok) {
    if (tok[0] == '#') {
      time = std::stoll(tok.substr(1));
      d.times.push_back(time);
    } else if (tok == "$dumpvars") {
      in_dump = true;
    } else if (tok == "$end") {
      if (!in_dump) throw std::runtime_error("$end outside $dumpvars");
      in_dump = false;
    } else if (tok[0] == 'b' || tok[0] == 'r') {
      Change c{time, "", tok[0], tok.substr(1), in_dump};
      in >> c.id;
      d.changes.push_back(c);
    } else if (tok[0] == '0' || tok[0] == '1' || tok[0] == 'x' || tok[0] == 'z') {
      d.changes.push_back({time, tok.substr(1), 's', tok.substr(0, 1), in_dump});
    } else {
      throw std::runtime_error("unexpected value token " + tok);
    }
    if (time < 0) throw std::runtime_error("value before the first time");
  }
  return d;
}

std::uint64_t binary(const std::string& bits) {
  std::uint64_t v = 0;
  for (const char c : bits) v = (v << 1U) | (c == '1' ? 1U : 0U);
  return v;
}

// ---------------------------------------------------------------------------------------------
// A small recording shaped like the simulator's: one module per device.

enum class DriveState : std::uint8_t { not_ready, startup_inhibit, ready, on, enabled };

struct Recording {
  std::ostringstream out;
  VcdWriter w{out, VcdHeader{"2026-11-21 12:00", "", "ibs simulator test"}};
  WireSignal control;
  WireSignal status;
  WireSignal reached;
  RealSignal speed;
  StateSignal state;
  WireSignal vf_control;
  RealSignal vf_hz;

  Recording() {
    w.begin_scope("bus");
    w.begin_scope("mc6000");
    control = w.add_wire("control_word", 16);
    status = w.add_wire("status_word", 16, 0x0240);
    reached = w.add_wire("reference_reached", 1);
    speed = w.add_real("speed_rpm");
    state =
        w.add_state("drive_state", {"NOT READY", "START-UP INHIBIT", "READY", "ON", "ENABLED"}, 1);
    w.end_scope();
    w.begin_scope("vf1000");
    vf_control = w.add_wire("control_word", 16);
    vf_hz = w.add_real("frequency_hz", 0.0);
    w.end_scope();
    w.end_scope();
  }
};

TEST(VcdWriter, HeaderHasTheDeclarationCommandsInOrder) {
  Recording r;
  r.w.finish();
  const Dump d = parse(r.out.str());
  const std::vector<std::string> expected{
      "$date",  "$version", "$comment", "$timescale", "$scope",   "$scope",
      "$var",   "$var",     "$var",     "$var",       "$var",     "$upscope",
      "$scope", "$var",     "$var",     "$upscope",   "$upscope", "$enddefinitions"};
  EXPECT_EQ(d.commands, expected);
  EXPECT_EQ(d.texts.at("$date"), "2026-11-21 12:00");
  EXPECT_EQ(d.texts.at("$version").rfind("ibs ", 0), 0U) << d.texts.at("$version");
  EXPECT_EQ(d.texts.at("$comment"), "ibs simulator test");
  EXPECT_EQ(d.texts.at("$timescale"), "1ns");
  ASSERT_EQ(d.vars.size(), 7U);
  EXPECT_EQ(d.vars[0].path, "bus.mc6000.control_word");
  EXPECT_EQ(d.vars[0].type, "wire");
  EXPECT_EQ(d.vars[0].width, 16U);
  EXPECT_EQ(d.var("bus.mc6000.reference_reached").width, 1U);
  EXPECT_EQ(d.var("bus.mc6000.speed_rpm").type, "real");
  EXPECT_EQ(d.var("bus.mc6000.speed_rpm").width, 64U);
  // Five states need 3 bits, rounded up to one hex digit.
  EXPECT_EQ(d.var("bus.mc6000.drive_state").width, 4U);
  EXPECT_EQ(d.var("bus.vf1000.control_word").path, "bus.vf1000.control_word");
}

TEST(VcdWriter, EmptyDateAndCommentAreLeftOutAndTheVersionDefaults) {
  std::ostringstream out;
  {
    VcdWriter w(out);
    w.add_wire("x", 1);
  }  // the destructor finishes the dump
  const Dump d = parse(out.str());
  EXPECT_EQ(d.commands,
            (std::vector<std::string>{"$version", "$timescale", "$var", "$enddefinitions"}));
  EXPECT_EQ(d.texts.at("$version").rfind("ibs ", 0), 0U);
  ASSERT_EQ(d.changes.size(), 1U);
  EXPECT_EQ(d.changes[0].value, "0");
}

TEST(VcdWriter, IdentifiersAreUniquePrintableAndMatchTheirSignals) {
  Recording r;
  r.w.finish();
  const Dump d = parse(r.out.str());
  std::set<std::string> ids;
  for (const Var& v : d.vars) {
    EXPECT_TRUE(ids.insert(v.id).second) << v.id;
    for (const char c : v.id) {
      EXPECT_GE(c, 33);
      EXPECT_LE(c, 126);
    }
  }
  EXPECT_EQ(d.var("bus.mc6000.status_word").id, r.w.identifier(r.status));
  EXPECT_EQ(r.w.path(r.status), "bus.mc6000.status_word");
  EXPECT_EQ(r.w.path(r.vf_hz), "bus.vf1000.frequency_hz");
}

TEST(VcdWriter, IdentifierCodesAreBijectiveBase94) {
  EXPECT_EQ(identifier_code(0), "!");
  EXPECT_EQ(identifier_code(1), "\"");
  EXPECT_EQ(identifier_code(93), "~");
  EXPECT_EQ(identifier_code(94), "!!");
  EXPECT_EQ(identifier_code(95), "\"!");
  EXPECT_EQ(identifier_code(94 + 93), "~!");
  EXPECT_EQ(identifier_code(94 + 94), "!\"");
  EXPECT_EQ(identifier_code(94 + 94 * 94 - 1), "~~");
  EXPECT_EQ(identifier_code(94 + 94 * 94), "!!!");
  std::unordered_set<std::string> seen;
  for (std::size_t i = 0; i < 200000; ++i) {
    const std::string id = identifier_code(i);
    ASSERT_TRUE(seen.insert(id).second) << i;
    for (const char c : id) ASSERT_TRUE(c >= '!' && c <= '~') << i;
  }
}

TEST(VcdWriter, ValuesAtTheirTimes) {
  Recording r;
  // 5.3.4 start-up: shutdown, ready, enable, reference reached.
  r.w.change(r.control, 0x0006U);
  r.w.advance(726us);
  r.w.change(r.status, 0x0231U);
  r.w.change(r.state, DriveState::ready);
  r.w.advance(1452us);
  r.w.change(r.control, 0x000FU);
  r.w.advance(2178us);
  r.w.change(r.status, 0x0237U);
  r.w.change(r.state, DriveState::enabled);
  r.w.change(r.speed, 1250.5);
  r.w.advance(214ms);
  r.w.change(r.status, 0x0437U);
  r.w.change(r.reached, 1U);
  r.w.change(r.speed, 2500.25);
  r.w.advance(1s);
  r.w.finish();
  const Dump d = parse(r.out.str());

  EXPECT_EQ(d.times,
            (std::vector<std::int64_t>{0, 726000, 1452000, 2178000, 214000000, 1000000000}));
  // $dumpvars at time 0 holds every signal, with the changes made before the first advance.
  std::size_t dumped = 0;
  for (const Change& c : d.changes) {
    if (c.in_dumpvars) {
      ++dumped;
      EXPECT_EQ(c.time, 0);
    }
  }
  EXPECT_EQ(dumped, 7U);
  EXPECT_EQ(binary(d.at("bus.mc6000.control_word", 0)), 0x0006U);
  EXPECT_EQ(binary(d.at("bus.mc6000.status_word", 0)), 0x0240U);
  EXPECT_EQ(binary(d.at("bus.mc6000.drive_state", 0)), 1U);
  EXPECT_EQ(binary(d.at("bus.mc6000.status_word", 726000)), 0x0231U);
  EXPECT_EQ(binary(d.at("bus.mc6000.drive_state", 726000)), 2U);
  EXPECT_EQ(binary(d.at("bus.mc6000.control_word", 1452000)), 0x000FU);
  EXPECT_EQ(binary(d.at("bus.mc6000.status_word", 2178000)), 0x0237U);
  EXPECT_EQ(d.at("bus.mc6000.speed_rpm", 2178000), "1250.5");
  EXPECT_EQ(binary(d.at("bus.mc6000.status_word", 214000000)), 0x0437U);
  EXPECT_EQ(d.at("bus.mc6000.reference_reached", 213999999), "0");
  EXPECT_EQ(d.at("bus.mc6000.reference_reached", 214000000), "1");
  EXPECT_EQ(d.at("bus.mc6000.speed_rpm", 214000000), "2500.25");
  // The closing time carries no change: finish() marks how far the dump reaches.
  for (const Change& c : d.changes) EXPECT_LT(c.time, 1000000000);
  EXPECT_EQ(r.w.changes_written(), 9U);  // 2 + 1 + 3 + 3 after $dumpvars
}

TEST(VcdWriter, ValueFormats) {
  Recording r;
  r.w.change(r.speed, -0.05);
  r.w.advance(1ns);
  r.w.change(r.status, 0x0237U);
  r.w.change(r.control, 0U);  // unchanged: nothing
  r.w.change(r.speed, 1e-9);
  r.w.change(r.reached, 1U);
  r.w.advance(2ns);
  r.w.change(r.status, 0x8000U);
  r.w.advance(3ns);
  r.w.finish();
  const std::string text = r.out.str();
  const std::string st{r.w.identifier(r.status)};
  const std::string sp{r.w.identifier(r.speed)};
  const std::string rr{r.w.identifier(r.reached)};
  const std::string cw{r.w.identifier(r.control)};
  EXPECT_NE(text.find("\nb0 " + cw + "\n"), std::string::npos) << text;           // zero
  EXPECT_NE(text.find("\nb1001000000 " + st + "\n"), std::string::npos) << text;  // 0240H
  EXPECT_NE(text.find("\nb1000110111 " + st + "\n"), std::string::npos) << text;  // 0237H
  EXPECT_NE(text.find("\nb1000000000000000 " + st + "\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nr-0.05 " + sp + "\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nr1e-09 " + sp + "\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n1" + rr + "\n"), std::string::npos) << text;  // scalar: no blank
  EXPECT_NE(text.find("#0\n$dumpvars\n"), std::string::npos) << text;

  // Every vector value drops its leading zeros; every real reads back.
  const Dump d = parse(text);
  for (const Change& c : d.changes) {
    if (c.kind == 'b') {
      EXPECT_TRUE(c.value == "0" || c.value[0] == '1') << c.value;
    }
    if (c.kind == 'r') {
      EXPECT_NO_THROW((void)std::stod(c.value)) << c.value;
    }
  }
  EXPECT_EQ(std::stod(d.at("bus.mc6000.speed_rpm", 2)), 1e-9);
}

TEST(VcdWriter, RealsReadBackExactly) {
  std::ostringstream out;
  VcdWriter w(out);
  const RealSignal s = w.add_real("v");
  const std::vector<double> values{0.1, 2500.25, -1.0 / 3.0, 6.02214076e23, 5e-324, 1e300};
  for (std::size_t i = 0; i < values.size(); ++i) {
    w.change(s, values[i]);
    w.advance(Time{static_cast<std::int64_t>(i + 1)});
  }
  w.finish();
  const Dump d = parse(out.str());
  const std::vector<Change> c = d.of("v");
  ASSERT_EQ(c.size(), values.size());
  // strtod, not stod: stod refuses the subnormal 5e-324 (ERANGE).
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(std::strtod(c[i].value.c_str(), nullptr), values[i]) << c[i].value;
  }
}

TEST(VcdWriter, OnlyChangesAreWritten) {
  std::ostringstream out;
  VcdWriter w(out);
  w.begin_scope("m");
  const WireSignal a = w.add_wire("a", 16);
  const WireSignal b = w.add_wire("b", 8);
  const RealSignal x = w.add_real("x", 1.5);
  w.end_scope();
  std::uint64_t va = 0;
  for (std::int64_t t = 1; t <= 1000; ++t) {
    // a changes every 3rd step, b never leaves 0 at a step's end, x is written unchanged.
    if (t % 3 == 0) va = (va + 1) & 0xFFFFU;
    w.change(a, va);
    w.change(b, 7U);  // changed and changed back within the step
    w.change(b, 0U);
    w.change(x, 1.5);
    w.advance(Time{t * 1000});
  }
  w.finish();
  const Dump d = parse(out.str());
  // No value equal to the one before it, no time without a change but the closing one.
  std::map<std::string, std::string> last;
  std::map<std::int64_t, int> per_time;
  for (const Change& c : d.changes) {
    if (!c.in_dumpvars) {
      EXPECT_NE(last[c.id], c.value) << c.id << " at " << c.time;
      ++per_time[c.time];
    }
    last[c.id] = c.value;
  }
  for (std::size_t i = 1; i + 1 < d.times.size(); ++i) {
    EXPECT_LT(d.times[i - 1], d.times[i]);
    EXPECT_EQ(per_time[d.times[i]], 1) << d.times[i];
  }
  EXPECT_EQ(d.of("m.a").size(), 1U + 333U);
  EXPECT_EQ(d.of("m.b").size(), 1U);
  EXPECT_EQ(d.of("m.x").size(), 1U);
  EXPECT_EQ(w.changes_written(), 333U);
  EXPECT_EQ(d.times.back(), 1000000);
}

TEST(VcdWriter, SameTimeAdvanceKeepsTheStepOpen) {
  std::ostringstream out;
  VcdWriter w(out);
  const WireSignal a = w.add_wire("a", 4);
  w.advance(10ns);
  w.change(a, 3U);
  w.advance(10ns);  // same time: still the same step
  w.change(a, 5U);
  w.advance(20ns);
  w.finish();
  const Dump d = parse(out.str());
  const std::vector<Change> c = d.of("a");
  ASSERT_EQ(c.size(), 2U);
  EXPECT_EQ(c[1].time, 10);
  EXPECT_EQ(c[1].value, "101");
}

TEST(VcdWriter, ManyChangesAllArrive) {
  // 256 signals x 4000 steps, every signal changing every step: about a million changes.
  std::ostringstream out;
  VcdWriter w(out);
  std::vector<WireSignal> s;
  for (int m = 0; m < 16; ++m) {
    w.begin_scope("dev" + std::to_string(m));
    for (int i = 0; i < 16; ++i) s.push_back(w.add_wire("w" + std::to_string(i), 16));
    w.end_scope();
  }
  constexpr std::int64_t kSteps = 4000;
  for (std::int64_t t = 1; t <= kSteps; ++t) {
    for (std::size_t i = 0; i < s.size(); ++i) {
      w.change(s[i], static_cast<std::uint64_t>(t + static_cast<std::int64_t>(i)) & 0xFFFFU);
    }
    w.advance(Time{t * 726000});
  }
  w.finish();
  // The first step's values are those at time 0: the $dumpvars block.
  EXPECT_EQ(w.changes_written(), s.size() * (kSteps - 1));
  const Dump d = parse(out.str());
  EXPECT_EQ(d.changes.size(), s.size() * kSteps);
  EXPECT_EQ(binary(d.at("dev15.w15", (kSteps - 1) * 726000)),
            static_cast<std::uint64_t>(kSteps + 255));
}

TEST(VcdWriter, TranslateFilterMatchesTheHexDisplay) {
  std::ostringstream out;
  VcdWriter w(out);
  w.begin_scope("mc6000");
  const StateSignal few = w.add_state("st", {"NOT READY", "READY", "ENABLED"});
  std::vector<std::string> many;
  for (int i = 0; i < 17; ++i) many.push_back("S" + std::to_string(i));
  const StateSignal lots = w.add_state("big", many);
  const StateSignal one = w.add_state("one", {"ONLY"});
  w.end_scope();
  EXPECT_EQ(w.width(few), 4U);
  EXPECT_EQ(w.width(lots), 8U);
  EXPECT_EQ(w.width(one), 4U);
  EXPECT_EQ(w.translate_filter(few),
            "# gtkwave translate filter for mc6000.st (4-bit vector, hex display)\n"
            "# Edit > Data Format > Translate Filter File > Enable and Select (docs/vcd.md)\n"
            "0 NOT READY\n1 READY\n2 ENABLED\n");
  const std::string big = w.translate_filter(lots);
  EXPECT_NE(big.find("\n00 S0\n"), std::string::npos) << big;
  EXPECT_NE(big.find("\n0A S10\n"), std::string::npos) << big;
  EXPECT_NE(big.find("\n10 S16\n"), std::string::npos) << big;
  w.change(lots, 16U);
  w.advance(1ns);
  w.finish();
  const Dump d = parse(out.str());
  EXPECT_EQ(d.var("mc6000.big").width, 8U);
  EXPECT_EQ(binary(d.at("mc6000.big", 0)), 16U);
}

TEST(VcdWriter, MisuseThrowsWithTheSignalNamed) {
  std::ostringstream out;
  VcdWriter w(out);
  w.begin_scope("m");
  const WireSignal a = w.add_wire("a", 4);
  const StateSignal st = w.add_state("st", {"A", "B"});
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const VcdError& e) {
      return std::string(e.what());
    }
    return std::string("<no exception>");
  };
  EXPECT_EQ(message([&] { w.add_wire("a", 4); }), "vcd: signal 'm.a' is declared twice");
  EXPECT_EQ(message([&] { w.add_wire("has space", 1); }),
            "vcd: signal name 'has space' must be letters, digits and '_' only, not empty");
  EXPECT_EQ(message([&] { w.add_wire("w0", 0); }),
            "vcd: wire 'w0' is 0 bits wide, the range is 1..64");
  EXPECT_EQ(message([&] { w.add_wire("w65", 65); }),
            "vcd: wire 'w65' is 65 bits wide, the range is 1..64");
  EXPECT_EQ(message([&] { w.add_wire("w2", 2, 4); }),
            "vcd: initial value 4 of wire 'w2' does not fit its 2 bits");
  EXPECT_EQ(message([&] { w.add_state("e", {}); }), "vcd: state 'e' has no states");
  EXPECT_EQ(message([&] { w.add_state("e", {" X"}); }),
            "vcd: state 'e': state name ' X' must be printable ASCII without leading or trailing "
            "blanks, not empty");
  // The scope is still open.
  EXPECT_EQ(message([&] { w.advance(1ns); }),
            "vcd: scope 'm' is still open at the end of the definitions");
  w.end_scope();
  EXPECT_EQ(message([&] { w.end_scope(); }), "vcd: end_scope() without an open scope");
  EXPECT_EQ(message([&] { w.change(a, 16U); }), "vcd: value 16 does not fit the 4-bit wire 'm.a'");
  EXPECT_EQ(message([&] { w.change(st, 2U); }),
            "vcd: state 2 is not one of the 2 states of 'm.st'");
  EXPECT_EQ(message([&] { w.add_wire("late", 1); }),
            "vcd: cannot declare wire 'late' after recording started (declare every signal first)");
  w.advance(5ns);
  EXPECT_EQ(message([&] { w.advance(4ns); }),
            "vcd: advance to 4 ns goes back from the current time 5 ns");
  EXPECT_EQ(message([&] { w.change(RealSignal{0}, 1.0); }),
            "vcd: real handle 0 is not from this writer");
  w.finish();
  EXPECT_EQ(message([&] { w.change(a, 1U); }), "vcd: the dump is finished");
  EXPECT_NO_THROW(w.finish());
}

TEST(VcdWriter, FailedStreamIsReported) {
  std::ostringstream out;
  VcdWriter w(out);
  w.add_wire("a", 1);
  out.setstate(std::ios::badbit);
  EXPECT_THROW(w.finish(), VcdError);
}

}  // namespace
}  // namespace ibs::vcd
