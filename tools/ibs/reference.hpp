// Every command and option of `ibs` on one page (issue 36.2): docs/cli.md in Markdown and the
// COMMANDS section of `man ibs`, both made from the command tree that `--help` prints, with the
// help formatter's own strings, so that the three cannot say different things. The hidden command
// `ibs reference markdown|man` prints them; tools/cli_reference.sh writes docs/cli.md, and a test
// (tests/tools/help_test.cpp) fails when the page and the built tool differ.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace ibs::cli {

// docs/cli.md: a table of every command, then per command its description, usage, a table of its
// positionals and options (as --help names them), its subcommands or its examples and exit codes.
std::string markdown_reference(const CLI::App& app);

// A help2man include file (help2man --include): a COMMANDS section with each command's whole
// --help, so that `man ibs` has every option of every command, not only the top-level help.
std::string man_reference(const CLI::App& app);

// The commands that --help shows (hidden ones, of group "", left out), in the order they were added.
std::vector<const CLI::App*> visible_subcommands(const CLI::App& app);

// "lustbus read" for that subcommand; "" for the root.
std::string command_path(const CLI::App& app);

}  // namespace ibs::cli
