// One client's input of a line channel, sans-I/O: bytes in, complete lines out, each line bounded.
// The buffer is allocated once (max_line + 1 bytes); taking bytes and lines never allocates.
//
//   LineBuffer b(64 * 1024);
//   std::span<char> room = b.space();            // read(fd, room.data(), room.size()) -> n
//   b.commit(n);
//   while (auto item = b.next()) { ... }          // lines and overlong reports, in order
//   if (end of input) if (auto last = b.finish()) { ... }
//
// Lines are numbered from 1 in this input; blank lines and lines whose first non-blank character
// is '#' are counted but not handed out; a trailing '\r' is removed. A line of more than
// max_line characters (its newline not counted) is reported once, as soon as its (max_line + 1)th
// character arrives, and its bytes are dropped up to its newline: the input goes on after it.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string_view>

namespace ibs::control {

class LineBuffer {
 public:
  enum class Kind : unsigned char { none, line, overlong };
  struct Item {
    Kind kind = Kind::none;
    std::size_t number = 0;  // the line's number in this input
    std::string_view text;   // Kind::line: the line, valid until the next call on this buffer
    explicit operator bool() const { return kind != Kind::none; }
  };

  explicit LineBuffer(std::size_t max_line);

  // Where the next bytes go: never empty while no Item is pending (call next() until it gives
  // none first).
  [[nodiscard]] std::span<char> space();
  // n bytes were written at the start of space().
  void commit(std::size_t n);
  // The next line or overlong report from what has arrived; none: more bytes are needed.
  Item next();
  // End of input: the last line, when it had no newline (none otherwise); the buffer is empty
  // afterwards and may take a new input (numbering from 1 again).
  Item finish();
  // Forgets everything (a new input, numbered from 1).
  void reset();

  [[nodiscard]] std::size_t max_line() const { return max_line_; }
  [[nodiscard]] std::size_t lines() const { return number_; }  // numbered so far
  [[nodiscard]] std::size_t buffered() const { return end_ - begin_; }

 private:
  Item take_line(std::size_t length);

  std::size_t max_line_;
  std::unique_ptr<char[]> data_;  // max_line_ + 1 bytes
  std::size_t begin_ = 0;         // the current line's first byte
  std::size_t scan_ = 0;          // bytes before this hold no newline of the current line
  std::size_t end_ = 0;           // one past the last byte taken
  bool skipping_ = false;         // an overlong line: bytes dropped up to its newline
  std::size_t number_ = 0;
};

}  // namespace ibs::control
