// Helpers of the wings' LUSTBUS tests: byte strings, one receiver fed directly, and a host with
// devices on a simulated line.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/line.hpp"
#include "ibs/lustbus/receiver.hpp"
#include "ibs/lustbus/telegram.hpp"

namespace ibs::lustbus::devtest {

using namespace std::chrono_literals;

struct Bytes {
  std::vector<std::uint8_t> v;
  Bytes& operator()(int b) {
    v.push_back(static_cast<std::uint8_t>(b));
    return *this;
  }
  Bytes& operator()(std::string_view s) {
    for (const char c : s) v.push_back(static_cast<std::uint8_t>(c));
    return *this;
  }
};

// Feeds a telegram at `now`, returns the answer and when it is due (relative to `now`), then
// ends the exchange with the host's EOT.
struct Fed {
  std::vector<std::uint8_t> answer;
  Duration due{};
};
inline Fed feed(Receiver& r, const std::vector<std::uint8_t>& bytes, Time now) {
  for (const auto b : bytes) r.receive(b, now);
  Fed f;
  if (const auto d = r.answer_due()) {
    f.due = *d - now;
    const auto a = r.take_answer(*d);
    f.answer.assign(a.begin(), a.end());
  }
  r.receive(kEot, now + 200ms);
  return f;
}
inline std::vector<std::uint8_t> bytes(std::span<const std::uint8_t> s) { return {s.begin(), s.end()}; }
// A SELECT / an ENQUIRY as the host sends it, the BCC by the rule of 2.2.
inline std::vector<std::uint8_t> sel(Address a, std::uint32_t code, std::string_view v) {
  return bytes(encode_select(a, make_code(code), make_value(v)).span());
}
inline std::vector<std::uint8_t> enq(Address a, std::uint32_t code) {
  return bytes(encode_enquiry(a, make_code(code)).span());
}

struct Bus {
  explicit Bus(HostConfig cfg = {}) : host(cfg), line(9600) { line.attach(host); }
  void add(Responder& d, Address a) {
    receivers.push_back(std::make_unique<Receiver>(d, a));
    line.attach(*receivers.back());
  }
  Outcome run(const Request& r, Duration limit = 60s) {
    const auto s = host.submit(r);
    EXPECT_TRUE(s) << to_string(s.error);
    EXPECT_TRUE(line.run_until_idle(line.now() + limit));
    const Outcome* o = host.outcome(s.id);
    EXPECT_NE(o, nullptr);
    return o ? *o : Outcome{};
  }
  Outcome read(Address a, std::uint32_t code) { return run(enquiry(a, make_code(code))); }
  // Lets time pass on the line without a telegram (a drive's ramp, a self-test).
  void wait(Duration d) { line.run_until(line.now() + d); }
  Outcome write(Address a, std::uint32_t code, std::string_view v) {
    return run(select(a, make_code(code), make_value(v)));
  }
  Host host;
  Line line;
  std::vector<std::unique_ptr<Receiver>> receivers;
};

}  // namespace ibs::lustbus::devtest
