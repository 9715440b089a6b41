// ../shared/specs/trace-format.md: reading, writing and refusing `ibs-trace 1` files.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>

#include "ibs/interbus/trace.hpp"

namespace ibs::trace {
namespace {

// The names the layers above give the format (the drive registry's kinds, DRIVECOM's targets).
constexpr std::string_view kDevices[] = {"vf1000", "mc6000"};
constexpr std::string_view kTargets[] = {"start-up-inhibit", "ready", "on", "enabled"};
// The drives' header settings (the registry gives their declarations' names).
constexpr std::string_view kSettings[] = {"supi", "ibcnf"};
const Vocabulary kVocabulary{kDevices, kTargets, kSettings};

constexpr const char* kInquiry = R"(# format: ibs-trace 1
# device: vf1000
# words: comm
# request: read 0x16
0, 0000, 8000, master idle, inverter ready for parameter access
1, 2416, 8000, value inquiry for parameter 22 (toggle 1)
2, 2416, A003, inverter sends high byte 03
3, 0400, A003, master has read the byte (toggle 0)
4, 0400, 88E8, inverter sends low byte E8 with ACK
5, 0000, 88E8, master returns to the starting position
6, 0000, 8000, inverter back in wait mode
)";

TEST(TraceFormat, ReadsTheSpecExample) {
  const Trace t = parse(kInquiry, "inq.trace");
  EXPECT_EQ(t.header.device, "vf1000");
  EXPECT_EQ(t.header.words, WordsKind::comm);
  ASSERT_TRUE(t.header.request.has_value());
  EXPECT_EQ(t.header.request->kind, Request::Kind::read);
  EXPECT_EQ(t.header.request->parameter, 22);
  EXPECT_EQ(t.header.request_at, 1U);
  EXPECT_EQ(t.header.max_gap, 100000U);
  EXPECT_TRUE(t.header.settings.empty());  // none given: the drive's defaults apply
  ASSERT_EQ(t.rows.size(), 7U);
  EXPECT_EQ(t.rows[4].s2m[0].value, 0x88E8);
  EXPECT_EQ(t.rows[4].line, 9U);
  EXPECT_EQ(t.rows[4].remark, "inverter sends low byte E8 with ACK");
}

TEST(TraceFormat, RemarksMayContainCommasAndSpacesAreIgnored) {
  const Trace t = parse("# format: ibs-trace 1\n# device: mc6000\n# words: pd\n"
                        "  0 ,  0000 0000 0000 ,0240 0000 0000 ,  a, b, c  \n",
                        "x");
  EXPECT_EQ(t.rows[0].remark, "a, b, c");
  EXPECT_EQ(t.rows[0].m2s.size(), 3U);
}

TEST(TraceFormat, PatternsQuestionMarksAndMasks) {
  const auto w = parse_words("0?37 ???? 0437/FDFF 0a3f", "x", 1);
  ASSERT_EQ(w.size(), 4U);
  EXPECT_EQ(w[0].mask, 0xF0FF);
  EXPECT_TRUE(w[0].matches(0x0537));
  EXPECT_FALSE(w[0].matches(0x0538));
  EXPECT_TRUE(w[1].matches(0x1234));
  EXPECT_TRUE(w[2].matches(0x0637));  // bit 9 ignored
  EXPECT_TRUE(w[2].matches(0x0437));
  EXPECT_FALSE(w[2].matches(0x0436));
  EXPECT_EQ(w[3].value, 0x0A3F);
  EXPECT_EQ(w[0].to_string(), "0?37");
  EXPECT_EQ(w[1].to_string(), "????");
  EXPECT_EQ(w[2].to_string(), "0437/FDFF");
  EXPECT_EQ(w[3].to_string(), "0A3F");
}

TEST(TraceFormat, WriteThenParseRoundTrips) {
  const std::string text = std::string(kInquiry) + "...\n7, 0000, 8000, after a gap\n";
  Trace t = parse(text, "a");
  t.header.init = DeviceStart::initialised;
  t.header.init_given = true;
  t.header.outcome = Outcome{Outcome::Kind::ok, 1000};
  t.header.max_gap = 12;
  t.header.max_gap_given = true;
  const std::string written = write(t);
  const Trace back = parse(written, "b");
  EXPECT_EQ(write(back), written);
  ASSERT_EQ(back.rows.size(), t.rows.size());
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    EXPECT_EQ(back.rows[i].gap, t.rows[i].gap);
    EXPECT_EQ(back.rows[i].step, t.rows[i].step);
    EXPECT_EQ(back.rows[i].m2s, t.rows[i].m2s);
    EXPECT_EQ(back.rows[i].s2m, t.rows[i].s2m);
    EXPECT_EQ(back.rows[i].remark, t.rows[i].remark);
  }
  EXPECT_EQ(back.header.outcome, t.header.outcome);
  EXPECT_EQ(back.header.init, DeviceStart::initialised);
  EXPECT_EQ(back.header.max_gap, 12U);
}

TEST(TraceFormat, RequestsAndOutcomes) {
  EXPECT_EQ(parse_request("write 0x15 500", "x", 1),
            (Request{Request::Kind::write, 0x15, 500, ""}));
  EXPECT_EQ(parse_request("describe 45", "x", 1).kind, Request::Kind::describe);
  EXPECT_EQ(parse_request("state start-up-inhibit", "x", 1, kVocabulary).target, "start-up-inhibit");
  EXPECT_EQ(parse_outcome("ok 0x3E8", "x", 1), (Outcome{Outcome::Kind::ok, 1000}));
  EXPECT_EQ(parse_outcome("timeout", "x", 1).kind, Outcome::Kind::timeout);
}

struct Bad {
  const char* text;
  std::size_t line;
  const char* message;
};

TEST(TraceFormat, MalformedFilesSayFileLineAndWhat) {
  const std::string h = "# format: ibs-trace 1\n# device: vf1000\n# words: comm\n";
  const std::vector<Bad> cases{
      {"", 1, "the first header must be 'format: ibs-trace 1'"},
      {"# device: vf1000\n", 1, "the first header must be 'format: ibs-trace 1'"},
      {"# format: ibs-trace 2\n", 1, "format: 'ibs-trace 2' is not 'ibs-trace 1'"},
      {"# format: ibs-trace 1\n# words: comm\n0, 0000, 8000\n", 3, "header 'device' is missing"},
      {"# format: ibs-trace 1\n# device: vf2000\n", 2, "device: 'vf2000' is not one of vf1000, mc6000"},
      {"# format: ibs-trace 1\n# device: vf1000\n# word: comm\n", 3, "unknown header 'word'"},
      {"# format: ibs-trace 1\n# device: vf1000\n# words: bytes\n", 3, "words: 'bytes' is not one of comm, pd, pcp"},
      {"# format: ibs-trace 1\n# device: vf1000\n# words: comm\n# request: state running\n", 4,
       "state target 'running' is not one of start-up-inhibit, ready, on, enabled"},
      {"# format: ibs-trace 1\n# device: vf1000\n# words: comm\n# request: erase 5\n", 4, "request: 'erase'"},
      {"# format: ibs-trace 1\n# device: vf1000\n# words: comm\n# outcome: maybe\n", 4, "outcome: 'maybe'"},
      {"# format: ibs-trace 1\n# device: vf1000\n# words: comm\n# max-gap: -3\n", 4, "max-gap: '-3'"},
      {"# format: ibs-trace 1\n# device: vf1000\n# words: comm\n# supi: eleven\n", 4, "supi: 'eleven'"},
  };
  for (const auto& c : cases) {
    try {
      parse(c.text, "f.trace", kVocabulary);
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const TraceError& e) {
      EXPECT_EQ(e.line(), c.line) << e.what();
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("f.trace:" + std::to_string(c.line) + ": ", 0), 0U) << what;
      EXPECT_NE(what.find(c.message), std::string::npos) << what;
    }
  }
  const std::vector<Bad> rows{
      {"1, 0000, 8000\n", 4, "the first row must be step 0"},
      {"0, 0000, 8000\n2, 0000, 8000\n", 5, "step 2 should be 1"},
      {"0, 000, 8000\n", 4, "must be exactly four hex digits"},
      {"0, 00G0, 8000\n", 4, "non-hex digit 'G'"},
      {"0, 0000/FF?F, 8000\n", 4, "'?' is not allowed in the mask"},
      {"0, 0000\n", 4, "found 2 field(s)"},
      {"0, , 8000\n", 4, "at least one word"},
      {"x, 0000, 8000\n", 4, "step 'x' is not a decimal step number"},
      {"0, 0000, 8000\n1, 0000 0000, 8000\n", 5, "row has 2 m2s and 1 s2m words; earlier rows have 1 and 1"},
      {"...\n", 4, "a gap '...' cannot be the first row"},
      {"0, 0000, 8000\n...\n", 5, "a gap '...' cannot be the last row"},
      {"0, 0000, 8000\n...\n...\n1, 0000, 8000\n", 6, "two gaps"},
      {"0, 0000, 8000\n# device: mc6000\n", 5, "no data rows"},
  };
  for (const auto& c : rows) {
    try {
      const Trace t = parse(h + c.text, "f.trace", kVocabulary);
      if (std::string(c.message) == "no data rows") continue;  // a '#' line after rows is a comment
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const TraceError& e) {
      EXPECT_EQ(e.line(), c.line) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
  }
}

TEST(TraceFormat, HeaderLikeLineAfterTheFirstRowIsAComment) {
  const Trace t = parse("# format: ibs-trace 1\n# device: vf1000\n# words: comm\n0, 0000, 8000\n"
                        "# device: mc6000\n1, 0000, 8000\n",
                        "x");
  EXPECT_EQ(t.header.device, "vf1000");
  ASSERT_EQ(t.rows[1].comments_before.size(), 1U);
}

TEST(TraceFormat, StepsAfterAGapAreLabels) {
  const Trace t = parse("# format: ibs-trace 1\n# device: vf1000\n# words: comm\n0, 0000, 8000\n"
                        "...\n40, 0000, 8000\n41, 0000, 8000\n",
                        "x");
  EXPECT_EQ(t.rows[2].step, 40U);
  EXPECT_THROW(parse("# format: ibs-trace 1\n# device: vf1000\n# words: comm\n0, 0000, 8000\n"
                     "...\n40, 0000, 8000\n43, 0000, 8000\n",
                     "x"),
               TraceError);
}

TEST(TraceFormat, MissingFileIsAnError) {
  try {
    load("/nonexistent/dir/x.trace");
    FAIL();
  } catch (const TraceError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/dir/x.trace:0: cannot read the file: it does not exist");
  }
}

// Issue 9, defect 6: a header given twice was taken silently (the last one won).
TEST(TraceFormat, AHeaderGivenTwiceIsAnError) {
  for (const char* key : {"device: vf1000", "words: pd", "supi: 3", "ibcnf: 2", "init: fault", "request: read 1",
                          "request-at: 1", "outcome: ok", "max-gap: 5"}) {
    const std::string text = std::string("# format: ibs-trace 1\n# device: mc6000\n# words: pcp\n# ") + key +
                             "\n# " + key + "\n0, 0000, 0000\n";
    const std::string name = std::string(key).substr(0, std::string(key).find(':'));
    try {
      parse(text, "t.trace");
      ADD_FAILURE() << key << " given twice was accepted";
    } catch (const TraceError& e) {
      const std::string first = name == "device" ? "2" : name == "words" ? "3" : "4";
      const std::string line = name == "device" || name == "words" ? "4" : "5";
      EXPECT_EQ(std::string(e.what()), "t.trace:" + line + ": header '" + name + "' given twice (first on line " +
                                           first + ")");
    }
  }
}

// A drive's setting is `# NAME: VALUE`, any name the vocabulary lists: kept with its line, written
// back in the vocabulary's order, so that a header written again reads byte for byte the same.
TEST(TraceFormat, DriveSettingsAreHeadersOfTheVocabulary) {
  const std::string text = "# format: ibs-trace 1\n# device: mc6000\n# words: pd\n# ibcnf: 3\n# supi: 12\n0, 0000, 0000\n";
  const Trace t = parse(text, "s.trace", kVocabulary);
  ASSERT_EQ(t.header.settings.size(), 2U);
  EXPECT_EQ(t.header.settings[0], (HeaderSetting{"supi", 12, 5}));
  EXPECT_EQ(t.header.settings[1], (HeaderSetting{"ibcnf", 3, 4}));
  EXPECT_EQ(write(t), "# format: ibs-trace 1\n# device: mc6000\n# words: pd\n# supi: 12\n# ibcnf: 3\n0, 0000, 0000\n");
  EXPECT_EQ(write(parse(write(t), "again.trace", kVocabulary)), write(t));
  // A name the vocabulary does not list is no header at all.
  try {
    parse("# format: ibs-trace 1\n# device: mc6000\n# words: pd\n# keypad: 1\n0, 0000, 0000\n", "k.trace", kVocabulary);
    ADD_FAILURE() << "accepted";
  } catch (const TraceError& e) {
    EXPECT_EQ(std::string(e.what()), "k.trace:4: unknown header 'keypad'");
  }
  // Set in code: appended, and written.
  Trace u = t;
  u.header.settings.clear();
  u.header.set_setting("supi", 3);
  u.header.set_setting("supi", 4);
  ASSERT_EQ(u.header.settings.size(), 1U);
  EXPECT_EQ(u.header.setting("supi")->value, 4);
  EXPECT_EQ(u.header.setting("ibcnf"), nullptr);
}

// Found by trace_fuzz after the settings became headers: with no vocabulary any key was taken as
// a drive's setting, and a key of NUL bytes gave a message that ended before it began. A setting
// is a header name; any other key is unknown, and the message shows what it holds.
TEST(TraceFormat, AnUnprintableHeaderIsUnknownAndShownAsItIs) {
  const std::string text = std::string("# format: ibs-trace 1\n# device: vf1000\n# words: pd\n#\t") +
                           std::string("\0\0\0uest", 7) + ": state enabled\n0, 0000 0000 0000, 0240 0000 0000\n";
  for (const Vocabulary& v : {Vocabulary{}, kVocabulary}) {
    try {
      parse(text, "n.trace", v);
      ADD_FAILURE() << "accepted";
    } catch (const TraceError& e) {
      EXPECT_EQ(std::string(e.what()), "n.trace:4: unknown header '\\x00\\x00\\x00uest'");
    }
  }
}

// trace-format.md, "Events": `! fault` and `! fault-cleared` between two data rows.
TEST(TraceFormat, EventLinesBetweenRowsAreReadAndWrittenBack) {
  const std::string head = "# format: ibs-trace 1\n# device: mc6000\n# words: pd\n";
  const std::string text = head + "0, 0000 0000 0000, 0240 0000 0000\n! fault overcurrent\n! fault-cleared\n"
                                  "1, 0000 0000 0000, 023F 0000 0000\n";
  const Trace t = parse(text, "e.trace");
  ASSERT_EQ(t.rows.size(), 2U);
  ASSERT_EQ(t.rows[1].events_before.size(), 2U);
  EXPECT_EQ(t.rows[1].events_before[0].kind, Event::Kind::fault);
  EXPECT_EQ(t.rows[1].events_before[0].text, "overcurrent");
  EXPECT_EQ(t.rows[1].events_before[0].line, 5U);
  EXPECT_EQ(t.rows[1].events_before[1].kind, Event::Kind::fault_cleared);
  EXPECT_EQ(write(t), text);
  const auto refused = [&](const std::string& body, const std::string& why) {
    try {
      parse(head + body, "e.trace");
      return std::string("accepted");
    } catch (const TraceError& e) {
      return std::string(e.what()) == "e.trace:" + why ? std::string() : std::string(e.what());
    }
  };
  EXPECT_EQ(refused("! fault\n0, 0000 0000 0000, 0240 0000 0000\n",
                    "4: an event must stand between two data rows; this one comes before the first row"),
            "");
  EXPECT_EQ(refused("0, 0000 0000 0000, 0240 0000 0000\n! fault\n",
                    "5: an event must stand between two data rows; no row follows this one"),
            "");
  EXPECT_EQ(refused("0, 0000 0000 0000, 0240 0000 0000\n! brownout\n1, 0000 0000 0000, 0240 0000 0000\n",
                    "5: unknown event 'brownout' (one of: fault, fault-cleared, no-data, write)"),
            "");
  EXPECT_EQ(refused("0, 0000 0000 0000, 0240 0000 0000\n...\n! fault\n1, 0000 0000 0000, 0240 0000 0000\n",
                    "6: an event cannot follow a gap '...': it would happen at no known step"),
            "");
  EXPECT_EQ(refused("0, 0000 0000 0000, 0240 0000 0000\n! fault\n...\n1, 0000 0000 0000, 0240 0000 0000\n",
                    "6: a gap '...' cannot follow an event (line 5): the event would happen at no known step"),
            "");
}

// trace-format.md: `watchdog_ms`, `step-time` and `! no-data N` (issue 23, item 16). The next
// row's step number counts the steps without data; all three are written back as read.
TEST(TraceFormat, WatchdogStepTimeAndStepsWithoutDataAreReadAndWrittenBack) {
  const std::string head = "# format: ibs-trace 1\n# device: mc6000\n# words: pd\n";
  const std::string text = head + "# watchdog_ms: 100\n# step-time: 8.2 ms\n0, 0000 0000 0000, 0240 0000 0000\n"
                                  "! no-data 3 bus corrupted\n! fault\n! no-data 2\n6, 0000 0000 0000, 0240 0000 0000\n"
                                  "7, 0000 0000 0000, 0240 0000 0000\n";
  const Trace t = parse(text, "w.trace");
  EXPECT_EQ(t.header.watchdog_ms, 100);
  EXPECT_EQ(t.header.lines.watchdog_ms, 4U);
  EXPECT_EQ(t.header.step_time, std::chrono::microseconds(8200));
  EXPECT_EQ(t.header.lines.step_time, 5U);
  ASSERT_EQ(t.rows.size(), 3U);
  ASSERT_EQ(t.rows[1].events_before.size(), 3U);
  EXPECT_EQ(t.rows[1].events_before[0].kind, Event::Kind::no_data);
  EXPECT_EQ(t.rows[1].events_before[0].steps, 3U);
  EXPECT_EQ(t.rows[1].events_before[0].text, "bus corrupted");
  EXPECT_EQ(t.rows[1].events_before[1].kind, Event::Kind::fault);
  EXPECT_EQ(t.rows[1].events_before[1].steps, 0U);
  EXPECT_EQ(t.rows[1].events_before[2].steps, 2U);
  EXPECT_EQ(t.rows[1].step, 6U);
  EXPECT_EQ(write(t), text);
  // Without the headers: the device's own watchdog and the adapters' step time.
  const Trace plain = parse(head + "0, 0000 0000 0000, 0240 0000 0000\n", "p.trace");
  EXPECT_FALSE(plain.header.watchdog_ms);
  EXPECT_FALSE(plain.header.step_time);
  EXPECT_EQ(parse(head + "# step-time: 726 us\n0, 0000 0000 0000, 0240 0000 0000\n", "u").header.step_time,
            std::chrono::microseconds(726));
  const auto refused = [&](const std::string& body) {
    try {
      parse(head + body, "w.trace");
      return std::string("accepted");
    } catch (const TraceError& e) {
      return std::string(e.what());
    }
  };
  const std::string row0 = "0, 0000 0000 0000, 0240 0000 0000\n";
  EXPECT_EQ(refused("# watchdog_ms: -1\n" + row0), "w.trace:4: watchdog_ms: '-1' is not a non-negative integer");
  EXPECT_EQ(refused("# watchdog_ms: 1 s\n" + row0), "w.trace:4: watchdog_ms: '1 s' is not a non-negative integer");
  EXPECT_EQ(refused("# watchdog_ms: 1\n# watchdog_ms: 2\n" + row0),
            "w.trace:5: header 'watchdog_ms' given twice (first on line 4)");
  EXPECT_EQ(refused("# step-time: 1 h\n" + row0), "w.trace:4: step-time: \"1 h\" has the unknown unit 'h' (ns, us, ms, s)");
  EXPECT_EQ(refused("# step-time: 0 s\n" + row0), "w.trace:4: step-time: '0 s' must lie above 0 s and be at most 1 s");
  EXPECT_EQ(refused("# step-time: 1.5 s\n" + row0), "w.trace:4: step-time: '1.5 s' must lie above 0 s and be at most 1 s");
  EXPECT_EQ(refused(row0 + "! no-data\n1, 0000 0000 0000, 0240 0000 0000\n"),
            "w.trace:5: no-data: '' is not a number of steps (N >= 1: `! no-data N`)");
  EXPECT_EQ(refused(row0 + "! no-data 0\n1, 0000 0000 0000, 0240 0000 0000\n"),
            "w.trace:5: no-data: '0' is not a number of steps (N >= 1: `! no-data N`)");
  EXPECT_EQ(refused(row0 + "! no-data 2x\n3, 0000 0000 0000, 0240 0000 0000\n"),
            "w.trace:5: no-data: '2x' is not a number of steps (N >= 1: `! no-data N`)");
  EXPECT_EQ(refused(row0 + "! no-data 10000001\n10000002, 0000 0000 0000, 0240 0000 0000\n"),
            "w.trace:5: no-data: 10000001 is more than the 10000000 steps one event may stand for");
  EXPECT_EQ(refused(row0 + "! no-data 2\n1, 0000 0000 0000, 0240 0000 0000\n"),
            "w.trace:6: step 1 should be 3 (the step after the previous row's, plus the 2 step(s) without data)");
  EXPECT_EQ(refused(row0 + "! no-data 2\n...\n1, 0000 0000 0000, 0240 0000 0000\n"),
            "w.trace:6: a gap '...' cannot follow an event (line 5): the event would happen at no known step");
}

// Issue 9, defect 4: max-gap is bounded (a gap that stands for 2^63 steps never ends).
TEST(TraceFormat, MaxGapIsBounded) {
  const std::string head = "# format: ibs-trace 1\n# device: vf1000\n# words: comm\n";
  EXPECT_EQ(parse(head + "# max-gap: 10000000\n0, 0000, 8000\n", "t").header.max_gap, kMaxGapLimit);
  try {
    parse(head + "# max-gap: 9223372036854775807\n0, 0000, 8000\n", "t");
    FAIL();
  } catch (const TraceError& e) {
    EXPECT_EQ(std::string(e.what()),
              "t:4: max-gap: 9223372036854775807 is more than the 10000000 steps a gap may stand for");
  }
}

TEST(TraceFormat, OnlyRegularFilesAreRead) {
  const std::string dir = ::testing::TempDir() + "ibs_trace_dir.trace";
  std::filesystem::create_directories(dir);
  try {
    load(dir);
    FAIL();
  } catch (const TraceError& e) {
    EXPECT_EQ(std::string(e.what()), dir + ":0: cannot read the file: it is a directory");
  }
  std::filesystem::remove(dir);
  // A FIFO would block the reader until a writer came: refused without opening it.
  const std::string fifo = ::testing::TempDir() + "ibs_trace_fifo.trace";
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    load(fifo);
    FAIL();
  } catch (const TraceError& e) {
    EXPECT_EQ(std::string(e.what()), fifo + ":0: cannot read the file: it is a FIFO (a named pipe), not a regular file");
  }
  std::filesystem::remove(fifo);
  // A regular file whose read fails (proc's memory file reads EIO at offset 0).
  try {
    load("/proc/self/mem");
    FAIL();
  } catch (const TraceError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/proc/self/mem:0: read error: ", 0), 0U) << e.what();
  }
}

// trace-format.md (issue 41): `setting: NAME VALUE` headers, repeatable, in the scenario's syntax
// (quotes optional), and `! write PNR VALUE [text]` events; both read and written back as read.
TEST(TraceFormat, SettingHeadersAndWriteEventsAreReadAndWrittenBack) {
  constexpr std::string_view kDeviceSettings[] = {"watchdog_reaction", "keypad", "reset_time"};
  const Vocabulary v{kDevices, kTargets, kSettings, kDeviceSettings};
  const std::string head = "# format: ibs-trace 1\n# device: vf1000\n# words: pd\n# watchdog_ms: 100\n";
  const std::string text = head + "# setting: watchdog_reaction 1\n# setting: reset_time 2 s\n# setting: keypad true\n"
                                  "0, 0000 0000 0000, 0240 0000 8000\n! write 906 200 over LUSTBUS\n! write 85 0\n"
                                  "1, 0000 0000 0000, 0240 0000 8000\n";
  const Trace t = parse(text, "s.trace", v);
  ASSERT_EQ(t.header.device_settings.size(), 3U);
  EXPECT_EQ(t.header.device_settings[0], (DeviceSetting{"watchdog_reaction", "1", 5}));
  EXPECT_EQ(t.header.device_settings[1].value, "2 s");
  EXPECT_EQ(t.header.device_settings[1].line, 6U);
  EXPECT_EQ(t.header.device_setting("keypad")->value, "true");
  EXPECT_EQ(t.header.device_setting("supi"), nullptr);
  ASSERT_EQ(t.rows[1].events_before.size(), 2U);
  const Event& w = t.rows[1].events_before[0];
  EXPECT_EQ(w.kind, Event::Kind::write);
  EXPECT_EQ(w.parameter, 906);
  EXPECT_EQ(w.value, 200);
  EXPECT_EQ(w.text, "over LUSTBUS");
  EXPECT_EQ(w.line, 9U);
  EXPECT_EQ(t.rows[1].events_before[1].parameter, 85);
  EXPECT_EQ(write(t), text);
  EXPECT_EQ(parse(write(t), "again", v).header.device_settings, t.header.device_settings);
  // Quotes as the scenario writes a time; hex and negative values of a write.
  const Trace q = parse(head + "# setting: reset_time \"500 ms\"\n0, 0000 0000 0000, 0240 0000 8000\n! write 0x196 -1\n"
                               "1, 0000 0000 0000, 0240 0000 8000\n",
                        "q.trace", v);
  EXPECT_EQ(q.header.device_settings[0].value, "500 ms");
  EXPECT_EQ(q.rows[1].events_before[0].parameter, 0x196);
  EXPECT_EQ(q.rows[1].events_before[0].value, -1);
  const auto refused = [&](const std::string& body, const std::string& why) {
    try {
      parse(head + body, "s.trace", v);
      return std::string("accepted");
    } catch (const TraceError& e) {
      return std::string(e.what()) == "s.trace:" + why ? std::string() : std::string(e.what());
    }
  };
  const std::string rows = "0, 0000 0000 0000, 0240 0000 8000\n";
  EXPECT_EQ(refused("# setting: watchdog_reaktion 1\n" + rows,
                    "5: setting: unknown setting 'watchdog_reaktion' (known: watchdog_reaction, keypad, reset_time)"),
            "");
  EXPECT_EQ(refused("# setting: keypad\n" + rows, "5: setting: 'keypad' needs a value (`setting: NAME VALUE`)"), "");
  EXPECT_EQ(refused("# setting:\n" + rows, "5: setting: '' is not a setting's name (`setting: NAME VALUE`)"), "");
  EXPECT_EQ(refused("# setting: keypad true\n# setting: keypad false\n" + rows,
                    "6: setting: 'keypad' given twice (first on line 5)"),
            "");
  EXPECT_EQ(refused("# setting: reset_time \"2 s\n" + rows, "5: setting: reset_time: '\"2 s' is not a value (a stray quote)"),
            "");
  const std::string next = "1, 0000 0000 0000, 0240 0000 8000\n";
  EXPECT_EQ(refused(rows + "! write 906\n" + next, "6: write: needs a parameter number and a value (`! write PNR VALUE`)"), "");
  EXPECT_EQ(refused(rows + "! write 70000 1\n" + next, "6: write: parameter number '70000' is not 0..65535"), "");
  EXPECT_EQ(refused(rows + "! write 906 4294967296\n" + next,
                    "6: write: value '4294967296' is not an integer -2147483648..4294967295 (a channel's raw value)"),
            "");
  EXPECT_EQ(refused(rows + "! write 906 2x\n" + next,
                    "6: write: value '2x' is not an integer -2147483648..4294967295 (a channel's raw value)"),
            "");
  EXPECT_EQ(refused("! write 906 1\n" + rows,
                    "5: an event must stand between two data rows; this one comes before the first row"),
            "");
}

TEST(TraceFormat, WithoutAVocabularyAnyWordNamesADeviceAndATarget) {
  const Trace t = parse("# format: ibs-trace 1\n# device: cda3000\n# words: pd\n# request: state running\n"
                        "0, 0000, 0240\n",
                        "f.trace");
  EXPECT_EQ(t.header.device, "cda3000");
  EXPECT_EQ(t.header.request->target, "running");
  EXPECT_THROW(parse("# format: ibs-trace 1\n# device: cda3000\n", "f.trace", kVocabulary), TraceError);
}

}  // namespace
}  // namespace ibs::trace
