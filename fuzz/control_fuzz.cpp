// The test bench's live control lines (docs/testbench.md): `ibs run --realtime --control` reads
// each as a timeline entry without `at` against the running scenario (sim::parse_control_line);
// `ibs dfs1 emulate --control` reads its own (parse_dfs1_control_line, the DFS-1 wing's event
// reader the bench uses too); and the channel that carries them (transports/control,
// control::Channel) with several clients whose bytes arrive interleaved (issue 41).
//
// Input: byte 0 chooses the part: bit 1 set: the channel; else bit 0: DFS-1 line, clear: the
// run's line; for a line the rest is one line of text.
// The channel's input: one byte each for the number of clients (1..4), max_clients (1..4),
// max_line (1..48), read_budget (1..64) and lines_per_poll (1..8); then operations, one byte each
// with what follows: a write of a client (its bytes: a length byte, then that many bytes), a
// client's end of input, or a poll. At the end every client ends and the channel is polled until
// it has none.
//
// Asserts:
// - parse_control_line refuses only with a sim::ScenarioError whose what() is `control:7: ...`
//   (the channel's line number given, never another); an accepted entry has no `at`, names a
//   device or controller of the bench scenario, and write_control_line writes it so that
//   parse_control_line reads it back equal;
// - parse_dfs1_control_line gives either an event or an error that says what, never both or
//   neither, and throws nothing;
// - the channel: a client beyond max_clients is refused, every other is numbered from 1 in the
//   order it came; each client's lines and overlong reports are exactly those of its own bytes
//   split as documented (lines of at most max_line characters, blank and '#' lines counted but
//   not handed out, a trailing '\r' removed, a last line without newline at its end), in order,
//   named `control:CLIENT` with their line numbers, whatever the interleaving; a poll hands out at
//   most lines_per_poll lines (plus the last line of each client that ended) and reads at most
//   read_budget bytes from each client; and each line's refusal by the run's reader names
//   `control:CLIENT:LINE`.
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "dfs1_cmd.hpp"
#include "fuzz_support.hpp"
#include "ibs/control/channel.hpp"
#include "ibs/sim/scenario.hpp"

namespace {

using namespace ibs;
using ibs::fuzz::fail;

// A bench: a servo and an inverter on the ring and on LUSTBUS, a DFS-1 controller on its line.
const sim::Scenario& bench() {
  static const sim::Scenario s = sim::parse_scenario_toml(R"(name = "bench"
duration = "8 s"
[[device]]
name = "servo"
type = "mc6000"
lustbus = 1
[[device]]
name = "fan"
type = "vf1000"
lustbus = 2
[lustbus]
pty = true
[dfs1]
pty = true
[[dfs1.controller]]
name = "press"
uid = 7
)",
                                                          "bench.toml");
  return s;
}

void interbus_line(const std::string& text) {
  sim::TimelineEntry e;
  try {
    e = sim::parse_control_line(text, 7, bench());
  } catch (const sim::ScenarioError& err) {
    const std::string what = err.what();
    if (what.rfind("control:7: ", 0) != 0 || what.size() == 11) fail("a refusal without its line: '" + what + "'");
    return;
  } catch (const std::exception& err) {
    fail(std::string("parse_control_line threw something else: ") + err.what());
  }
  if (e.at != Time{0}) fail("an accepted control line has a time");
  if (e.source_line != 7) fail("an accepted control line forgot its line");
  const std::string again = sim::write_control_line(e);
  try {
    if (!(sim::parse_control_line(again, 7, bench()) == e)) fail("write_control_line does not read back equal: " + again);
  } catch (const std::exception& err) {
    fail("write_control_line wrote a line its reader refuses: " + again + ": " + err.what());
  }
}

void dfs1_line(const std::string& text) {
  try {
    const auto parsed = cli::parse_dfs1_control_line(text);
    if (parsed.event.has_value() == !parsed.error.empty()) fail("an event and an error, or neither: " + parsed.error);
  } catch (const std::exception& err) {
    fail(std::string("parse_dfs1_control_line threw: ") + err.what());
  }
}

// What the channel must hand out for a client's bytes: "N:text" and "N:overlong", as documented.
std::vector<std::string> expected_items(const std::string& bytes, std::size_t max_line) {
  std::vector<std::string> out;
  std::size_t number = 0;
  std::size_t begin = 0;
  while (begin < bytes.size()) {
    const std::size_t nl = bytes.find('\n', begin);
    const std::size_t end = nl == std::string::npos ? bytes.size() : nl;
    std::string_view line(bytes.data() + begin, end - begin);
    ++number;
    if (line.size() > max_line) {
      out.push_back(std::to_string(number) + ":overlong");
    } else {
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      const auto first = line.find_first_not_of(" \t");
      if (first != std::string_view::npos && line[first] != '#') out.push_back(std::to_string(number) + ":" + std::string(line));
    }
    if (nl == std::string::npos) break;
    begin = nl + 1;
  }
  return out;
}

void channel(ibs::fuzz::Input& in) {
  const std::size_t n = 1 + in.ConsumeIntegral<std::uint8_t>() % 4;
  control::Limits limits;
  limits.max_clients = 1 + in.ConsumeIntegral<std::uint8_t>() % 4;
  limits.max_line = 1 + in.ConsumeIntegral<std::uint8_t>() % 48;
  limits.read_budget = 1 + in.ConsumeIntegral<std::uint8_t>() % 64;
  limits.lines_per_poll = 1 + in.ConsumeIntegral<std::uint8_t>() % 8;
  auto ch = control::Channel::streams(limits);
  struct Client {
    int ours = -1;             // the channel's end
    int theirs = -1;           // the client's end; -1 once it has ended its input
    std::uint32_t number = 0;  // 0: refused
    std::string bytes;
    std::vector<std::string> seen;
  };
  std::vector<Client> clients(n);
  std::uint32_t next = 1;
  for (Client& c : clients) {
    int fds[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0, fds) != 0) fail("socketpair");
    c.ours = fds[0];
    c.theirs = fds[1];
    const bool taken = ch->adopt(c.ours);
    if (taken != (next - 1 < limits.max_clients)) fail("a client taken beyond max_clients, or refused below it");
    if (taken) c.number = next++;
  }
  const sim::Scenario& running = bench();
  const auto client_of = [&](const control::Origin& o) -> Client& {
    for (Client& c : clients) {
      if (c.number != 0 && c.number == o.client) {
        if (o.name != "control:" + std::to_string(c.number)) fail("a line named " + std::string(o.name));
        return c;
      }
    }
    fail("a line of a client never taken");
  };
  std::size_t handed = 0;
  const control::Channel::LineFn line = [&](const control::Origin& o, std::string_view text) {
    ++handed;
    Client& c = client_of(o);
    c.seen.push_back(std::to_string(o.line) + ":" + std::string(text));
    if (c.seen.size() > 4) return;  // the reader's own checks are the line parts'; a few here
    try {
      (void)sim::parse_control_line(std::string(text), o.line, running, std::string(o.name));
    } catch (const sim::ScenarioError& err) {
      const std::string prefix = std::string(o.name) + ":" + std::to_string(o.line) + ": ";
      if (std::string(err.what()).rfind(prefix, 0) != 0) fail("a refusal without its client and line: " + std::string(err.what()));
    }
  };
  const control::Channel::ErrorFn error = [&](const control::Origin& o, std::string_view) {
    ++handed;
    client_of(o).seen.push_back(std::to_string(o.line) + ":overlong");
  };
  const auto poll = [&] {
    handed = 0;
    const std::uint64_t bytes = ch->counters().bytes;
    const std::size_t open = ch->clients();
    ch->poll(line, error);
    if (handed > limits.lines_per_poll + open) fail("a poll handed out more than its lines");
    if (ch->counters().bytes - bytes > open * limits.read_budget) fail("a poll read more than its budget");
  };
  while (in.remaining_bytes() > 0) {
    const auto op = in.ConsumeIntegral<std::uint8_t>();
    Client& c = clients[(op >> 2U) % n];
    switch (op % 4) {
      case 0:
      case 1: {
        const auto bytes = in.ConsumeBytes<char>(in.ConsumeIntegral<std::uint8_t>() % 64);
        if (c.theirs < 0 || bytes.empty()) break;
        const ssize_t w = ::send(c.theirs, bytes.data(), bytes.size(), MSG_NOSIGNAL);
        if (w > 0) c.bytes.append(bytes.data(), static_cast<std::size_t>(w));
        break;
      }
      case 2:
        if (c.theirs >= 0) ::close(c.theirs);
        c.theirs = -1;
        break;
      default: poll(); break;
    }
  }
  for (Client& c : clients) {
    if (c.theirs >= 0) ::close(c.theirs);
    c.theirs = -1;
  }
  for (int i = 0; i < 100000 && ch->clients() > 0; ++i) poll();
  if (ch->clients() != 0) fail("clients that ended were never closed");
  for (const Client& c : clients) {
    if (c.number == 0) continue;
    if (c.seen != expected_items(c.bytes, limits.max_line)) {
      std::string s;
      for (const auto& x : c.seen) s += "[" + x + "]";
      fail("client " + std::to_string(c.number) + " was handed out other lines than its bytes: " + s);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  if ((data[0] & 2U) != 0) {
    ibs::fuzz::Input in(data + 1, size - 1);
    channel(in);
    return 0;
  }
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  if ((data[0] & 1U) != 0) {
    dfs1_line(text);
  } else {
    interbus_line(text);
  }
  return 0;
}
