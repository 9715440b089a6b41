// The MC6000's process data as the master handles it (INTERBUS manual 5.3): the DRIVECOM sequencer
// plus the reference and actual in engineering units in the layout's words.
#pragma once

#include <algorithm>
#include <array>
#include <span>

#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/drivecom/sequencer.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"

namespace ibs::devices {

class Mc6000PdMaster {
 public:
  explicit Mc6000PdMaster(const mc6000::Layout& layout,
                          const drivecom::SequencerConfig& config = drivecom::SequencerConfig::defaults());

  drivecom::Sequencer& sequencer() { return sequencer_; }
  [[nodiscard]] const drivecom::Sequencer& sequencer() const { return sequencer_; }
  // Encodes the reference into its bus words at once (a pure function of the layout and the
  // value), so that the cycle writes them without looking at the value.
  void set_reference_rpm(double rpm);
  [[nodiscard]] double reference_rpm() const { return reference_; }

  // One master cycle: reads the status-side words, writes the control-side words. Inline: it is
  // every MC6000 driver's cycle on the full bus (docs/performance.md, "master cycle"). The common
  // case is a leaf: the actual words those decoded last (decode_actual is a function of the
  // layout and the words alone), the sequencer holding its target
  // (Sequencer::step_holding): then the words written are those cycle_general writes, without
  // its calls. Anything else, cycle_general.
  void cycle(std::span<const Word> s2m, std::span<Word> m2s, Time now) {
    if (!cycle_holding(s2m, m2s)) cycle_general(s2m, m2s, now);
  }
  // cycle()'s common case alone: true when it applies, with cycle()'s words and effects; false
  // otherwise, and nothing changed (the caller then calls cycle_general). Reads no time.
  bool cycle_holding(std::span<const Word> s2m, std::span<Word> m2s) {
    Word control = 0;
    if (s2m.size() > actual_words_ && !m2s.empty() && m2s.size() <= reference_words_.size() + 1 &&
        same_actual(s2m) && sequencer_.step_holding(s2m[0], control)) {
      m2s[0] = control;
      put_reference(m2s);
      return true;
    }
    return false;
  }
  // cycle() without its shortcut, every case (out of line: cycle's common case calls nothing).
  // The same words and state as cycle(); Mc6000PdMasterShortcut.* compares the two at random.
  void cycle_general(std::span<const Word> s2m, std::span<Word> m2s, Time now);
  // The words before the first cycle: BLOCK POWER, reference 0.
  void initial(std::span<Word> m2s) const;

  [[nodiscard]] double actual_rpm() const { return actual_.value; }
  [[nodiscard]] const mc6000::Actual& actual() const { return actual_; }
  [[nodiscard]] const mc6000::Layout& layout() const { return layout_; }

 private:
  // The actual words (1..actual_words_ of s2m, which has more than that) are those actual_ was
  // decoded from.
  [[nodiscard]] bool same_actual(std::span<const Word> s2m) const {
    bool same = decoded_;
    switch (actual_words_) {
      case 2: same = same && s2m[2] == actual_raw_[1]; [[fallthrough]];
      case 1: same = same && s2m[1] == actual_raw_[0]; break;
      default: break;
    }
    return same;
  }
  // Reference and 0 in any word the layout leaves unused (SUPI 12 with IBCNF 2), word by word: a
  // loop here became a call of memset and memcpy for one or two words.
  void put_reference(std::span<Word> m2s) const {
    switch (m2s.size()) {
      case 4: m2s[3] = reference_words_[2]; [[fallthrough]];
      case 3: m2s[2] = reference_words_[1]; [[fallthrough]];
      case 2: m2s[1] = reference_words_[0]; [[fallthrough]];
      default: break;
    }
    for (std::size_t w = reference_words_.size() + 1; w < m2s.size(); ++w) m2s[w] = 0;  // never: 4 words at most
  }
  void decode_actual_words(std::span<const Word> words);
  void encode_reference_words();

  mc6000::Layout layout_;
  drivecom::Sequencer sequencer_;
  double reference_ = 0.0;
  // The reference as bus words, encoded by set_reference_rpm (and the constructor).
  // Words 2..4 of the slot: the encoded reference, then 0 in any word the layout leaves unused.
  std::array<Word, 3> reference_words_{};
  mc6000::Actual actual_{};
  // The layout's actual words (at most 2, 3.2.3) and the words actual_ was decoded from;
  // decoded_ false before the first decode and after one from fewer words than the layout's.
  std::size_t actual_words_ = 0;
  std::array<Word, 2> actual_raw_{};
  bool decoded_ = false;
};

}  // namespace ibs::devices
