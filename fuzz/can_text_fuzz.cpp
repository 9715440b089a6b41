// can-utils' text forms as `ibs canlust send`, `monitor` and `play` read them (can/can_text.hpp,
// can/candump.hpp; docs/canlust.md, "CAN tools"): arbitrary text as cansend's ID#DATA, as
// candump's filters and as candump log lines with their time.
//
// Asserts:
// - cansend: an accepted frame is a valid 11-bit classic frame, cansend_text() writes it in the
//   form it came in up to case and '.' (a data frame: the text's hex digits, in order) and reads
//   back to the same frame; a refusal names a column 1..length+1 and says what;
// - filters: a refusal names a column 1..length+1, says what and leaves the set as it was; an
//   accepted text adds one filter per ID:MASK term (none for j), no mask carries the error flag,
//   and passes() is the OR (or with j the AND) of the filters' matches for every frame tried;
// - candump log line: an accepted classic line writes back (candump_line) to a line that reads to
//   the same frame; an accepted time reads as microseconds that print back to the same value.
//
// Input: byte 0 selects the part (mod 3: 0 cansend, 1 filters, 2 candump line); the rest is the
// text; for the filters, the last two bytes (when there are) are also the identifier of a frame
// to try.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "ibs/can/can_text.hpp"
#include "ibs/can/candump.hpp"

namespace {

using namespace ibs;
using canlust::CanFrame;

bool column_ok(const can::TextError& e, std::string_view text) {
  return e.column >= 1 && e.column <= text.size() + 1 && !e.what.empty();
}

std::string hex_digits_upper(std::string_view s) {
  std::string out;
  for (const char c : s) {
    if (c == '.') continue;
    out += (c >= 'a' && c <= 'f') ? static_cast<char>(c - 'a' + 'A') : (c == 'r' ? 'R' : c);
  }
  return out;
}

void cansend_part(std::string_view text) {
  const can::FrameText r = can::parse_cansend(text);
  if (!r.frame) {
    IBS_FUZZ_REQUIRE(column_ok(r.error, text), "a refusal without its column: " + r.error.what);
    return;
  }
  const CanFrame& f = *r.frame;
  IBS_FUZZ_REQUIRE(f.valid(), "an accepted frame is not a valid classic frame");
  const std::string back = can::cansend_text(f);
  // A remote frame's R0 is written R; every other accepted text comes back as it was, in capitals.
  if (!f.rtr) IBS_FUZZ_REQUIRE(back == hex_digits_upper(text), "written back as '" + back + "'");
  const can::FrameText again = can::parse_cansend(back);
  IBS_FUZZ_REQUIRE(again.frame && *again.frame == f, "written back, it reads to another frame");
}

void filters_part(std::string_view text, std::uint16_t id_bits) {
  can::CanFilterSet set;
  set.filters.push_back({0x123, 0x7FF, false});
  const can::CanFilterSet before = set;
  const auto e = can::add_candump_filters(text, set);
  if (e) {
    IBS_FUZZ_REQUIRE(column_ok(*e, text), "a refusal without its column: " + e->what);
    IBS_FUZZ_REQUIRE(set.filters.size() == before.filters.size() && set.join == before.join, "a refused text changed the set");
    return;
  }
  std::size_t terms = 0;
  std::size_t start = 0;
  for (;;) {
    const auto comma = text.find(',', start);
    const std::string_view t = text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    if (t != "j" && t != "J") ++terms;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  IBS_FUZZ_REQUIRE(set.filters.size() == before.filters.size() + terms, "not one filter per ID:MASK term");
  for (const can::CanFilter& f : set.filters) IBS_FUZZ_REQUIRE((f.mask & can::kCanErrFlag) == 0, "a mask with the error flag");
  CanFrame frame;
  frame.id = static_cast<std::uint16_t>(id_bits & 0x7FFU);
  frame.rtr = (id_bits & 0x8000U) != 0;
  bool any = false;
  bool all = true;
  for (const can::CanFilter& f : set.filters) {
    any = any || f.matches(frame);
    all = all && f.matches(frame);
  }
  IBS_FUZZ_REQUIRE(set.passes(frame) == (set.join ? all : any), "passes() is not the OR / AND of the filters");
}

void candump_part(std::string_view text) {
  const can::CandumpParsed p = can::read_candump_line(text);
  if (!p.record) {
    IBS_FUZZ_REQUIRE(!p.error.empty(), "a refused line without why");
    return;
  }
  if (const auto us = can::candump_time_us(p.record->time)) {
    IBS_FUZZ_REQUIRE(*us >= 0, "a negative time");
    char b[48];
    std::snprintf(b, sizeof b, "%lld.%06lld", static_cast<long long>(*us / 1000000), static_cast<long long>(*us % 1000000));
    IBS_FUZZ_REQUIRE(can::candump_time_us(b) == us, "the time printed back reads to another value");
  }
  if (!p.record->classic) return;
  IBS_FUZZ_REQUIRE(p.record->frame.valid(), "an accepted frame is not valid");
  const auto at = std::chrono::system_clock::time_point(std::chrono::microseconds(1795431275322679LL));
  const std::string back = can::candump_line(p.record->frame, at, p.record->interface_name);
  const auto again = can::parse_candump_line(back);
  IBS_FUZZ_REQUIRE(again && again->classic && again->frame == p.record->frame, "written back, it reads to another frame");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  switch (data[0] % 3) {
    case 0: cansend_part(text); break;
    case 1: {
      const std::uint16_t id = size >= 3 ? static_cast<std::uint16_t>((data[size - 2] << 8U) | data[size - 1]) : 0;
      filters_part(text, id);
      break;
    }
    default: candump_part(text); break;
  }
  return 0;
}
