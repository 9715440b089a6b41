// The help a user reads (issue 36.2): every command's --help, found by walking the whole command
// tree as a user would (`ibs --help`, then each subcommand's), names each value by what it is and
// never by the parser's type or a validator's text; docs/cli.md is what the built tool prints
// (`ibs reference markdown`) and holds every option line of every --help; `man ibs` has every
// command's help.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_shell.hpp"

namespace {

using ibs::test::run_shell;

std::string help_of(const std::string& path) {
  const auto r = run_shell(std::string(IBS_CLI) + (path.empty() ? "" : " " + path) + " --help 2>&1");
  EXPECT_EQ(r.exit_code, 0) << path << "\n" << r.out;
  return r.out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The entries of one section of a help ("Subcommands:", "Options:", "Positionals:"): the lines
// indented by two spaces up to the next blank line; of each, the left column (the name and its
// value's name), which ends at a run of two spaces or the end of the line (a long one wraps its
// description onto the next line).
std::vector<std::string> section_heads(const std::string& help, const std::string& title) {
  std::vector<std::string> heads;
  bool in = false;
  for (const std::string& line : lines_of(help)) {
    if (line == title) {
      in = true;
      continue;
    }
    if (!in) continue;
    if (line.empty()) break;
    if (line.size() > 2 && line.compare(0, 2, "  ") == 0 && line[2] != ' ') {
      const auto end = line.find("  ", 2);
      heads.push_back(line.substr(2, end == std::string::npos ? std::string::npos : end - 2));
    }
  }
  return heads;
}

struct Command {
  std::string path;  // "lustbus read"; "" the root
  std::string help;  // what `ibs PATH --help` prints
};

// Every command, the root first, then depth first as --help lists them, each with its help (read
// once per test process: the sanitizer build starts the tool slowly).
void walk(const std::string& path, std::vector<Command>& out) {
  out.push_back({path, help_of(path)});
  const std::string help = out.back().help;
  for (const std::string& sub : section_heads(help, "Subcommands:")) walk(path.empty() ? sub : path + " " + sub, out);
}

const std::vector<Command>& tree() {
  static const std::vector<Command> commands = [] {
    std::vector<Command> c;
    walk("", c);
    return c;
  }();
  return commands;
}

// The paths below the root.
std::vector<std::string> all_commands() {
  std::vector<std::string> paths;
  for (const Command& c : tree()) {
    if (!c.path.empty()) paths.push_back(c.path);
  }
  return paths;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::string reference() {
  const auto r = run_shell(std::string(IBS_CLI) + " reference markdown");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  return r.out;
}

// The left column as docs/cli.md shows it: in a code span, its pipes escaped.
std::string as_cell(const std::string& head) {
  std::string out = "| `";
  for (const char c : head) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out + "` |";
}

TEST(HelpReference, TheWalkFindsEveryCommand) {
  const std::vector<std::string> commands = all_commands();
  for (const char* expected : {"run", "replay", "decode", "campaign", "layout", "timing", "lustbus", "lustbus read",
                               "lustbus emulate", "dfs1", "dfs1 read", "canlust", "canlust read", "canlust play",
                               "completion"}) {
    EXPECT_NE(std::find(commands.begin(), commands.end(), expected), commands.end()) << expected;
  }
  EXPECT_GE(commands.size(), 30U);
  // The hidden command that prints this reference is not one a user is offered.
  EXPECT_EQ(std::find(commands.begin(), commands.end(), "reference"), commands.end());
  const auto completion = run_shell(std::string(IBS_CLI) + " completion bash");
  EXPECT_EQ(completion.out.find("reference"), std::string::npos);
}

// `--interval MS:UINT in [1 - 3600000]`, `--seed N:UINT`, `--format FORMAT:{toml,json}` were the
// help of CLI11's validators: a value is named by a word that says what it is, or by its choices.
TEST(HelpReference, EveryCommandsHelpNamesItsValuesByMeaning) {
  const std::regex parser_word(R"(\b(TEXT|INT|UINT|FLOAT|NUMBER|BOOLEAN|BOOL)\b)");
  std::vector<Command> commands = tree();
  commands.push_back({"reference", help_of("reference")});
  std::size_t options = 0;
  for (const auto& [path, help] : commands) {
    for (const char* title : {"Options:", "Positionals:"}) {
      for (const std::string& head : section_heads(help, title)) {
        ++options;
        EXPECT_FALSE(std::regex_search(head, parser_word)) << "ibs " << path << ": " << head;
        for (const char* leak : {":", "[", "{", " in "}) {
          EXPECT_EQ(head.find(leak), std::string::npos) << "ibs " << path << ": '" << leak << "' in " << head;
        }
      }
    }
  }
  EXPECT_GT(options, 200U);  // the walk read the options, not only the commands
}

// The limits a validator checks are said in the option's own words, as 405-SUPI's `0..12`.
TEST(HelpReference, RangesAreSaidInTheDescription) {
  const std::pair<const char*, const char*> expected[] = {
      {"run", "--threads N=1               threads that step the devices, 0..256 "},
      {"run", "--rt-priority PRIO          with --realtime: SCHED_FIFO at this priority (1..99)"},
      {"campaign", "--transactions N            parameter transactions to run, 1..100000000 (default 100000)"},
      {"lustbus emulate", "--reaction-ms MS            a fixed reaction time instead, 0..10000 ms"},
      {"lustbus read", "--interval MS               with --repeat: MS from one reading's start to the next, "
                       "1..3600000 (default 1000)"},
      {"dfs1 read", "--interval MS               with --repeat: MS from one reading's start to the next, "
                    "1..3600000"},
      {"dfs1 status", "--interval MS               with --repeat: MS from one reading's start to the next, "
                      "1..3600000"},
      {"canlust read", "--interval MS               with --repeat: MS from one reading's start to the next, "
                       "1..3600000"},
      {"replay", "--emulate device|master REQUIRED"},
      {"run", "--format toml|json "},
  };
  for (const auto& [path, line] : expected) {
    const std::string help = help_of(path);
    EXPECT_NE(help.find(line), std::string::npos) << "ibs " << path << ": no '" << line << "'\n" << help;
  }
  // The limits still hold: the validator lost its text, not its check.
  const auto r = run_shell(std::string(IBS_CLI) + " lustbus read -p /dev/null -a 1 --device vf1000 --interval 0 1 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--interval: Value 0 not in range 1 to 3600000"), std::string::npos) << r.out;
  const auto f = run_shell(std::string(IBS_CLI) + " run - --format yaml 2>&1 </dev/null");
  EXPECT_EQ(f.exit_code, 2) << f.out;
}

TEST(HelpReference, DocsCliMdIsWhatTheToolPrints) {
  const std::string page = read_file(std::string(IBS_SOURCE_DIR) + "/docs/cli.md");
  const std::string printed = reference();
  ASSERT_FALSE(printed.empty());
  EXPECT_TRUE(page == printed)
      << "docs/cli.md is not what the built ibs prints: regenerate it with\n  tools/cli_reference.sh\n(or, with this "
         "build's ibs: tools/cli_reference.sh " << IBS_CLI << ") and commit it\n";
}

// The reference holds each command's section with every option line its --help shows.
TEST(HelpReference, TheReferenceHasEveryOptionOfEveryHelp) {
  const std::string page = reference();
  for (const auto& [path, help] : tree()) {
    if (path.empty()) continue;
    const auto at = page.find("\n## ibs " + path + "\n");
    ASSERT_NE(at, std::string::npos) << "no section for ibs " << path;
    const auto next = page.find("\n## ", at + 1);
    const std::string section = page.substr(at, next == std::string::npos ? std::string::npos : next - at);
    EXPECT_NE(page.find("| [`ibs " + path + "`](#ibs-" + std::regex_replace(path, std::regex(" "), "-") + ") |"),
              std::string::npos)
        << "ibs " << path << " is not in the table of commands";
    for (const char* title : {"Options:", "Positionals:"}) {
      for (const std::string& head : section_heads(help, title)) {
        if (head == "-h,--help") continue;  // said once at the top
        EXPECT_NE(section.find(as_cell(head)), std::string::npos) << "ibs " << path << ": " << head << "\n" << section;
      }
    }
    for (const std::string& sub : section_heads(help, "Subcommands:")) {
      EXPECT_NE(section.find("[`ibs " + path + " " + sub + "`]"), std::string::npos) << "ibs " << path << ": " << sub;
    }
    const auto examples = help.find("Examples:\n");
    if (examples != std::string::npos) {
      EXPECT_NE(section.find(help.substr(examples, help.find('\n', examples + 10) - examples)), std::string::npos)
          << "ibs " << path << ": its examples";
    }
  }
}

// help2man makes `man ibs` from the top-level help; the COMMANDS section adds every command's.
TEST(HelpReference, TheManPageHasEveryCommandsHelp) {
  const std::string cli = IBS_CLI;
  const std::string man = read_file(cli.substr(0, cli.rfind('/')) + "/ibs.1");
  if (man.empty()) GTEST_SKIP() << "no ibs.1 beside the tool (help2man not installed)";
  for (const std::string& path : all_commands()) {
    EXPECT_NE(man.find(".SS \"ibs " + path + "\"\n.nf\n"), std::string::npos) << "ibs " << path;
  }
  EXPECT_NE(man.find("  --interval MS               with --repeat"), std::string::npos);
  EXPECT_NE(man.find("\n.SH COMMANDS\n"), std::string::npos);
  const auto bad = run_shell(cli + " reference html 2>&1");
  EXPECT_EQ(bad.exit_code, 2) << bad.out;
}

}  // namespace
