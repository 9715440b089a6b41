// The parameter changes a drive's channels made, for whoever records the drive through one face
// only: a recording of its process-data words (`ibs run --trace`) writes the changes the other
// channels made -- the MC6000's PCP, a LUSTBUS face serving the same core -- as `! write PNR
// VALUE` events (../shared/specs/trace-format.md, "Events"), so that the recording replays.
// A face notes each change its channel makes: a value written, and 85-SIOF/SERR when a request
// changed it (a read erases its bits, a refusal sets one). Off until enabled; a fixed number of
// entries (a change noted while it is full is counted, not kept). Cycle path: no allocation, no
// exceptions, no locks (the faces of one drive run on one thread).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace ibs::drive {

struct ParameterChange {
  std::uint16_t number = 0;
  std::uint32_t value = 0;  // the raw value as the channel carried it (85: the bits left)

  friend bool operator==(const ParameterChange&, const ParameterChange&) = default;
};

class ParameterJournal {
 public:
  static constexpr std::size_t kCapacity = 32;

  void enable(bool on) {
    enabled_ = on;
    size_ = 0;
  }
  [[nodiscard]] bool enabled() const { return enabled_; }
  void note(std::uint16_t number, std::uint32_t value) {
    if (!enabled_) return;
    if (size_ == kCapacity) {
      ++dropped_;
      return;
    }
    entries_[size_++] = {number, value};
  }
  // Takes the oldest changes into `out` (as many as fit); returns how many. The rest stay.
  std::size_t take(std::span<ParameterChange> out) {
    const std::size_t n = std::min(out.size(), size_);
    std::copy_n(entries_.begin(), n, out.begin());
    std::copy(entries_.begin() + static_cast<std::ptrdiff_t>(n), entries_.begin() + static_cast<std::ptrdiff_t>(size_),
              entries_.begin());
    size_ -= n;
    return n;
  }
  [[nodiscard]] std::size_t size() const { return size_; }
  // Changes noted while the journal was full, since it was made.
  [[nodiscard]] std::uint32_t dropped() const { return dropped_; }

 private:
  std::array<ParameterChange, kCapacity> entries_{};
  std::size_t size_ = 0;
  std::uint32_t dropped_ = 0;
  bool enabled_ = false;
};

// Notes 85-SIOF/SERR when a channel's request changed it: made before the request, it compares at
// the end of the scope. `Drive` has siof() and journal().
template <typename Drive>
class SiofNote {
 public:
  SiofNote(Drive& drive, std::uint16_t siof_number) : drive_(drive), number_(siof_number), before_(drive.siof()) {}
  ~SiofNote() {
    if (drive_.siof() != before_) drive_.journal().note(number_, drive_.siof());
  }
  SiofNote(const SiofNote&) = delete;
  SiofNote& operator=(const SiofNote&) = delete;

 private:
  Drive& drive_;
  std::uint16_t number_;
  std::uint8_t before_;
};

}  // namespace ibs::drive
