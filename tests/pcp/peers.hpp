// Hand-driven peers for protocol-violation tests: a bare master link that sends any PDU to a real
// server, and a bare servo link that answers a real client with any PDU.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "ibs/pcp/client.hpp"
#include "ibs/pcp/link.hpp"
#include "ibs/pcp/server.hpp"

namespace ibs::pcp::test {

inline std::vector<std::uint8_t> pdu_bytes(std::initializer_list<Word> words) {
  std::vector<std::uint8_t> b;
  for (const Word w : words) {
    b.push_back(high_byte(w));
    b.push_back(low_byte(w));
  }
  return b;
}

// A real server driven by a bare master-side link, lock-step 1 ms.
class RawMaster {
 public:
  explicit RawMaster(Server& s)
      : server_(s), link_({s.config().channel_words, Direction::to_server, 1s}) {}

  void step() {
    now_ += 1ms;
    const auto to_server = m2s_;
    const auto from_server = s2m_;
    const LinkEvents ev = link_.receive(now_, from_server);
    if (link_.has_message()) {
      const auto m = link_.message();
      received_.emplace_back(m.begin(), m.end());
      link_.release_message();
    }
    resets_ += ev.reset ? 1 : 0;
    link_.transmit(now_, m2s_);
    server_.step(now_, to_server, s2m_);
  }
  // Sends the PDU and returns the next message from the server within `limit` steps.
  std::optional<std::vector<std::uint8_t>> exchange(const std::vector<std::uint8_t>& pdu,
                                                    int limit = 200) {
    for (int i = 0; i < limit && !link_.can_send(); ++i) step();
    if (!link_.send(pdu)) return std::nullopt;
    const std::size_t before = received_.size();
    for (int i = 0; i < limit && received_.size() == before; ++i) step();
    if (received_.size() == before) return std::nullopt;
    return received_.back();
  }
  // Sends without waiting for an answer (the server may stay silent).
  bool send(const std::vector<std::uint8_t>& pdu, int limit = 200) {
    for (int i = 0; i < limit && !link_.can_send(); ++i) step();
    return link_.send(pdu);
  }
  void run(int steps) {
    for (int i = 0; i < steps; ++i) step();
  }
  [[nodiscard]] const std::vector<std::vector<std::uint8_t>>& received() const { return received_; }
  [[nodiscard]] Time now() const { return now_; }

 private:
  Server& server_;
  Link link_;
  Time now_{};
  std::array<Word, 4> m2s_{};
  std::array<Word, 4> s2m_{};
  std::vector<std::vector<std::uint8_t>> received_;
  int resets_ = 0;
};

// A real client answered by a bare servo-side link, lock-step 1 ms. `answer` maps each received
// message to the reply (nullopt: stay silent).
class FakeServer {
 public:
  using Answer =
      std::function<std::optional<std::vector<std::uint8_t>>(const std::vector<std::uint8_t>&)>;
  FakeServer(Client& c, Answer a)
      : client_(c),
        answer_(std::move(a)),
        link_({c.config().channel_words, Direction::to_client, 1s, true}) {}

  void step() {
    now_ += 1ms;
    const auto to_server = m2s_;
    const auto from_server = s2m_;
    client_.step(now_, from_server, m2s_);
    link_.receive(now_, to_server);
    if (link_.has_message()) {
      const auto m = link_.message();
      received_.emplace_back(m.begin(), m.end());
      link_.release_message();
      if (auto reply = answer_(received_.back())) pending_ = *reply;
    }
    if (pending_ && link_.can_send() && link_.send(*pending_)) pending_.reset();
    link_.transmit(now_, s2m_);
  }
  std::optional<Result> await(int limit = 2000) {
    for (int i = 0; i < limit; ++i) {
      step();
      if (auto r = client_.take_result()) return r;
    }
    return std::nullopt;
  }
  void run(int steps) {
    for (int i = 0; i < steps; ++i) step();
  }
  [[nodiscard]] const std::vector<std::vector<std::uint8_t>>& received() const { return received_; }
  [[nodiscard]] Time now() const { return now_; }

 private:
  Client& client_;
  Answer answer_;
  Link link_;
  Time now_{};
  std::array<Word, 4> m2s_{};
  std::array<Word, 4> s2m_{};
  std::vector<std::vector<std::uint8_t>> received_;
  std::optional<std::vector<std::uint8_t>> pending_;
};

}  // namespace ibs::pcp::test
