#include "gnuplot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern char** environ;

namespace ibs::cli {

namespace {

// A temporary file that is removed again.
struct TempFile {
  std::string path;
  int fd = -1;
  explicit TempFile(const char* suffix) {
    const char* dir = std::getenv("TMPDIR");
    std::string templ = std::string(dir != nullptr && *dir != '\0' ? dir : "/tmp") + "/ibs-plot-XXXXXX" + suffix;
    std::vector<char> buf(templ.begin(), templ.end());
    buf.push_back('\0');
    fd = ::mkstemps(buf.data(), static_cast<int>(std::strlen(suffix)));
    if (fd >= 0) path = buf.data();
  }
  ~TempFile() {
    if (fd >= 0) ::close(fd);
    if (!path.empty()) ::unlink(path.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
};

std::string first_lines(const std::string& text, int count) {
  std::string out;
  std::size_t pos = 0;
  for (int i = 0; i < count && pos < text.size(); ++i) {
    const auto e = text.find('\n', pos);
    out += (i ? "\n  " : "") + text.substr(pos, e == std::string::npos ? std::string::npos : e - pos);
    if (e == std::string::npos) break;
    pos = e + 1;
  }
  return out;
}

}  // namespace

bool gnuplot_available() {
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  std::size_t pos = 0;
  while (pos <= dirs.size()) {
    const auto e = dirs.find(':', pos);
    const std::string dir = dirs.substr(pos, e == std::string::npos ? std::string::npos : e - pos);
    const std::string candidate = (dir.empty() ? "." : dir) + "/gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    if (e == std::string::npos) break;
    pos = e + 1;
  }
  return false;
}

bool run_gnuplot(const std::string& script, std::ostream& image, std::string& error) {
  TempFile script_file(".gp");
  TempFile err_file(".err");
  if (script_file.fd < 0 || err_file.fd < 0) {
    error = std::string("cannot create a temporary file for gnuplot: ") + std::strerror(errno);
    return false;
  }
  {
    std::ofstream out(script_file.path, std::ios::binary | std::ios::trunc);
    out << script;
    if (!out.flush()) {
      error = "cannot write the gnuplot script " + script_file.path;
      return false;
    }
  }
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) {
    error = std::string("cannot create a pipe for gnuplot: ") + std::strerror(errno);
    return false;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err_file.fd, 2);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[1]);
  std::string program = "gnuplot";
  std::string script_arg = script_file.path;
  char* argv[] = {program.data(), script_arg.data(), nullptr};
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  if (rc != 0) {
    ::close(pipe_fds[0]);
    error = rc == ENOENT ? "gnuplot is not installed (Debian package gnuplot-nox)"
                         : std::string("cannot start gnuplot: ") + std::strerror(rc);
    return false;
  }
  std::size_t bytes = 0;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(pipe_fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    image.write(buf, n);
    bytes += static_cast<std::size_t>(n);
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::ifstream err_in(err_file.path, std::ios::binary);
  const std::string messages((std::istreambuf_iterator<char>(err_in)), std::istreambuf_iterator<char>());
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    error = "gnuplot failed (" +
            (WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                               : "signal " + std::to_string(WTERMSIG(status))) +
            "): " + first_lines(messages, 4);
    return false;
  }
  if (bytes == 0) {
    error = "gnuplot wrote no image" + (messages.empty() ? std::string() : ": " + first_lines(messages, 4));
    return false;
  }
  return true;
}

}  // namespace ibs::cli
