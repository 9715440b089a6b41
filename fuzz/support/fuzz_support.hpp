// What every fuzz target shares: how a violated invariant ends the run (a message on stderr, then
// abort(), which libFuzzer reports as a crash and saves the input), the `FILE:LINE: message` check
// of refusals, and a reader of structured input from the fuzzer's bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace ibs::fuzz {

// Structured input read front to back, integers big-endian, so that seeds read as they are
// written (a control word 0006 is the bytes 00 06). Past the end every read gives zeros.
// (FuzzedDataProvider reads integers from the back, which makes hand-made seeds unreadable.)
class Input {
 public:
  Input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  [[nodiscard]] std::size_t remaining_bytes() const { return size_ - pos_; }

  template <typename T>
  T ConsumeIntegral() {
    static_assert(std::is_integral_v<T>);
    using U = std::make_unsigned_t<T>;
    U v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) v = static_cast<U>((v << 8U) | byte());
    return static_cast<T>(v);
  }
  // lo + (a number read in as many bytes as the range needs) modulo the range.
  template <typename T>
  T ConsumeIntegralInRange(T lo, T hi) {
    const auto range = static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo);
    std::uint64_t v = 0;
    for (std::uint64_t r = range; r != 0; r >>= 8U) v = (v << 8U) | byte();
    return static_cast<T>(static_cast<std::uint64_t>(lo) + (range == ~std::uint64_t{0} ? v : v % (range + 1)));
  }
  bool ConsumeBool() { return (byte() & 1U) != 0; }
  // Up to n bytes (fewer at the end of the input).
  template <typename T>
  std::vector<T> ConsumeBytes(std::size_t n) {
    static_assert(sizeof(T) == 1);
    const std::size_t k = n < remaining_bytes() ? n : remaining_bytes();
    std::vector<T> out(data_ + pos_, data_ + pos_ + k);
    pos_ += k;
    return out;
  }

 private:
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

// A violated invariant: says what, and aborts so that libFuzzer keeps the input.
[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "\n==ibs-fuzz== INVARIANT VIOLATED: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

#define IBS_FUZZ_REQUIRE(cond, message)                                                            \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      ::ibs::fuzz::fail(std::string(__FILE__ ":") + std::to_string(__LINE__) + ": " #cond ": " +  \
                        std::string(message));                                                     \
    }                                                                                              \
  } while (0)

// The number of lines a text has as the readers count them: one more than its newlines.
inline std::size_t count_lines(std::string_view text) {
  std::size_t n = 1;
  for (const char c : text) n += c == '\n' ? 1U : 0U;
  return n;
}

// Why `what` is not `FILE:LINE: message` with this file, a line 1..max_line and a message that
// is not empty; "" when it is.
inline std::string file_line_problem(std::string_view what, std::string_view file, std::size_t max_line) {
  if (what.substr(0, file.size()) != file || what.size() <= file.size() || what[file.size()] != ':') {
    return "does not start with '" + std::string(file) + ":'";
  }
  std::size_t i = file.size() + 1;
  std::size_t line = 0;
  std::size_t digits = 0;
  while (i < what.size() && what[i] >= '0' && what[i] <= '9' && digits < 12) {
    line = line * 10 + static_cast<std::size_t>(what[i] - '0');
    ++i;
    ++digits;
  }
  if (digits == 0) return "has no line number after the file name";
  if (line < 1 || line > max_line) {
    return "names line " + std::to_string(line) + ", outside the input's lines 1.." + std::to_string(max_line);
  }
  if (what.substr(i, 2) != ": ") return "has no ': ' after the line number";
  if (what.size() <= i + 2) return "has an empty message";
  return "";
}

inline std::string hex4(unsigned w) {
  char b[8];
  std::snprintf(b, sizeof b, "%04X", w & 0xFFFFU);
  return b;
}

// The last N steps of a run, for the message of a violated invariant: each a pair of words
// (`IN>OUT`) or a note (a string literal: "restart", "power-on", ...). Cheap to record every
// step; formatted only when something fails.
template <std::size_t N = 48>
class Recent {
 public:
  void words(unsigned in, unsigned out) { push({nullptr, in, out}); }
  void note(const char* what) { push({what, 0, 0}); }
  [[nodiscard]] std::string str() const {
    std::string s;
    const std::size_t n = count_ < N ? count_ : N;
    for (std::size_t i = 0; i < n; ++i) {
      const Entry& e = ring_[(next_ + N - n + i) % N];
      s += ' ';
      s += e.note != nullptr ? std::string(e.note) : hex4(e.in) + ">" + hex4(e.out);
    }
    return s;
  }

 private:
  struct Entry {
    const char* note;
    unsigned in;
    unsigned out;
  };
  void push(const Entry& e) {
    ring_[next_] = e;
    next_ = (next_ + 1) % N;
    ++count_;
  }
  Entry ring_[N]{};
  std::size_t next_ = 0;
  std::size_t count_ = 0;
};

}  // namespace ibs::fuzz
