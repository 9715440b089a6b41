// An emulated PowerTec DFS-1 controller on an RS-485 line: the protocol's controller side
// (ibs::dfs1::ControllerReceiver) in front of a model of the drive: parameters, speed commands
// (82 set, 83 execute, 84 both), status 81 with ST2/ST1, analog and digital I/O (87..8C),
// operational mode (8D/8E: bit 0, the E-stop input, can never be remote) and application mode
// (8F), and a first-order speed plant stepped with time passed in. docs/dfs1.md, "Emulator".
//
// Everything after construction allocates nothing and throws nothing.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/devices/dfs1/events.hpp"
#include "ibs/devices/dfs1/parameters.hpp"
#include "ibs/dfs1/controller.hpp"
#include "ibs/dfs1/frame.hpp"
#include "ibs/base/time.hpp"

namespace ibs::devices::dfs1 {

// ST2, bit 7 down (notes, "Status (81)").
inline constexpr std::uint8_t kSt2Remote = 0x80;  // 1 = remote (some function of parameter 3)
inline constexpr std::uint8_t kSt2Slave = 0x40;   // 1 = slave (application mode 1)
inline constexpr std::uint8_t kSt2AtSpeed = 0x20;
inline constexpr std::uint8_t kSt2Forward = 0x10;
inline constexpr std::uint8_t kSt2Fault = 0x08;
inline constexpr std::uint8_t kSt2Enabled = 0x04;
inline constexpr std::uint8_t kSt2MicroFault = 0x02;
inline constexpr std::uint8_t kSt2ZeroSpeed = 0x01;
// ST1, bit 7 down (the notes call the order inferred).
inline constexpr std::uint8_t kSt1BusNotCharged = 0x80;
inline constexpr std::uint8_t kSt1Ioc = 0x40;
inline constexpr std::uint8_t kSt1Stall = 0x20;
inline constexpr std::uint8_t kSt1I2t = 0x10;
inline constexpr std::uint8_t kSt1HeatsinkOvertemp = 0x08;
inline constexpr std::uint8_t kSt1Commutation = 0x04;
inline constexpr std::uint8_t kSt1Overvolt = 0x02;
inline constexpr std::uint8_t kSt1Undervolt = 0x01;

// I/O channels (the parameter list names analog inputs #1-#2, analog outputs #1-#2, digital
// inputs #1-#7, digital outputs #1-#3 and a digital out #4; value ranges invented, D7).
inline constexpr std::uint8_t kAnalogInputs = 2;
inline constexpr std::uint8_t kAnalogOutputs = 2;
inline constexpr std::uint8_t kDigitalInputs = 7;
inline constexpr std::uint8_t kDigitalOutputs = 4;
inline constexpr std::uint32_t kAnalogMax = 1023;
inline constexpr std::uint8_t kEstopInput = 1;  // digital input 1 (notes, 8D)

// The first-order speed plant: the motor follows its target with time constant tau.
class SpeedPlant {
 public:
  explicit SpeedPlant(Duration tau) : tau_(tau) {}
  void step(Duration dt, double target_rpm);
  double speed() const { return speed_; }

 private:
  Duration tau_;
  double speed_ = 0.0;
};

struct ControllerConfig {
  std::uint8_t uid = 1;
  Duration plant_time_constant = 500ms;  // invented
};

class Controller final : public ::ibs::dfs1::RequestHandler {
 public:
  // Throws std::invalid_argument for UID 0 ("dfs1 controller: UID 0 is the global address ...").
  explicit Controller(const ControllerConfig& config);

  // The line side.
  void receive(std::uint8_t byte, Time now);
  void receive(std::span<const std::uint8_t> bytes, Time now);
  std::span<const std::uint8_t> pending(Time now) const { return receiver_.pending(now); }
  void consume(std::size_t n) { receiver_.consume(n); }
  std::optional<Time> next_deadline() const { return receiver_.next_deadline(); }
  // Advances the plant to `now` (also done by every request).
  void step(Time now);

  // The hardware side (terminal strip), for tests and scenarios.
  // 1..7; 1 is the E-stop: opening it stops the motor and drops the run command (D19).
  void set_digital_input(std::uint8_t channel, bool closed);
  void set_analog_input(std::uint8_t channel, std::uint32_t value);
  // Latches exactly these ST1 bits (a fault without a lasting cause, D16); any bit set stops the
  // motor and drops the run command.
  void set_faults(std::uint8_t st1);
  // A plant or fault event at `now` (events.hpp; decisions D15-D20): the plant is stepped to `now`
  // first. Returns what a host reads right after it.
  EventReport apply(const Event& event, Time now);
  // A parameter set at the keypad: the same checks as a write (82, 83), nullopt when accepted.
  std::optional<::ibs::dfs1::ErrorCode> set_parameter(std::uint8_t number, std::uint32_t value);

  // Observation.
  std::uint8_t uid() const { return receiver_.uid(); }
  std::uint32_t parameter(std::uint8_t number) const;
  std::int32_t preset_speed() const { return preset_speed_; }        // set by 82
  std::int32_t commanded_speed() const { return commanded_speed_; }  // executed by 83/84
  double actual_speed() const { return plant_.speed(); }
  std::uint8_t st2() const;
  std::uint8_t st1() const;
  std::uint32_t load_percent() const;
  // A fault latched (ST1 bits or the uP fault; not the bus-not-charged of mains off, D17).
  bool fault_latched() const { return latched_st1_ != 0 || latched_micro_; }
  // The cause of a fault still present (its duration not over) at the controller's time.
  bool cause_present(FaultCause cause) const;
  bool mains_on() const { return mains_on_; }
  std::uint32_t load() const { return load_; }  // the load event's %, D18
  std::uint16_t operational_mode() const { return operational_mode_; }
  std::uint8_t application_mode() const { return application_mode_; }
  bool digital_input(std::uint8_t channel) const;  // effective: terminal or remote (8D)
  std::uint32_t analog_output(std::uint8_t channel) const { return analog_out_[channel - 1U]; }
  bool digital_output(std::uint8_t channel) const { return digital_out_[channel - 1U]; }
  bool enabled() const;
  const ::ibs::dfs1::ControllerReceiver::Counters& counters() const { return receiver_.counters(); }
  Duration turnaround() const { return receiver_.turnaround(); }

  ::ibs::dfs1::Reply handle(const ::ibs::dfs1::Frame& request, bool global, Time now) override;

 private:
  std::size_t index(std::uint8_t number) const;
  bool remote(std::uint32_t functions) const;
  double target_speed(Time now) const;
  bool faulted() const { return st1() != 0 || latched_micro_; }
  bool estop_closed() const { return terminal_inputs_[kEstopInput - 1U]; }
  // D16: a latched fault is reset while the E-stop is open and no cause is present.
  void settle();
  void power_on_reset(Time now);
  ::ibs::dfs1::Reply speed_command(::ibs::dfs1::Command c, std::int32_t rpm, Time now);
  ::ibs::dfs1::Reply write_parameter(std::uint8_t number, std::uint32_t value);
  ::ibs::dfs1::Reply status_reply() const;

  ::ibs::dfs1::ControllerReceiver receiver_;
  SpeedPlant plant_;
  std::array<std::uint32_t, kParameters.size()> values_{};
  Time now_{};
  std::int32_t preset_speed_ = 0;
  std::int32_t commanded_speed_ = 0;
  Time contactor_closes_at_{};  // when a start from rest may drive the motor (parameter 62)
  bool running_ = false;
  std::uint8_t latched_st1_ = 0;
  bool latched_micro_ = false;
  std::array<Time, kFaultCauses> cause_until_{};  // a cause is present while now_ < its time
  bool mains_on_ = true;
  std::uint32_t load_ = 0;
  std::uint16_t operational_mode_ = 0;
  std::uint8_t application_mode_ = 0;
  std::uint32_t application_value_ = 0;
  std::array<bool, kDigitalInputs> terminal_inputs_{};
  std::array<std::uint32_t, kAnalogInputs> analog_in_{};
  std::array<std::uint32_t, kAnalogOutputs> analog_out_{};
  std::array<bool, kDigitalOutputs> digital_out_{};
};

}  // namespace ibs::devices::dfs1
