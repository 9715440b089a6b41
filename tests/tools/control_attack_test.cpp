// Issue 41's attack on the live control channel of `ibs run --realtime --control unix:PATH`, as a
// user's scripts would make it: one client sends a 64 MiB line without a newline and stays
// connected, eleven more each send a good line and a bad one (one of them a fault injection), one
// more only garbage. Every good line is applied (the summary lists it with its client), every bad
// line is reported with its client and line, the run ends on time with exit 0 and removes its
// socket.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace std::chrono_literals;

std::string temp(const std::string& name) {
  return ::testing::TempDir() + "ibs_attack_" + std::to_string(::getpid()) + "_" + name;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

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

bool send_all(int fd, const std::string& text) {
  std::size_t at = 0;
  while (at < text.size()) {
    const ssize_t n = ::send(fd, text.data() + at, text.size() - at, MSG_NOSIGNAL);
    if (n <= 0) return false;
    at += static_cast<std::size_t>(n);
  }
  return true;
}

TEST(ControlAttack, AnEndlessLineAndGarbageBlockNoneOfTwelveClients) {
  const std::string scenario = temp("attack.toml");
  std::ofstream(scenario) << "duration = \"4 s\"\n[[device]]\nname = \"servo\"\ntype = \"mc6000\"\n"
                             "[[timeline]]\nat = \"0 s\"\ndevice = \"servo\"\nstate = \"enabled\"\n";
  const std::string sock = temp("control.sock");
  const std::string out = temp("out.txt");
  const std::string err = temp("err.txt");
  ::unlink(sock.c_str());
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen(out.c_str(), "w", stdout);
    std::freopen(err.c_str(), "w", stderr);
    ::execl(IBS_CLI, IBS_CLI, "run", scenario.c_str(), "--realtime", "--control", ("unix:" + sock).c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ASSERT_GT(pid, 0);
  // The socket exists once the run has opened it (an overall deadline of 10 s).
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (::access(sock.c_str(), F_OK) != 0 && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(10ms);
  ASSERT_EQ(::access(sock.c_str(), F_OK), 0) << "no socket: " << slurp(err);

  // Client 1: an endless line, held open until the run ends (its sends then fail).
  const int endless = connect_to(sock);
  ASSERT_GE(endless, 0);
  std::atomic<std::size_t> flooded{0};
  std::thread flood([&] {
    const std::string chunk(1 << 20, 'x');
    for (int i = 0; i < 64 && send_all(endless, chunk); ++i) flooded += chunk.size();
  });
  std::this_thread::sleep_for(100ms);
  // Clients 2..12: a good line and a bad one each; client 2's good line is a fault injection.
  std::vector<int> clients;
  for (int i = 0; i < 11; ++i) {
    const int fd = connect_to(sock);
    ASSERT_GE(fd, 0) << "client " << i + 2 << " could not connect";
    clients.push_back(fd);
  }
  ASSERT_TRUE(send_all(clients[0], "{\"device\": \"servo\", \"fault\": \"device\", \"cause\": \"E-OP1\", \"duration\": \"0.5 s\"}\n"
                                   "{\"device\": \"servo\", \"speed\": }\n"));
  for (std::size_t i = 1; i < clients.size(); ++i) {
    ASSERT_TRUE(send_all(clients[i], "{\"device\": \"servo\", \"speed\": " + std::to_string(100 * i) + "}\n" +
                                         "{\"device\": \"nobody\", \"speed\": 1}\n"));
  }
  // Client 13: garbage only, and it stays.
  const int garbage = connect_to(sock);
  ASSERT_GE(garbage, 0);
  ASSERT_TRUE(send_all(garbage, std::string("\x01\x02 not json\n[1, 2]\n")));

  int status = 0;
  pid_t done = 0;
  const auto end = std::chrono::steady_clock::now() + 30s;
  while ((done = ::waitpid(pid, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(20ms);
  }
  if (done == 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    FAIL() << "the run did not end within 30 s";
  }
  flood.join();
  for (const int fd : clients) ::close(fd);
  ::close(endless);
  ::close(garbage);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_NE(::access(sock.c_str(), F_OK), 0) << "the socket is removed at exit";

  const std::string o = slurp(out);
  const std::string e = slurp(err);
  // The endless line: reported once, with its client, while it was still being sent.
  EXPECT_NE(e.find("control:1:1: longer than 65536 characters; skipped\n"), std::string::npos) << e;
  // Every good line applied, with its client.
  EXPECT_NE(o.find(R"(client 2 line 1     {"device": "servo", "fault": "device", "duration": "500 ms", "cause": "E-OP1"})"),
            std::string::npos)
      << o;
  EXPECT_NE(o.find("error 16 (E-OP1)"), std::string::npos) << o;
  for (std::size_t i = 1; i < 11; ++i) {
    const std::string line = "client " + std::to_string(i + 2) + " line 1     {\"device\": \"servo\", \"speed\": " +
                             std::to_string(100 * i) + ".0}";
    EXPECT_NE(o.find(line), std::string::npos) << line << "\n" << o;
    // And every bad line reported with its client and line.
    EXPECT_NE(e.find("control:" + std::to_string(i + 2) + ":2: unknown device 'nobody'"), std::string::npos)
        << i + 2 << "\n" << e;
  }
  EXPECT_NE(e.find("control:2:2: JSON syntax error"), std::string::npos) << e;
  EXPECT_NE(e.find("control:13:1: "), std::string::npos) << e;
  EXPECT_NE(e.find("control:13:2: "), std::string::npos) << e;
  EXPECT_NE(e.find("control:12: connected (pid " + std::to_string(::getpid()) + ")"), std::string::npos) << e;
  ::unlink(scenario.c_str());
  ::unlink(out.c_str());
  ::unlink(err.c_str());
}

}  // namespace
