#include "ibs/devices/mc6000/pd_master.hpp"

#include <algorithm>

namespace ibs::devices {

Mc6000PdMaster::Mc6000PdMaster(const mc6000::Layout& layout,
                               const drivecom::SequencerConfig& config)
    : layout_(layout),
      sequencer_(config),
      actual_words_(std::min(static_cast<std::size_t>(std::max(layout.actual_words, 0)), std::size_t{2})) {
  encode_reference_words();
}

void Mc6000PdMaster::set_reference_rpm(double rpm) {
  reference_ = rpm;
  encode_reference_words();
}

void Mc6000PdMaster::initial(std::span<Word> m2s) const {
  std::fill(m2s.begin(), m2s.end(), Word{0});
}

void Mc6000PdMaster::cycle_general(std::span<const Word> s2m, std::span<Word> m2s, Time now) {
  if (m2s.empty() || s2m.empty()) return;
  // The actual words decoded only when they changed (same_actual).
  if (s2m.size() > actual_words_) {
    if (!same_actual(s2m)) decode_actual_words(s2m.subspan(1, actual_words_));
  } else {
    decode_actual_words(s2m.subspan(1));
  }
  m2s[0] = sequencer_.step(s2m[0], now);
  put_reference(m2s);
}

void Mc6000PdMaster::decode_actual_words(std::span<const Word> words) {
  actual_ = mc6000::decode_actual(layout_, words);
  decoded_ = words.size() == actual_words_;
  std::copy_n(words.begin(), std::min(words.size(), actual_raw_.size()), actual_raw_.begin());
}

void Mc6000PdMaster::encode_reference_words() {
  const auto ref_words = static_cast<std::size_t>(layout_.reference_words);
  mc6000::encode_reference(layout_, reference_, std::span<Word>(reference_words_.data(), ref_words));
}

}  // namespace ibs::devices
