// The VF1000's process data as the master handles it (INTERBUS manual 5.2): the DRIVECOM sequencer with
// the ramp and direction bits, the frequency reference and actual in 0.05 Hz words.
#pragma once

#include <span>

#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/drivecom/sequencer.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"

namespace ibs::devices {

class Vf1000PdMaster {
 public:
  explicit Vf1000PdMaster(const drivecom::SequencerConfig& config = drivecom::SequencerConfig::defaults());

  drivecom::Sequencer& sequencer() { return sequencer_; }
  [[nodiscard]] const drivecom::Sequencer& sequencer() const { return sequencer_; }
  // Signed: positive runs clockwise (STR), negative counter-clockwise (STL), 0 sets neither.
  void set_frequency_hz(double hz);
  [[nodiscard]] double frequency_setpoint_hz() const { return setpoint_; }

  // One master cycle over words 1 and 2; `comm` is the parameter channel's word 3 to send.
  void cycle(std::span<const Word> s2m, std::span<Word> m2s, Time now, Word comm = 0);
  void initial(std::span<Word> m2s) const;

  [[nodiscard]] double actual_hz() const { return actual_; }

 private:
  drivecom::Sequencer sequencer_;
  double setpoint_ = 0.0;
  double actual_ = 0.0;
};

}  // namespace ibs::devices
