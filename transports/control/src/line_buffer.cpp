#include "ibs/control/line_buffer.hpp"

#include <cstring>
#include <stdexcept>

namespace ibs::control {

LineBuffer::LineBuffer(std::size_t max_line) : max_line_(max_line) {
  if (max_line == 0) throw std::invalid_argument("LineBuffer: max_line must be at least 1");
  data_ = std::make_unique<char[]>(max_line + 1);
}

void LineBuffer::reset() {
  begin_ = scan_ = end_ = 0;
  skipping_ = false;
  number_ = 0;
}

std::span<char> LineBuffer::space() {
  if (begin_ > 0) {
    // What is left of the current line goes to the front.
    std::memmove(data_.get(), data_.get() + begin_, end_ - begin_);
    scan_ -= begin_;
    end_ -= begin_;
    begin_ = 0;
  }
  return {data_.get() + end_, max_line_ + 1 - end_};
}

void LineBuffer::commit(std::size_t n) {
  if (n > max_line_ + 1 - end_) throw std::logic_error("LineBuffer::commit: more bytes than space() had");
  if (!skipping_) {
    end_ += n;
    return;
  }
  // The rest of an overlong line: dropped up to and with its newline.
  const char* p = data_.get() + end_;
  const void* nl = std::memchr(p, '\n', n);
  if (nl == nullptr) return;
  skipping_ = false;
  begin_ = scan_ = static_cast<std::size_t>(static_cast<const char*>(nl) - data_.get()) + 1;
  end_ += n;
}

LineBuffer::Item LineBuffer::take_line(std::size_t length) {
  ++number_;
  std::string_view text(data_.get() + begin_, length);
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos || text[first] == '#') return {Kind::none, number_, {}};
  return {Kind::line, number_, text};
}

LineBuffer::Item LineBuffer::next() {
  while (true) {
    const void* nl = std::memchr(data_.get() + scan_, '\n', end_ - scan_);
    if (nl == nullptr) break;
    const auto at = static_cast<std::size_t>(static_cast<const char*>(nl) - data_.get());
    const std::size_t line_begin = begin_;
    Item item = take_line(at - line_begin);
    begin_ = scan_ = at + 1;
    if (item.kind == Kind::line) {
      // The text stays where it is until the next call (space() moves bytes, next() does not).
      return item;
    }
  }
  scan_ = end_;
  if (end_ - begin_ > max_line_) {
    // No newline within max_line + 1 characters: too long. Reported now, dropped to its end.
    ++number_;
    begin_ = scan_ = end_ = 0;
    skipping_ = true;
    return {Kind::overlong, number_, {}};
  }
  return {};
}

LineBuffer::Item LineBuffer::finish() {
  Item item;
  if (!skipping_ && end_ > begin_) {
    item = take_line(end_ - begin_);
    if (item.kind == Kind::none) item = {};
  }
  // The text of `item` stays valid: reset() moves no bytes.
  begin_ = scan_ = end_ = 0;
  skipping_ = false;
  number_ = 0;
  return item;
}

}  // namespace ibs::control
