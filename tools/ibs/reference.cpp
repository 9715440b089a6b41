#include "reference.hpp"

#include <sstream>
#include <vector>

namespace ibs::cli {

namespace {

// A table cell: one line, its pipes escaped (GitHub reads `\|` as a pipe inside code spans too).
std::string cell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|') {
      out += "\\|";
    } else if (c == '\n') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  while (!s.empty() && (s.front() == '\n' || s.front() == ' ')) s.erase(s.begin());
  return s;
}

// "ibs lustbus read", the name --help's usage line gives the command.
std::string full_name(const CLI::App& app) {
  const std::string path = command_path(app);
  return path.empty() ? "ibs" : "ibs " + path;
}

// GitHub's anchor of a heading "ibs lustbus read": lower case, spaces as dashes.
std::string anchor(const CLI::App& app) {
  std::string a;
  for (const char c : full_name(app)) a += c == ' ' ? '-' : c;
  return a;
}

void all_commands(const CLI::App& app, std::vector<const CLI::App*>& out) {
  out.push_back(&app);
  for (const CLI::App* sub : visible_subcommands(app)) all_commands(*sub, out);
}

// One command's section: what --help shows, as Markdown, with the formatter's own strings.
void section(const CLI::App& app, std::ostringstream& s) {
  const CLI::Formatter f;
  s << "## " << full_name(app) << "\n\n" << trim(app.get_description()) << "\n\n";
  std::string usage = trim(f.make_usage(&app, full_name(app)));
  if (usage.rfind("Usage: ", 0) == 0) usage.erase(0, 7);
  s << "```text\n" << usage << "\n```\n\n";
  std::vector<const CLI::Option*> options;
  for (const CLI::Option* opt : app.get_options()) {
    if (opt == app.get_help_ptr() || opt->get_group().empty()) continue;  // -h,--help: said once above
    options.push_back(opt);
  }
  if (!options.empty()) {
    s << "| option | what |\n| --- | --- |\n";
    for (const bool positional : {true, false}) {  // positionals first, as --help lists them
      for (const CLI::Option* opt : options) {
        if (positional ? !opt->get_positional() : !opt->nonpositional()) continue;
        const std::string head = f.make_option_name(opt, positional) + f.make_option_opts(opt);
        s << "| `" << cell(head) << "` | " << cell(f.make_option_desc(opt)) << " |\n";
      }
    }
    s << "\n";
  }
  const auto subs = visible_subcommands(app);
  if (!subs.empty()) {
    s << "| command | what it does |\n| --- | --- |\n";
    for (const CLI::App* sub : subs) {
      s << "| [`" << full_name(*sub) << "`](#" << anchor(*sub) << ") | " << cell(trim(sub->get_description())) << " |\n";
    }
    s << "\n";
  }
  if (const std::string footer = trim(app.get_footer()); !footer.empty()) s << "```text\n" << footer << "\n```\n\n";
}

// A line of text for roff inside .nf: backslashes printed as such, no line taken for a request
// (. or ') or, in help2man's include file, for a section name ([...]) or a pattern (/.../).
std::string roff_line(const std::string& line) {
  std::string out;
  if (!line.empty() && (line[0] == '.' || line[0] == '\'' || line[0] == '[' || line[0] == '/')) out = "\\&";
  for (const char c : line) {
    if (c == '\\') {
      out += "\\e";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

std::vector<const CLI::App*> visible_subcommands(const CLI::App& app) {
  std::vector<const CLI::App*> out;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (!sub->get_group().empty()) out.push_back(sub);
  }
  return out;
}

std::string command_path(const CLI::App& app) {
  std::vector<std::string> parts;
  for (const CLI::App* a = &app; a != nullptr && a->get_parent() != nullptr; a = a->get_parent()) {
    parts.insert(parts.begin(), a->get_name());
  }
  std::string p;
  for (const std::string& part : parts) p += (p.empty() ? "" : " ") + part;
  return p;
}

std::string markdown_reference(const CLI::App& app) {
  std::vector<const CLI::App*> commands;
  all_commands(app, commands);
  std::ostringstream s;
  s << "# The `ibs` command line\n\n"
    << "<!-- Made by `ibs reference markdown` from the command tree; do not edit by hand: run\n"
    << "     tools/cli_reference.sh after changing a command or an option. -->\n\n"
    << "Every command of `ibs` with every option, as `ibs COMMAND --help` and `man ibs` show them: this\n"
    << "page is made from the same definitions by `tools/cli_reference.sh`, and a test\n"
    << "(`tests/tools/help_test.cpp`) fails when it and the built tool differ. Every command also takes\n"
    << "`-h,--help`. A value is named by what it is (`PORT`, `ADDR`, `MS`, `FILE`, `N`), `REQUIRED` marks\n"
    << "what must be given, `=VALUE` a default, and `...` an argument given any number of times.\n\n"
    << "| command | what it does |\n| --- | --- |\n";
  for (const CLI::App* c : commands) {
    if (c == &app) continue;
    s << "| [`" << full_name(*c) << "`](#" << anchor(*c) << ") | " << cell(trim(c->get_description())) << " |\n";
  }
  s << "\n";
  for (const CLI::App* c : commands) section(*c, s);
  std::string out = s.str();
  while (out.size() > 1 && out[out.size() - 1] == '\n' && out[out.size() - 2] == '\n') out.pop_back();
  return out;
}

std::string man_reference(const CLI::App& app) {
  std::vector<const CLI::App*> commands;
  all_commands(app, commands);
  std::ostringstream s;
  s << "[COMMANDS]\n"
    << "Each command's own help, as `ibs COMMAND --help` prints it.\n";
  for (const CLI::App* c : commands) {
    if (c == &app) continue;
    const std::string parent = full_name(*c->get_parent());
    s << ".SS \"" << full_name(*c) << "\"\n.nf\n";
    std::istringstream help(trim(c->help(parent)));
    for (std::string line; std::getline(help, line);) s << roff_line(line) << "\n";
    s << ".fi\n";
  }
  return s.str();
}

}  // namespace ibs::cli
