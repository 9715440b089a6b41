#include "ibs/base/text_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace ibs {

namespace {

[[noreturn]] void fail(const std::string& why) { throw FileReadError(why); }

std::string errno_text(int e) { return std::strerror(e); }

// Closes the descriptor on every way out.
struct Fd {
  int fd;
  explicit Fd(int d) : fd(d) {}
  Fd(Fd&& o) noexcept : fd(o.fd) { o.fd = -1; }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  Fd& operator=(Fd&&) = delete;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

std::string not_regular(mode_t m) {
  if (S_ISDIR(m)) return "cannot read the file: it is a directory";
  if (S_ISFIFO(m)) return "cannot read the file: it is a FIFO (a named pipe), not a regular file";
  if (S_ISSOCK(m)) return "cannot read the file: it is a socket, not a regular file";
  if (S_ISCHR(m) || S_ISBLK(m)) return "cannot read the file: it is a device, not a regular file";
  return "cannot read the file: it is not a regular file";
}

}  // namespace

namespace {

// The regular file at `path`, opened without blocking; throws FileReadError.
Fd open_regular(const std::string& path, struct stat& st) {
  if (::stat(path.c_str(), &st) != 0) {
    const int e = errno;
    if (e == ENOENT) fail("cannot read the file: it does not exist");
    fail("cannot read the file: " + errno_text(e));
  }
  // Checked before opening: opening a FIFO for reading blocks until a writer comes.
  if (!S_ISREG(st.st_mode)) fail(not_regular(st.st_mode));
  Fd f(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (f.fd < 0) fail("cannot open the file: " + errno_text(errno));
  // The path may have been replaced between stat and open: look at what was opened.
  if (::fstat(f.fd, &st) != 0) fail("cannot read the file: " + errno_text(errno));
  if (!S_ISREG(st.st_mode)) fail(not_regular(st.st_mode));
  return f;
}

}  // namespace

std::string read_text_head(const std::string& path, std::size_t max_bytes) {
  struct stat st {};
  Fd f = open_regular(path, st);
  std::string text(max_bytes, '\0');
  std::size_t got = 0;
  while (got < max_bytes) {
    const ssize_t n = ::read(f.fd, text.data() + got, max_bytes - got);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("read error: " + errno_text(errno));
    }
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  text.resize(got);
  return text;
}

std::vector<std::string> lines_of(const std::string& head, bool whole) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < head.size()) {
    const std::size_t end = head.find('\n', start);
    if (end == std::string::npos) {
      if (whole) lines.push_back(head.substr(start));
      break;
    }
    lines.push_back(head.substr(start, end - start));
    start = end + 1;
  }
  for (std::string& l : lines) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
  }
  return lines;
}

std::string read_text_file(const std::string& path) {
  struct stat st {};
  Fd f = open_regular(path, st);
  if (static_cast<std::size_t>(st.st_size) > kMaxInputFileBytes) {
    fail("cannot read the file: it has " + std::to_string(st.st_size) + " bytes, more than the " +
         std::to_string(kMaxInputFileBytes >> 20U) + " MiB an input file may have");
  }
  std::string text;
  text.reserve(static_cast<std::size_t>(st.st_size));
  char buf[65536];
  while (true) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("read error: " + errno_text(errno));
    }
    if (n == 0) break;
    if (text.size() + static_cast<std::size_t>(n) > kMaxInputFileBytes) {
      fail("cannot read the file: it is larger than the " + std::to_string(kMaxInputFileBytes >> 20U) +
           " MiB an input file may have");
    }
    text.append(buf, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace ibs
