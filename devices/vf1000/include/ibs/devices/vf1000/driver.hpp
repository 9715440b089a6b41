// The VF1000's master driver: the DRIVECOM sequencer with the ramp and direction bits, the
// frequency reference in 0.05 Hz, and parameter access through the communication word's client
// (vf1000_channel/client.hpp, INTERBUS manual 4.1).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "ibs/devices/driver.hpp"
#include "ibs/devices/vf1000/pd_master.hpp"
#include "ibs/vf1000_channel/client.hpp"

namespace ibs::devices {

class Vf1000Driver final : public DeviceDriver, private ParameterAccess {
 public:
  explicit Vf1000Driver(const vf1000_channel::ClientConfig& channel = {},
                        const drivecom::SequencerConfig& config = drivecom::SequencerConfig::defaults());
  void cycle(const DriverIo& io, Time now) override;
  void initial(const DriverIo& io) override;
  void restart(Time now) override;
  drivecom::Sequencer& sequencer() override { return master_.sequencer(); }
  ParameterAccess& parameters() override { return *this; }
  void set_reference(double hz) override { master_.set_frequency_hz(hz); }
  [[nodiscard]] double reference() const override { return master_.frequency_setpoint_hz(); }
  [[nodiscard]] double actual() const override { return master_.actual_hz(); }
  [[nodiscard]] std::string_view unit() const override { return "Hz"; }
  [[nodiscard]] const vf1000_channel::Client& channel() const { return client_; }

 private:
  ParamId submit(ParamOp op, std::uint16_t number, std::int64_t value) override;
  [[nodiscard]] ParamStatus status(ParamId id) const override;
  [[nodiscard]] std::string describe(ParamId id) const override;
  [[nodiscard]] bool closing() const override {
    return client_.state() == vf1000_channel::ClientState::closing;
  }

  Vf1000PdMaster master_;
  vf1000_channel::Client client_;
  vf1000_channel::SubmitError last_refusal_ = vf1000_channel::SubmitError::none;
};

}  // namespace ibs::devices
