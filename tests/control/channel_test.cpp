// The control channel over a Unix socket (transports/control, channel.hpp; issue 41): every
// client served at once with its own line numbers, each line bounded, the clients bounded with a
// refusal for the next, a client that stalls or floods delays no one, the socket owner-only
// whatever the umask, and a poll that allocates nothing.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "../support/counting_new.hpp"
#include "ibs/control/channel.hpp"

namespace ibs::control {
namespace {

std::string socket_path(const std::string& what) {
  return ::testing::TempDir() + "ibs_control_" + what + "_" + std::to_string(::getpid()) + ".sock";
}

// A connected client (blocking), or -1.
int connect_to(const std::string& path) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  std::snprintf(a.sun_path, sizeof a.sun_path, "%s", path.c_str());
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

void send_all(int fd, const std::string& text) {
  std::size_t at = 0;
  while (at < text.size()) {
    const ssize_t n = ::send(fd, text.data() + at, text.size() - at, MSG_NOSIGNAL);
    ASSERT_GT(n, 0) << std::strerror(errno);
    at += static_cast<std::size_t>(n);
  }
}

// What a poll handed out: "control:C:L text", "control:C:L ! what"; the notices apart.
struct Seen {
  std::vector<std::string> items;
  std::vector<std::string> notices;
  void poll(Channel& c) {
    c.poll([this](const Origin& o, std::string_view text) { items.push_back(to_string(o) + " " + std::string(text)); },
           [this](const Origin& o, std::string_view what) { items.push_back(to_string(o) + " ! " + std::string(what)); },
           [this](std::string_view notice) { notices.emplace_back(notice); });
  }
  [[nodiscard]] bool has(const std::string& s) const {
    for (const auto& i : items) {
      if (i == s) return true;
    }
    for (const auto& i : notices) {
      if (i == s) return true;
    }
    return false;
  }
  [[nodiscard]] std::size_t count_prefix(const std::string& p) const {
    std::size_t n = 0;
    for (const auto& i : items) n += i.rfind(p, 0) == 0 ? 1U : 0U;
    return n;
  }
};

struct Socket {
  explicit Socket(const std::string& what, const Limits& limits = {}) : path(socket_path(what)) {
    ::unlink(path.c_str());
    std::string error;
    channel = Channel::open("unix:" + path, error, limits);
    EXPECT_NE(channel, nullptr) << error;
  }
  ~Socket() {
    for (const int fd : fds) {
      if (fd >= 0) ::close(fd);
    }
  }
  int client() {
    fds.push_back(connect_to(path));
    return fds.back();
  }
  std::string path;
  std::unique_ptr<Channel> channel;
  std::vector<int> fds;
};

TEST(ControlChannel, EveryClientIsServedAtOnceWithItsOwnLineNumbers) {
  Socket s("clients");
  const int a = s.client();
  const int b = s.client();
  const int c = s.client();
  send_all(a, "a1\n# a comment, counted\na3\n");
  send_all(b, "b1\n");
  send_all(c, "c1\nc2 without its newline yet");
  Seen seen;
  seen.poll(*s.channel);
  EXPECT_TRUE(seen.has("control:1: connected (pid " + std::to_string(::getpid()) + ")")) << ::testing::PrintToString(seen.notices);
  EXPECT_TRUE(seen.has("control:1:1 a1"));
  EXPECT_TRUE(seen.has("control:1:3 a3"));
  EXPECT_TRUE(seen.has("control:2:1 b1"));
  EXPECT_TRUE(seen.has("control:3:1 c1"));
  EXPECT_EQ(seen.count_prefix("control:3:2"), 0U);
  EXPECT_EQ(s.channel->clients(), 3U);
  // The end of a client's input ends its last line; the others go on.
  ::close(c);
  s.fds[2] = -1;
  send_all(b, "b2\n");
  seen.poll(*s.channel);
  EXPECT_TRUE(seen.has("control:3:2 c2 without its newline yet")) << ::testing::PrintToString(seen.items);
  EXPECT_TRUE(seen.has("control:2:2 b2"));
  EXPECT_EQ(s.channel->clients(), 2U);
  // A client that comes later is the next number, its lines from 1.
  send_all(s.client(), "d1\n");
  seen.poll(*s.channel);
  EXPECT_TRUE(seen.has("control:4:1 d1")) << ::testing::PrintToString(seen.items);
  EXPECT_EQ(s.channel->counters().accepted, 4U);
  EXPECT_EQ(s.channel->counters().closed, 1U);
}

TEST(ControlChannel, AStalledClientDelaysNoOne) {
  Socket s("stalled");
  const int stalled = s.client();
  send_all(stalled, R"({"device": "servo", "spe)");  // and nothing more, connected
  const int other = s.client();
  send_all(other, "{\"device\": \"servo\", \"speed\": 5}\n");
  Seen seen;
  seen.poll(*s.channel);
  EXPECT_TRUE(seen.has(R"(control:2:1 {"device": "servo", "speed": 5})")) << ::testing::PrintToString(seen.items);
  EXPECT_EQ(seen.count_prefix("control:1:"), 0U);
}

// The issue's attack: a client sends a 64 MiB line without a newline and stays connected while
// another injects; the endless line is reported at once, with its client, and costs every poll
// at most its read budget; the other client's lines are applied as they come.
TEST(ControlChannel, AnEndlessLineIsReportedAtOnceAndDelaysNoOne) {
  Socket s("endless");
  const int endless = s.client();
  const int injector = s.client();
  std::atomic<bool> written{false};
  std::thread flood([&] {
    const std::string chunk(1 << 20, 'x');
    for (int i = 0; i < 64; ++i) send_all(endless, chunk);
    written = true;
  });
  Seen seen;
  std::size_t polls = 0;
  std::uint64_t most = 0;
  int sent = 0;
  while (!written || s.channel->counters().bytes < (64U << 20U)) {
    if (sent < 20 && polls % 100 == 0) send_all(injector, "{\"line\": " + std::to_string(++sent) + "}\n");
    const std::uint64_t before = s.channel->counters().bytes;
    seen.poll(*s.channel);
    most = std::max(most, s.channel->counters().bytes - before);
    ++polls;
    ASSERT_LT(polls, 1000000U) << "the flood was not drained";
  }
  flood.join();
  seen.poll(*s.channel);
  // Every poll read at most the two clients' budgets.
  EXPECT_LE(most, 2 * s.channel->limits().read_budget);
  EXPECT_TRUE(seen.has("control:1:1 ! longer than 65536 characters; skipped")) << ::testing::PrintToString(seen.items);
  EXPECT_EQ(seen.count_prefix("control:1:"), 1U);
  for (int i = 1; i <= 20; ++i) {
    EXPECT_TRUE(seen.has("control:2:" + std::to_string(i) + " {\"line\": " + std::to_string(i) + "}")) << i;
  }
  // The endless line's client may go on: its next line is its second.
  send_all(endless, "\n{\"after\": true}\n");
  seen.poll(*s.channel);
  EXPECT_TRUE(seen.has("control:1:2 {\"after\": true}")) << ::testing::PrintToString(seen.items);
  EXPECT_EQ(s.channel->counters().overlong, 1U);
}

TEST(ControlChannel, AFloodingClientTakesItsShareOfAPollAndNoMore) {
  Limits limits;
  limits.lines_per_poll = 8;
  Socket s("flood", limits);
  const int flood = s.client();
  const int quiet = s.client();
  std::string lines;
  for (int i = 0; i < 1000; ++i) lines += "flood " + std::to_string(i) + "\n";
  send_all(flood, lines);
  Seen seen;
  seen.poll(*s.channel);  // accepts both; the flood starts
  send_all(quiet, "quiet\n");
  for (int round = 0; round < 3 && !seen.has("control:2:1 quiet"); ++round) {
    const std::size_t before = seen.items.size();
    seen.poll(*s.channel);
    EXPECT_LE(seen.items.size() - before, limits.lines_per_poll);
  }
  // In the first or second poll after it was sent (the starting client moves on), never after the flood.
  EXPECT_TRUE(seen.has("control:2:1 quiet")) << ::testing::PrintToString(seen.items);
  EXPECT_LT(seen.count_prefix("control:1:"), 40U);
  while (seen.count_prefix("control:1:") < 1000U) seen.poll(*s.channel);
  EXPECT_TRUE(seen.has("control:1:1000 flood 999"));
}

TEST(ControlChannel, TheClientAfterTheLastIsRefusedAndToldWhy) {
  Limits limits;
  limits.max_clients = 3;
  Socket s("refused", limits);
  for (int i = 0; i < 3; ++i) s.client();
  const int fourth = s.client();
  ASSERT_GE(fourth, 0) << "the backlog takes the connection; the channel refuses it";
  Seen seen;
  seen.poll(*s.channel);
  EXPECT_TRUE(seen.has("control: a client refused: 3 clients are connected (the most)"))
      << ::testing::PrintToString(seen.notices);
  char buf[256] = {};
  const ssize_t n = ::read(fourth, buf, sizeof buf - 1);
  ASSERT_GT(n, 0);
  EXPECT_STREQ(buf,
               "ibs: refused: 3 clients are connected, the most this channel serves at once; try again when one has "
               "closed\n");
  EXPECT_EQ(::read(fourth, buf, sizeof buf), 0) << "then closed";
  EXPECT_EQ(s.channel->counters().refused, 1U);
  EXPECT_EQ(s.channel->clients(), 3U);
  // One leaves: the next is taken, numbered after the ones taken before.
  ::close(s.fds[0]);
  s.fds[0] = -1;
  seen.poll(*s.channel);
  send_all(s.client(), "hello\n");
  seen.poll(*s.channel);
  EXPECT_TRUE(seen.has("control:4:1 hello")) << ::testing::PrintToString(seen.items);
}

TEST(ControlChannel, TheSocketIsOwnerOnlyWhateverTheUmask) {
  for (const mode_t mask : {mode_t{0}, mode_t{022}, mode_t{077}}) {
    const mode_t before = ::umask(mask);
    {
      Socket s("mode");
      struct stat st {};
      ASSERT_EQ(::lstat(s.path.c_str(), &st), 0);
      EXPECT_TRUE(S_ISSOCK(st.st_mode));
      EXPECT_EQ(st.st_mode & 07777, 0600U) << "umask " << mask;
    }
    EXPECT_EQ(::umask(before), mask) << "the umask is given back";
  }
}

TEST(ControlChannel, APathThatExistsIsNeverReplacedNorOneThatTookTheSocketsPlace) {
  const std::string path = socket_path("exists");
  { std::ofstream(path) << "mine"; }
  std::string error;
  EXPECT_EQ(Channel::open("unix:" + path, error), nullptr);
  EXPECT_NE(error.find(path + " exists"), std::string::npos) << error;
  {
    auto c = Channel::open("unix:" + path + ".sock", error);
    ASSERT_NE(c, nullptr) << error;
    EXPECT_EQ(c->path(), path + ".sock");
    // Someone replaces the socket with a file of theirs while the channel runs.
    ::unlink((path + ".sock").c_str());
    std::ofstream(path + ".sock") << "theirs";
  }
  std::ifstream in(path + ".sock");
  std::string text;
  in >> text;
  EXPECT_EQ(text, "theirs");
  std::ifstream mine(path);
  mine >> text;
  EXPECT_EQ(text, "mine");
  ::unlink(path.c_str());
  ::unlink((path + ".sock").c_str());
  // The socket itself is removed at the end.
  const std::string own = socket_path("own");
  ::unlink(own.c_str());
  { auto c = Channel::open("unix:" + own, error); }
  EXPECT_NE(::access(own.c_str(), F_OK), 0);
  // Other forms and limits of 0 are refused.
  EXPECT_EQ(Channel::open("tcp:1234", error), nullptr);
  EXPECT_NE(error.find("give - (standard input) or unix:PATH"), std::string::npos) << error;
  Limits none;
  none.max_clients = 0;
  EXPECT_EQ(Channel::open("unix:" + own, error, none), nullptr);
}

TEST(ControlChannel, AdoptedStreamsAreClientsToo) {
  Limits limits;
  limits.max_clients = 2;
  auto c = Channel::streams(limits);
  int a[2];
  int b[2];
  int d[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, a), 0);
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, b), 0);
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, d), 0);
  EXPECT_TRUE(c->adopt(a[0]));
  EXPECT_TRUE(c->adopt(b[0]));
  EXPECT_FALSE(c->adopt(d[0]));  // full: closed and refused
  send_all(a[1], "x\n");
  send_all(b[1], "y\n");
  Seen seen;
  seen.poll(*c);
  EXPECT_TRUE(seen.has("control:1:1 x"));
  EXPECT_TRUE(seen.has("control:2:1 y"));
  char ch = 0;
  EXPECT_GT(::read(d[1], &ch, 1), 0) << "the refused one is told";
  for (const int fd : {a[1], b[1], d[1]}) ::close(fd);
}

// The channel is read inside a real-time cycle: a poll allocates nothing, whatever its clients do
// (connect, send lines and endless lines, get refused, hang up).
TEST(ControlChannel, APollAllocatesNothing) {
  Limits limits;
  limits.max_clients = 2;
  limits.max_line = 64;
  Socket s("alloc", limits);
  std::size_t lines = 0;
  std::size_t errors = 0;
  std::size_t notices = 0;
  const Channel::LineFn line = [&](const Origin&, std::string_view) { ++lines; };
  const Channel::ErrorFn error = [&](const Origin&, std::string_view) { ++errors; };
  const Channel::NoticeFn notice = [&](std::string_view) { ++notices; };
  const int a = s.client();
  const int b = s.client();
  const int refused = s.client();
  send_all(a, "one\ntwo\n" + std::string(200, 'z') + "\nthree");
  send_all(b, "b\n");
  {
    test::AllocationCounter counting;
    for (int i = 0; i < 10; ++i) s.channel->poll(line, error, notice);
    ::close(a);
    s.fds[0] = -1;
    for (int i = 0; i < 10; ++i) s.channel->poll(line, error, notice);
    EXPECT_EQ(counting.count(), 0);
  }
  EXPECT_EQ(lines, 4U);
  EXPECT_EQ(errors, 1U);
  EXPECT_EQ(notices, 3U);  // two connected, one refused
  (void)refused;
}

}  // namespace
}  // namespace ibs::control
