// The MC6000's process data as the master handles it (seed 001, 5.3): the DRIVECOM sequencer
// plus the reference and actual in engineering units in the layout's words.
#pragma once

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
  void set_reference_rpm(double rpm) { reference_ = rpm; }
  [[nodiscard]] double reference_rpm() const { return reference_; }

  // One master cycle: reads the status-side words, writes the control-side words.
  void cycle(std::span<const Word> s2m, std::span<Word> m2s, Time now);
  // The words before the first cycle: BLOCK POWER, reference 0.
  void initial(std::span<Word> m2s) const;

  [[nodiscard]] double actual_rpm() const { return actual_.value; }
  [[nodiscard]] const mc6000::Actual& actual() const { return actual_; }
  [[nodiscard]] const mc6000::Layout& layout() const { return layout_; }

 private:
  mc6000::Layout layout_;
  drivecom::Sequencer sequencer_;
  double reference_ = 0.0;
  // The reference as bus words, encoded again only when it changes.
  // Words 2..4 of the slot: the encoded reference, then 0 in any word the layout leaves unused.
  std::array<Word, 3> reference_words_{};
  double encoded_reference_ = 0.0;
  mc6000::Actual actual_{};
};

}  // namespace ibs::devices
