#include "help.hpp"

#include "reference.hpp"

#include <map>
#include <sstream>
#include <string_view>
#include <vector>

namespace ibs::cli {

namespace {

// What a value is, by the option's long name; one not listed is named after itself (--id-step:
// ID_STEP). The parser's own names (TEXT, INT, UINT, FLOAT) never reach the user.
std::string metavariable(const std::string& long_name) {
  static const std::map<std::string, std::string, std::less<>> names = {
      {"port", "PORT"},         {"address", "ADDR"},        {"addr", "ADDR"},          {"uid", "ADDR"},
      {"device", "DRIVE"},      {"baud", "BAUD"},           {"log", "FILE"},           {"pcap", "FILE"},
      {"vcd", "FILE"},          {"plot", "FILE"},           {"trace", "DIR"},          {"timeout-ms", "MS"},
      {"interval", "MS"},       {"reaction-ms", "MS"},      {"repeat", "N"},           {"seed", "N"},
      {"threads", "N"},         {"transactions", "N"},      {"rt-priority", "PRIO"},   {"control", "SPEC"},
      {"pty-link", "LINK"},     {"framing", "FRAMING"},     {"format", "FORMAT"},      {"bus", "BUS"},
      {"sw-us", "US"},          {"supi", "N"},              {"ibcnf", "N"},            {"emulate", "SIDE"},
      {"listen-ms", "MS"},      {"duration-ms", "MS"},      {"id-step", "N"},          {"cacnf", "N"},
      {"watchdog-reaction", "REACTION"}, {"stats-every", "TIME"},
      {"lustbus-pcap", "FILE"}, {"dfs1-pcap", "FILE"},
      {"board", "NODE"},        {"duration", "S"},
  };
  if (const auto it = names.find(long_name); it != names.end()) return it->second;
  std::string n;
  for (const char c : long_name) n += c == '-' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return n;
}

bool parser_name(const std::string& t) {
  for (const std::string_view p : {"TEXT", "INT", "UINT", "FLOAT", "NUMBER", "BOOLEAN", "UINT:INT", "INT:INT"}) {
    if (t == p || t.rfind(std::string(p) + " ", 0) == 0) return true;
  }
  return t.find("TEXT") != std::string::npos || t.find("INT") != std::string::npos ||
         t.find("FLOAT") != std::string::npos;
}

struct Footer {
  const char* path;  // "lustbus read"
  const char* text;  // examples and exit codes
};

// Two examples that run as written (after `./dev.sh run`, ibs on the PATH or as
// ./build/release/tools/ibs/ibs) and the exit codes; tools/check_docs.sh does not run them, the
// CLI tests run the ones marked there (tests/tools/cli_test.cpp, Cli.HelpEndsWithExamplesAndExitCodes).
constexpr Footer kFooters[] = {
    {"", "Examples:\n  ibs run --pcap /tmp/run.pcap\n  ibs lustbus emulate --pty-link /tmp/drive vf1000@1\n"
         "Every command has --help; docs/ in the source explains each bus.\n"
         "Exit codes: 0 ok; 1 a device refused or did not answer, a replay or check failed; 2 bad input; 130 interrupted"},
    {"run", "Examples:\n  ibs run --trace /tmp/traces --vcd /tmp/run.vcd\n  ibs run - --format toml < my.toml --json\n"
            "Exit codes: 0 ok; 2 bad input (FILE:LINE: what); 130 interrupted, nothing written"},
    {"master", "Examples:\n  ibs master --board IBB1N1\n  ibs master --board IBB1N1 examples/default.toml --json --duration 3\n"
               "ibs's virtual board takes another file's ring and faults with IBS_DDI_SCENARIO=FILE "
               "IBS_DDI_MASTER_COMMANDS=ibs-master (docs/board.md).\n"
               "Exit codes: 0 ok; 2 bad input, or a DDI error (the call and its code); 130 interrupted (the drives "
               "stopped, the board shut down, the summary printed)"},
    {"replay", "Examples:\n  ibs run --trace /tmp/traces && ibs replay --emulate device /tmp/traces/mc6000.trace\n"
               "  ibs replay --emulate master - < /tmp/traces/vf1000.trace\n"
               "Exit codes: 0 every row matched; 1 a row did not match; 2 bad input"},
    {"decode", "Examples:\n  ibs run --trace /tmp/traces && ibs decode /tmp/traces/mc6000.trace\n"
               "  ibs decode /tmp/lustbus.log   (a byte log of ibs lustbus ... --log; a capture of --pcap too)\n"
               "Exit codes: 0 ok; 2 bad input"},
    {"campaign", "Examples:\n  ibs campaign --transactions 1000\n  ibs campaign --seed 7 --json\n"
                 "Exit codes: 0 no violation; 1 a check failed; 2 bad input"},
    {"layout", "Examples:\n  ibs layout mc6000 --supi 11 --ibcnf 2\n  ibs layout vf1000 --json\n"
               "Exit codes: 0 ok; 2 bad input"},
    {"timing", "Examples:\n  ibs timing\n  ibs timing mc6000:11 mc6000:5:local vf1000 --baud 2M --json\n"
               "Exit codes: 0 ok; 2 bad input"},
    {"lustbus emulate", "Examples:\n  ibs lustbus emulate --pty vf1000@1 mc6000@3\n"
                        "  ibs lustbus emulate --pty-link /tmp/drive --control unix:/tmp/drive.ctl vf1000@1\n"
                        "Exit codes: 0 ended by SIGINT/SIGTERM; 2 bad input"},
    {"lustbus read", "Examples:\n  ibs lustbus read -p /tmp/drive -a 1 --device vf1000 FSSEL\n"
                     "  ibs lustbus read -p /dev/ttyUSB0 -a 3 --device mc6000 77 -j --repeat 10 --interval 500\n"
                     "Exit codes: 0 ok; 1 NAK (the 85 cause is printed), no or a broken answer; 2 bad input"},
    {"lustbus write", "Examples:\n  ibs lustbus write -p /tmp/drive -a 1 --device vf1000 FSSIO 50\n"
                      "  ibs lustbus write -p /dev/ttyUSB0 -a 3 --device mc6000 RSIO 132.15 --log /tmp/lustbus.log\n"
                      "Exit codes: 0 ok; 1 NAK (the 85 cause is printed), no or a broken answer; 2 bad input"},
    {"lustbus describe", "Examples:\n  ibs lustbus describe -p /tmp/drive -a 1 --device vf1000 VB2\n"
                         "  ibs lustbus describe -p /dev/ttyUSB0 -a 3 --device mc6000 RSIO -j\n"
                         "Exit codes: 0 ok; 1 NAK, no or a broken answer; 2 bad input"},
    {"lustbus scan", "Examples:\n  ibs lustbus scan -p /tmp/drive\n  ibs lustbus scan -p /dev/ttyUSB0 --baud 19200 -j\n"
                     "Exit codes: 0 ok; 1 the line did not answer as a bus does; 2 bad input"},
    {"lustbus download", "Examples:\n  ibs lustbus download -p /tmp/drive -a 3 dataset.txt\n"
                         "  ibs lustbus download -p /dev/ttyUSB0 -a 3 dataset.txt -j\n"
                         "Exit codes: 0 downloaded; 1 refused (the step and the 85 cause) or no answer; 2 bad input"},
    {"dfs1 emulate", "Examples:\n  ibs dfs1 emulate --pty dfs1@1 dfs1@2\n"
                     "  ibs dfs1 emulate --pty-link /tmp/dfs1 --control - dfs1@7\n"
                     "Exit codes: 0 ended by SIGINT/SIGTERM; 2 bad input"},
    {"dfs1 status", "Examples:\n  ibs dfs1 status -p /tmp/dfs1 -a 1\n  ibs dfs1 status -p /dev/ttyUSB0 -a 7 -j --repeat 0 --interval 250\n"
                    "Exit codes: 0 ok; 1 NAK, timeout or a bad response; 2 bad input"},
    {"dfs1 read", "Examples:\n  ibs dfs1 read -p /tmp/dfs1 -a 1 6\n  ibs dfs1 read -p /dev/ttyUSB0 -a 7 6 -j\n"
                  "Exit codes: 0 ok; 1 NAK, timeout or a bad response; 2 bad input"},
    {"dfs1 write", "Examples:\n  ibs dfs1 write -p /tmp/dfs1 -a 1 3 15\n  ibs dfs1 write -p /dev/ttyUSB0 -a 7 6 1500 -j\n"
                   "Exit codes: 0 ok; 1 NAK, timeout or a bad response; 2 bad input"},
    {"dfs1 speed", "Examples:\n  ibs dfs1 speed -p /tmp/dfs1 -a 1 1000\n  ibs dfs1 speed -p /tmp/dfs1 -a 0 --execute\n"
                   "Exit codes: 0 ok; 1 NAK, timeout or a bad response; 2 bad input"},
    {"canlust emulate", "Examples:\n  ibs canlust emulate -p udp:29701:127.0.0.1:29700 cda3000@1 cda3000@2\n"
                        "  ibs canlust emulate -p socketcan:vcan0 --control unix:/tmp/cda.ctl cda3000@1\n"
                        "Exit codes: 0 ended by SIGINT/SIGTERM; 2 bad input"},
    {"canlust start", "Examples:\n  ibs canlust start -p udp:29700:127.0.0.1:29701\n"
                      "  ibs canlust start -p socketcan:can0 --listen-ms 500 -j\n"
                      "Exit codes: 0 sent (the drives that answered are listed); 2 bad input"},
    {"canlust stop", "Examples:\n  ibs canlust stop -p udp:29700:127.0.0.1:29701\n"
                     "  ibs canlust stop -p socketcan:can0 -j\n"
                     "Exit codes: 0 sent (the drives that answered are listed); 2 bad input"},
    {"canlust read", "Examples:\n  ibs canlust read -p udp:29700:127.0.0.1:29701 -a 1 360-DISP\n"
                     "  ibs canlust read -p socketcan:can0 -a 2 REFF -j --repeat 10 --interval 500\n"
                     "Exit codes: 0 ok; 1 refused (the status decoded) or no answer; 2 bad input"},
    {"canlust write", "Examples:\n  ibs canlust write -p udp:29700:127.0.0.1:29701 -a 1 CAWDG 120\n"
                      "  ibs canlust write -p socketcan:can0 -a 2 NAME \"Line 3 pump\" -j\n"
                      "Exit codes: 0 ok; 1 refused (the status decoded) or no answer; 2 bad input"},
    {"canlust describe", "Examples:\n  ibs canlust describe -p udp:29700:127.0.0.1:29701 -a 1 575\n"
                         "  ibs canlust describe -p socketcan:can0 -a 2 CAWDG -j\n"
                         "Exit codes: 0 ok; 1 refused or no answer; 2 bad input"},
    {"canlust download", "Examples:\n  ibs canlust download -p udp:29700:127.0.0.1:29701 -a 1 dataset.txt\n"
                         "  ibs canlust download -p socketcan:can0 -a 2 dataset.txt -j\n"
                         "Exit codes: 0 downloaded; 1 rejected or refused (the parameter and FILE:LINE), no answer; "
                         "2 bad input (FILE:LINE: what)"},
    {"canlust monitor", "Examples:\n  ibs canlust monitor -p udp:29700:127.0.0.1:29701 -f 373:7FF -n 5 -t d\n"
                        "  ibs canlust monitor -p socketcan:can0 -f 373:7FF,375:7FF -t a --log /tmp/canlust.log\n"
                        "Exit codes: 0 ended (COUNT frames, --duration-ms, -T, SIGINT/SIGTERM); 2 bad input"},
    {"canlust send", "Examples:\n  ibs canlust send -p udp:29700:127.0.0.1:29701 0DD#01\n"
                     "  ibs canlust send -p socketcan:can0 0DD#00 --log /tmp/sent.log\n"
                     "Exit codes: 0 sent; 1 the bus did not take it; 2 bad input (what and the column)"},
    {"canlust play", "Examples:\n  ibs canlust play -p udp:29700:127.0.0.1:29701 /tmp/canlust.log\n"
                     "  ibs canlust play -p socketcan:can0 - < /tmp/canlust.log\n"
                     "Exit codes: 0 played; 1 a frame was not sent; 2 bad input (FILE:LINE: what); 130 interrupted"},
    {"completion", "Examples:\n  ibs completion bash > ~/.local/share/bash-completion/completions/ibs\n"
                   "  ibs completion bash > /tmp/ibs.bash && . /tmp/ibs.bash\n"
                   "Exit codes: 0 ok; 2 bad input"},
};

std::string path_of(const CLI::App* app) {
  std::vector<std::string> parts;
  for (const CLI::App* a = app; a != nullptr && a->get_parent() != nullptr; a = a->get_parent()) {
    parts.insert(parts.begin(), a->get_name());
  }
  std::string p;
  for (const std::string& s : parts) p += (p.empty() ? "" : " ") + s;
  return p;
}

// A validator's text stays out of the value's name (issue 36.2: `--interval MS:UINT in [1 - 3600000]`):
// a choice of words becomes the name (`--format toml|json`), a range is said in the description
// as the other options say theirs (`1..3600000`), added at its end when the description does not
// say it already.
CLI::Validator* validator_at(CLI::Option* opt, int index) {
  try {
    return opt->get_validator(index);
  } catch (const CLI::OptionNotFound&) {  // CLI11 2.1 has no count: past the last one
    return nullptr;
  }
}

void name_by_meaning(CLI::Option* opt) {
  std::string choices;
  for (int i = 0; CLI::Validator* v = validator_at(opt, i); ++i) {
    const std::string d = v->get_description();
    v->description("");
    if (d.size() > 2 && d.front() == '{' && d.back() == '}') {
      choices = d.substr(1, d.size() - 2);
      for (char& c : choices) c = c == ',' ? '|' : c;
    } else if (const auto at = d.find(" in ["); at != std::string::npos && d.back() == ']') {
      std::string range = d.substr(at + 5, d.size() - at - 6);  // "1 - 3600000"
      if (const auto dash = range.find(" - "); dash != std::string::npos) range.replace(dash, 3, "..");
      if (opt->get_description().find(range) == std::string::npos) {
        opt->description(opt->get_description() + " (" + range + ")");
      }
    }
  }
  if (!choices.empty() && !opt->get_lnames().empty()) opt->type_name(choices);
}

void polish(CLI::App* app) {
  for (CLI::Option* opt : app->get_options()) {
    if (opt->get_type_size() == 0) continue;  // a flag takes no value
    name_by_meaning(opt);
    if (opt->get_positional() && opt->get_lnames().empty()) {
      opt->type_name("");  // a positional's name says what it is already (PARAM, FILE, DEVICE)
      continue;
    }
    if (!parser_name(opt->get_type_name())) continue;  // named already (N, MS, toml|json)
    const auto& longs = opt->get_lnames();
    if (!longs.empty()) opt->type_name(metavariable(longs.front()));
  }
  const std::string path = path_of(app);
  for (const Footer& f : kFooters) {
    if (path == f.path) app->footer(f.text);
  }
  for (CLI::App* sub : app->get_subcommands({})) polish(sub);
}

void completion_case(const CLI::App* app, const std::string& path, std::ostringstream& s) {
  std::string words;
  for (const CLI::App* sub : visible_subcommands(*app)) words += sub->get_name() + " ";
  std::string files;
  for (const CLI::Option* opt : app->get_options()) {
    for (const std::string& l : opt->get_lnames()) words += "--" + l + " ";
    for (const std::string& sn : opt->get_snames()) words += "-" + sn + " ";
    const std::string t = opt->get_type_name();
    if (t == "FILE" || t == "DIR" || t == "PORT" || t == "LINK") {
      for (const std::string& l : opt->get_lnames()) files += (files.empty() ? "" : "|") + ("--" + l);
      for (const std::string& sn : opt->get_snames()) files += (files.empty() ? "" : "|") + ("-" + sn);
    }
  }
  s << "    \"" << path << "\")\n";
  if (!files.empty()) {
    s << "      case \"$prev\" in " << files << ") COMPREPLY=($(compgen -f -- \"$cur\")); return ;; esac\n";
  }
  s << "      COMPREPLY=($(compgen -W \"" << words << "\" -- \"$cur\"))\n";
  s << "      if [ ${#COMPREPLY[@]} -eq 0 ]; then COMPREPLY=($(compgen -f -- \"$cur\")); fi\n";
  s << "      ;;\n";
  for (const CLI::App* sub : visible_subcommands(*app)) {
    completion_case(sub, path.empty() ? sub->get_name() : path + " " + sub->get_name(), s);
  }
}

}  // namespace

void polish_help(CLI::App& app) { polish(&app); }

std::string bash_completion(const CLI::App& app) {
  std::ostringstream s;
  s << "# bash completion for ibs, made by `ibs completion bash` from the command tree itself.\n"
    << "_ibs() {\n"
    << "  local cur prev path w i\n"
    << "  cur=\"${COMP_WORDS[COMP_CWORD]}\"\n"
    << "  prev=\"${COMP_WORDS[COMP_CWORD-1]}\"\n"
    << "  path=\"\"\n"
    << "  # The command path so far: the words that name a subcommand at their level.\n"
    << "  for ((i = 1; i < COMP_CWORD; i++)); do\n"
    << "    w=\"${COMP_WORDS[i]}\"\n"
    << "    case \"$path:$w\" in\n";
  // The known paths: each subcommand word that extends the path before it.
  std::vector<std::pair<std::string, const CLI::App*>> stack{{"", &app}};
  while (!stack.empty()) {
    const auto [path, a] = stack.back();
    stack.pop_back();
    for (const CLI::App* sub : visible_subcommands(*a)) {
      const std::string next = path.empty() ? sub->get_name() : path + " " + sub->get_name();
      s << "      \"" << path << ":" << sub->get_name() << "\") path=\"" << next << "\" ;;\n";
      stack.emplace_back(next, sub);
    }
  }
  s << "    esac\n"
    << "  done\n"
    << "  case \"$path\" in\n";
  completion_case(&app, "", s);
  s << "  esac\n"
    << "  return 0\n"
    << "}\n"
    << "complete -F _ibs ibs\n";
  return s.str();
}

}  // namespace ibs::cli
