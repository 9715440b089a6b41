#include "ibs/interbus/process_image.hpp"

#include <algorithm>

namespace ibs::interbus {

std::span<Word> ProcessImage::words(Area a) noexcept {
  switch (a) {
    case Area::in:
      return in;
    case Area::out:
      return out;
    case Area::pcp_in:
      return pcp_in;
    case Area::pcp_out:
      return pcp_out;
  }
  return {};
}

std::span<const Word> ProcessImage::words(Area a) const noexcept {
  switch (a) {
    case Area::in:
      return in;
    case Area::out:
      return out;
    case Area::pcp_in:
      return pcp_in;
    case Area::pcp_out:
      return pcp_out;
  }
  return {};
}

namespace {
// True when [offset, offset + length) lies inside [0, size), without overflow.
constexpr bool inside(std::size_t offset, std::size_t length, std::size_t size) {
  return offset <= size && length <= size - offset;
}
}  // namespace

std::span<Word> ProcessImage::slice(Area a, Slice s) noexcept {
  const std::span<Word> w = words(a);
  if (!inside(s.offset, s.length, w.size())) return {};
  return w.subspan(s.offset, s.length);
}

std::span<const Word> ProcessImage::slice(Area a, Slice s) const noexcept {
  const std::span<const Word> w = words(a);
  if (!inside(s.offset, s.length, w.size())) return {};
  return w.subspan(s.offset, s.length);
}

bool ProcessImage::read_bytes(Area a, std::size_t byte_address,
                              std::span<std::uint8_t> dst) const noexcept {
  const std::span<const Word> w = words(a);
  if (!inside(byte_address, dst.size(), w.size() * 2)) return false;
  for (std::size_t i = 0; i < dst.size(); ++i) {
    const std::size_t b = byte_address + i;
    const Word word = w[b / 2];
    dst[i] = (b % 2 == 0) ? high_byte(word) : low_byte(word);
  }
  return true;
}

bool ProcessImage::write_bytes(Area a, std::size_t byte_address,
                               std::span<const std::uint8_t> src) noexcept {
  const std::span<Word> w = words(a);
  if (!inside(byte_address, src.size(), w.size() * 2)) return false;
  for (std::size_t i = 0; i < src.size(); ++i) {
    const std::size_t b = byte_address + i;
    Word& word = w[b / 2];
    word = (b % 2 == 0) ? make_word(src[i], low_byte(word)) : make_word(high_byte(word), src[i]);
  }
  return true;
}

std::uint8_t ProcessImage::byte(Area a, std::size_t byte_address) const noexcept {
  std::array<std::uint8_t, 1> b{};
  return read_bytes(a, byte_address, b) ? b[0] : std::uint8_t{0};
}

void ProcessImage::clear() noexcept {
  in.fill(0);
  out.fill(0);
  pcp_in.fill(0);
  pcp_out.fill(0);
}

}  // namespace ibs::interbus
