// Runs a shell command line as a user would type it and keeps its exit code and output: the
// command-line tests of tests/tools run the built `ibs` this way.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace ibs::test {

struct ShellResult {
  int exit_code;
  std::string out;  // what the command printed on standard output (add 2>&1 for both streams)
};

inline ShellResult run_shell(const std::string& cmd) {
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return {-1, ""};
  std::string out;
  std::array<char, 4096> buf{};
  while (const std::size_t n = fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace ibs::test
