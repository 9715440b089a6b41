// A deliberately loose model of the PCP channel's receiving side, written from docs/pcp.md
// ("Segmentation") rather than from pcp::Link: which messages *could* a receiver have assembled
// from the frames it saw? It starts a candidate at every FIRST frame, appends a NEXT or LAST frame
// whose SEQ follows the candidate's last one (any other SEQ is a repeat, an old frame or the
// second of a window whose first was missed: the candidate waits), and at a LAST frame keeps the
// candidate's first `4 + 2 * count` bytes if they lie in 6..134 (no link CRC: INTERBUS checks
// every cycle). Over 4 words a LAST frame alone is a message too. It ignores aborts,
// acknowledgements, flow control and timeouts, so what it offers is a superset of what a correct
// receiver may deliver: a delivered message or an executed request that it does not offer came
// from nowhere.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "ibs/base/words.hpp"

namespace ibs::fuzz {

using Bytes = std::vector<std::uint8_t>;

class PlausibleMessages {
 public:
  // `channel_words`: 1, 2 or 4; `from_client`: the frames are the master's (DIR 0).
  PlausibleMessages(int channel_words, bool from_client)
      : words_(static_cast<std::size_t>(channel_words)), dir_(from_client ? 0U : 1U) {}

  // One frame as the receiver saw it; returns the messages (PDUs) it completes.
  std::vector<Bytes> feed(std::span<const Word> frame) {
    std::vector<Bytes> done;
    if (frame.size() < words_) return done;
    std::array<std::uint8_t, 8> b{};
    for (std::size_t i = 0; i < words_; ++i) {
      b[2 * i] = static_cast<std::uint8_t>(frame[i] >> 8U);
      b[2 * i + 1] = static_cast<std::uint8_t>(frame[i] & 0xFFU);
    }
    const unsigned admin = b[0];
    if (std::popcount(admin) % 2 == 0) return done;  // odd parity
    if ((admin >> 7U) != dir_) return done;
    const unsigned type = (admin >> 5U) & 3U;
    const auto seq = static_cast<std::uint8_t>((admin >> 3U) & 3U);
    if (type == 0) return done;  // control frames carry no data
    const std::span<const std::uint8_t> data(b.data() + 1, 2 * words_ - 1);

    std::vector<Candidate> next;
    for (Candidate& c : candidates_) {
      if (type == 1 || seq == c.last) {
        next.push_back(std::move(c));  // a FIRST (the candidate goes on), or a repeat
        continue;
      }
      if (seq != ((c.last + 1U) & 3U)) {
        next.push_back(std::move(c));  // not the next: the receiver waits for it
        continue;
      }
      c.bytes.insert(c.bytes.end(), data.begin(), data.end());
      c.last = seq;
      if (type == 3) {
        if (auto m = complete(c.bytes)) done.push_back(std::move(*m));
        continue;
      }
      if (c.bytes.size() <= 300) next.push_back(std::move(c));
    }
    if (type == 3 && words_ == 4) {
      // A message of one frame (the 6-byte requests fit 7 data bytes).
      if (auto m = complete(Bytes(data.begin(), data.end()))) done.push_back(std::move(*m));
    }
    if (type == 1) {
      Candidate c{Bytes(data.begin(), data.end()), seq};
      if (std::none_of(next.begin(), next.end(), [&](const Candidate& o) { return o.last == c.last && o.bytes == c.bytes; })) {
        next.push_back(std::move(c));
      }
    }
    candidates_ = std::move(next);
    if (candidates_.size() > 512) {
      // Too many to follow: from here on anything is plausible (the model stays sound).
      overflowed_ = true;
      candidates_.clear();
    }
    return done;
  }

  // True once the model gave up following the candidates (then every message is plausible).
  [[nodiscard]] bool overflowed() const { return overflowed_; }

 private:
  struct Candidate {
    Bytes bytes;
    std::uint8_t last = 0;
  };

  static std::optional<Bytes> complete(const Bytes& b) {
    if (b.size() < 4) return std::nullopt;
    const std::size_t pdu = 4U + 2U * ((static_cast<std::size_t>(b[2]) << 8U) | b[3]);
    if (pdu < 6 || pdu > 134 || b.size() < pdu) return std::nullopt;
    return Bytes(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(pdu));
  }

  std::size_t words_;
  unsigned dir_;
  std::vector<Candidate> candidates_;
  bool overflowed_ = false;
};

}  // namespace ibs::fuzz
