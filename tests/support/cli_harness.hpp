// What the command-line tests of `ibs lustbus`, `ibs dfs1` and `ibs canlust` share: running one
// command group in this process with captured output, and an `ibs ... emulate` as a child process
// whose first output line (`pty: PATH`, `bus: ...`) is read before the test talks to it.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ibs::test {

struct CliRun {
  int rc = -1;
  std::string out;
  std::string err;
};

// Parses `args` (the words after `ibs`) with the group's `add`, then runs it with `run`; a parse
// error gives `bad_input_exit` and CLI11's message.
template <typename State>
CliRun run_cli_group(std::vector<std::string> args, int bad_input_exit, void (*add)(CLI::App&, State&),
                     std::optional<int> (*run)(const State&, std::ostream&, std::ostream&)) {
  CLI::App app{"test"};
  app.require_subcommand(1);
  State state;
  add(app, state);
  CliRun r;
  std::reverse(args.begin(), args.end());
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    r.rc = bad_input_exit;
    r.err = e.what();
    return r;
  }
  std::ostringstream out;
  std::ostringstream err;
  r.rc = run(state, out, err).value_or(-1);
  r.out = out.str();
  r.err = err.str();
  return r;
}

// `argv` (the program first) as a child process with its standard output on a pipe; the first
// line it prints is read at construction. Killed on destruction unless stopped.
class ChildProcess {
 public:
  explicit ChildProcess(std::vector<std::string> argv) {
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe");
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(fds[1], STDOUT_FILENO);
      ::close(fds[0]);
      ::close(fds[1]);
      std::vector<char*> args;
      for (auto& a : argv) args.push_back(a.data());
      args.push_back(nullptr);
      ::execv(args[0], args.data());
      ::_exit(127);
    }
    ::close(fds[1]);
    out_ = ::fdopen(fds[0], "r");
    char line[512] = {};
    if (std::fgets(line, sizeof line, out_) != nullptr) first_line_ = line;
    if (!first_line_.empty() && first_line_.back() == '\n') first_line_.pop_back();
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (out_ != nullptr) std::fclose(out_);
  }
  [[nodiscard]] const std::string& first_line() const { return first_line_; }
  // The text after the first line's first space: the path of `pty: PATH`.
  [[nodiscard]] std::string pty() const { return first_line_.substr(first_line_.find(' ') + 1); }
  // Sends `sig` and returns the exit code (-1: not a normal exit).
  int stop(int sig) {
    ::kill(pid_, sig);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  // After stop(): what the child printed after its first line, to the end.
  [[nodiscard]] std::string rest() {
    std::string text;
    char buf[4096];
    while (const std::size_t n = std::fread(buf, 1, sizeof buf, out_)) text.append(buf, n);
    return text;
  }
  // Reads standard output to its end into `rest` and waits for the exit: the exit code (-1: not a
  // normal exit). For a child that ends by itself (`ibs run --realtime` at the end of its run).
  int wait(std::string& rest) {
    char buf[4096];
    while (const std::size_t n = std::fread(buf, 1, sizeof buf, out_)) rest.append(buf, n);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

 private:
  pid_t pid_ = -1;
  FILE* out_ = nullptr;
  std::string first_line_;
};

}  // namespace ibs::test
