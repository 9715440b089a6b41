// Helpers of the LUSTBUS tests: byte strings, a responder that records what reached it, and a
// host + devices on a simulated line.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "fake_drive.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/line.hpp"
#include "ibs/lustbus/receiver.hpp"

namespace ibs::lustbus::test {

// Bytes{}(4)(64)("00112")(5).v
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

inline std::vector<std::uint8_t> to_vector(std::span<const std::uint8_t> s) {
  return {s.begin(), s.end()};
}

inline std::string hex(const std::vector<std::uint8_t>& v) {
  std::string s;
  char b[4];
  for (const auto x : v) {
    std::snprintf(b, sizeof b, "%02X ", x);
    s += b;
  }
  return s;
}

// Records every call; answers as told.
class RecordingResponder : public Responder {
 public:
  EnquiryAnswer enquiry_answer = EnquiryAnswer::text(make_value("03E8"));
  SelectAnswer select_answer = SelectAnswer::ack();
  int enquiries = 0;
  int selects = 0;
  int checksum_errors = 0;
  int telegrams = 0;
  Code last_code{};
  Value last_value{};
  Context last_ctx{};

  EnquiryAnswer enquiry(const Code& c, const Context& ctx) override {
    ++enquiries;
    last_code = c;
    last_ctx = ctx;
    return enquiry_answer;
  }
  SelectAnswer select(const Code& c, const Value& v, const Context& ctx) override {
    ++selects;
    last_code = c;
    last_value = v;
    last_ctx = ctx;
    return select_answer;
  }
  void checksum_error(const Context& ctx) override {
    ++checksum_errors;
    last_ctx = ctx;
  }
  void telegram_received(const Context&) override { ++telegrams; }
};

// Feeds bytes at one instant; returns the receiver's answer (taken at `now` + a long time).
inline std::vector<std::uint8_t> feed(Receiver& r, const std::vector<std::uint8_t>& bytes,
                                      Time now = Time{0}) {
  for (const auto b : bytes) r.receive(b, now);
  return to_vector(r.take_answer(now + 10s));
}

// A host and devices on one line.
struct Bus {
  explicit Bus(HostConfig cfg = {}, std::uint32_t baud = 9600) : host(cfg), line(baud) {
    line.attach(host);
  }
  Receiver& add(FakeDrive& d, Address a) {
    receivers.push_back(std::make_unique<Receiver>(d, a));
    line.attach(*receivers.back());
    return *receivers.back();
  }
  // Submits and runs until the host is idle; the outcome.
  Outcome run(const Request& r, Duration limit = 60s) {
    const auto s = host.submit(r);
    EXPECT_TRUE(s) << to_string(s.error);
    EXPECT_TRUE(line.run_until_idle(line.now() + limit));
    const Outcome* o = host.outcome(s.id);
    EXPECT_NE(o, nullptr);
    return o ? *o : Outcome{};
  }
  Host host;
  Line line;
  std::vector<std::unique_ptr<Receiver>> receivers;
};

}  // namespace ibs::lustbus::test
