#include "ibs/devices/vf1000/pd_master.hpp"

#include <algorithm>

namespace ibs::devices {

Vf1000PdMaster::Vf1000PdMaster(const drivecom::SequencerConfig& config) : sequencer_(config) {
  sequencer_.set_application_bits(vf1000::kRampRun);
}

void Vf1000PdMaster::set_frequency_hz(double hz) {
  setpoint_ = hz;
  vf1000::ControlBits b = vf1000::decode_control_bits(vf1000::kRampRun);
  b.str = hz > 0;
  b.stl = hz < 0;
  sequencer_.set_application_bits(vf1000::encode_control_bits(b));
}

void Vf1000PdMaster::initial(std::span<Word> m2s) const {
  std::fill(m2s.begin(), m2s.end(), Word{0});
}

void Vf1000PdMaster::cycle(std::span<const Word> s2m, std::span<Word> m2s, Time now, Word comm) {
  actual_ = vf1000::actual_hz(s2m[1]);
  m2s[0] = sequencer_.step(s2m[0], now);
  m2s[1] = vf1000::reference_word(setpoint_);
  m2s[2] = comm;
}

}  // namespace ibs::devices
