#include "ibs/devices/mc6000/layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ibs::devices::mc6000 {

SupiRange allowed_supi(Ibcnf c) {
  // "Possible 'SUPI' settings" column of 3.2.3.
  switch (c) {
    case Ibcnf::none: return {1, 12};
    case Ibcnf::word16: return {7, 12};
    case Ibcnf::q16: return {10, 12};
    case Ibcnf::speed_torque: return {10, 12};
    case Ibcnf::lisim: return {9, 9};
  }
  return {1, 0};
}

Expected<Layout> try_make_layout(int supi, int ibcnf, interbus::BusKind bus) {
  if (supi < 0 || supi > kSupiMax) {
    return Error{ErrorCode::layout_setting_out_of_range,
                 "405-SUPI = " + std::to_string(supi) + " is out of range (0..12, INTERBUS manual 3.2.2)"};
  }
  if (ibcnf < 0 || ibcnf > kIbcnfMax) {
    return Error{
        ErrorCode::layout_setting_out_of_range,
        "406-IBCNF = " + std::to_string(ibcnf) + " is out of range (0..4, INTERBUS manual 3.2.3)"};
  }
  const auto c = static_cast<Ibcnf>(ibcnf);
  if (c == Ibcnf::lisim) {
    return Error{ErrorCode::layout_setting_unsupported,
                 "406-IBCNF = 4 (modified LISIM software) is not supported"};
  }
  const SupiRow& row = kSupiTable[static_cast<std::size_t>(supi)];
  Layout l;
  l.supi = supi;
  l.ibcnf = c;
  l.bus = bus;
  l.id_code = bus == interbus::BusKind::local ? row.id_local : row.id_remote;
  if (supi == 0) {
    // 3.2.2 footnote: reported as configuration 4, the INTERBUS CPU loops without data exchange.
    l.pd_words = row.pd_words;
    l.pcp_words = 0;
    l.exchanges_data = false;
    l.reference_words = 0;
    l.actual_words = 0;
    return l;
  }
  const SupiRange r = allowed_supi(c);
  if (supi < r.first || supi > r.last) {
    return Error{ErrorCode::layout_settings_conflict,
                 "406-IBCNF = " + std::to_string(ibcnf) + " needs 405-SUPI " +
                     std::to_string(r.first) + ".." + std::to_string(r.last) + ", not " +
                     std::to_string(supi) + " (INTERBUS manual 3.2.3)"};
  }
  l.pd_words = row.pd_words;
  l.pcp_words = row.pcp_words;
  switch (c) {
    case Ibcnf::none: l.reference_words = 0; l.actual_words = 0; break;
    case Ibcnf::word16: l.reference_words = 1; l.actual_words = 1; break;
    case Ibcnf::q16: l.reference_words = 2; l.actual_words = 2; break;
    case Ibcnf::speed_torque: l.reference_words = 2; l.actual_words = 2; break;
    case Ibcnf::lisim: break;
  }
  return l;
}

#if IBS_EXCEPTIONS
Layout make_layout(int supi, int ibcnf, interbus::BusKind bus) {
  Expected<Layout> l = try_make_layout(supi, ibcnf, bus);
  detail::require<LayoutError>(l.error());
  return std::move(l).value();
}
#endif

std::int32_t to_q16(double value) {
  // Rounded half away from zero, as std::round, without the library call (every device sample
  // encodes its actual value): inside the clamp c - trunc(c) is exact.
  constexpr double kMax = std::numeric_limits<std::int32_t>::max();
  constexpr double kMin = std::numeric_limits<std::int32_t>::min();
  const double c = std::clamp(value * 65536.0, kMin, kMax);
  auto i = static_cast<std::int64_t>(c);
  const double frac = c - static_cast<double>(i);
  if (frac >= 0.5) ++i;
  if (frac <= -0.5) --i;
  return static_cast<std::int32_t>(std::clamp<std::int64_t>(i, std::numeric_limits<std::int32_t>::min(),
                                                            std::numeric_limits<std::int32_t>::max()));
}

double from_q16(std::int32_t raw) { return static_cast<double>(raw) / 65536.0; }

namespace {
Word to_word16(double value) {
  const double r = std::clamp(std::round(value), -32768.0, 32767.0);
  return static_cast<Word>(static_cast<std::int16_t>(r));
}
double from_word16(Word w) { return static_cast<double>(static_cast<std::int16_t>(w)); }
void put_q16(double value, std::span<Word> words) {
  const auto raw = static_cast<std::uint32_t>(to_q16(value));
  words[0] = high_word(raw);
  words[1] = low_word(raw);
}
double get_q16(std::span<const Word> words) {
  return from_q16(static_cast<std::int32_t>(make_dword(words[0], words[1])));
}
}  // namespace

void encode_reference(const Layout& l, double value, std::span<Word> words) {
  for (Word& w : words) w = 0;
  switch (l.ibcnf) {
    case Ibcnf::word16:
      if (!words.empty()) words[0] = to_word16(value);
      break;
    case Ibcnf::q16:
    case Ibcnf::speed_torque:
      if (words.size() >= 2) put_q16(value, words);
      break;
    case Ibcnf::none:
    case Ibcnf::lisim: break;
  }
}

double decode_reference(const Layout& l, std::span<const Word> words) {
  switch (l.ibcnf) {
    case Ibcnf::word16: return words.empty() ? 0.0 : from_word16(words[0]);
    case Ibcnf::q16:
    case Ibcnf::speed_torque: return words.size() >= 2 ? get_q16(words) : 0.0;
    case Ibcnf::none:
    case Ibcnf::lisim: break;
  }
  return 0.0;
}

void encode_actual(const Layout& l, const Actual& a, std::span<Word> words) {
  // Written word by word, without clearing first: every device sample goes through here.
  Word first = 0;
  Word second = 0;
  switch (l.ibcnf) {
    case Ibcnf::word16: first = to_word16(a.value); break;
    case Ibcnf::q16:
      if (words.size() >= 2) {
        const auto raw = static_cast<std::uint32_t>(to_q16(a.value));
        first = high_word(raw);
        second = low_word(raw);
      }
      break;
    case Ibcnf::speed_torque:
      first = to_word16(a.value);
      second = to_word16(a.torque);
      break;
    case Ibcnf::none:
    case Ibcnf::lisim: break;
  }
  const std::size_t n = words.size();
  if (n > 0) words[0] = first;
  if (n > 1) words[1] = second;
  // (Word by word: a loop here becomes a library memset call for what is at most one word.)
  if (n > 2) words[2] = 0;
  for (std::size_t i = 3; i < n; ++i) words[i] = 0;
}

Actual decode_actual(const Layout& l, std::span<const Word> words) {
  Actual a;
  switch (l.ibcnf) {
    case Ibcnf::word16: a.value = words.empty() ? 0.0 : from_word16(words[0]); break;
    case Ibcnf::q16: a.value = words.size() >= 2 ? get_q16(words) : 0.0; break;
    case Ibcnf::speed_torque:
      if (words.size() >= 2) {
        a.value = from_word16(words[0]);
        a.torque = from_word16(words[1]);
      }
      break;
    case Ibcnf::none:
    case Ibcnf::lisim: break;
  }
  return a;
}

}  // namespace ibs::devices::mc6000
