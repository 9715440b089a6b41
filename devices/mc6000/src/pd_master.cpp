#include "ibs/devices/mc6000/pd_master.hpp"

#include <algorithm>

namespace ibs::devices {

Mc6000PdMaster::Mc6000PdMaster(const mc6000::Layout& layout,
                               const drivecom::SequencerConfig& config)
    : layout_(layout), sequencer_(config) {}

void Mc6000PdMaster::initial(std::span<Word> m2s) const {
  std::fill(m2s.begin(), m2s.end(), Word{0});
}

void Mc6000PdMaster::cycle(std::span<const Word> s2m, std::span<Word> m2s, Time now) {
  if (m2s.empty() || s2m.empty()) return;
  const auto actual_words = static_cast<std::size_t>(layout_.actual_words);
  actual_ = mc6000::decode_actual(layout_, s2m.subspan(1, actual_words));
  m2s[0] = sequencer_.step(s2m[0], now);
  const auto ref_words = static_cast<std::size_t>(layout_.reference_words);
  if (reference_ != encoded_reference_) {
    mc6000::encode_reference(layout_, reference_, std::span<Word>(reference_words_.data(), ref_words));
    encoded_reference_ = reference_;
  }
  // Control word, reference, and 0 in any word the layout leaves unused (SUPI 12 with IBCNF 2),
  // word by word: a loop here became a call of memset and memcpy for one or two words.
  switch (m2s.size()) {
    case 4: m2s[3] = reference_words_[2]; [[fallthrough]];
    case 3: m2s[2] = reference_words_[1]; [[fallthrough]];
    case 2: m2s[1] = reference_words_[0]; [[fallthrough]];
    default: break;
  }
  for (std::size_t w = reference_words_.size() + 1; w < m2s.size(); ++w) m2s[w] = 0;  // never: 4 words at most
}

}  // namespace ibs::devices
