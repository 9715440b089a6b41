// What `ibs --help` shows a user who has to act on it (issue 27.6): metavariables that say what
// a value is (PORT, ADDR, FILE, MS) instead of the parser's TEXT and INT, and every command's help
// ending with two examples that run as written and its exit codes; and the bash completion that
// `ibs completion bash` prints, generated from the same command tree so that it cannot go stale.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace ibs::cli {

// Names each option's value by what it is and gives each command its footer. Call once, after
// every command is added.
void polish_help(CLI::App& app);

// A bash completion script for `app` (complete -F): subcommands at each level, then the options
// of the command given so far; a FILE, DIR or PORT value completes as a path.
std::string bash_completion(const CLI::App& app);

}  // namespace ibs::cli
