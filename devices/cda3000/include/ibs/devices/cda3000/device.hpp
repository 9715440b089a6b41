// The emulated CDA3000 inverter with its CM-CAN1 module (CANLust manual): the CANLust node of the core
// (system states, logon, stored command, cyclic status, watchdog, parameter channel), the DRIVECOM
// device state machine of drivecom/ (5.4.2: "the DRIVECOM state machine", the same as the
// INTERBUS drives'), the parameters of parameters.hpp with their flash copy (150-SAVE, mains
// reset), and a first-order speed plant.
//
//   Cda3000 drive({.connector_address = 1});
//   drive.power_on(now);
//   drive.receive(frame, now);    // every frame from the bus
//   drive.step(now);              // cyclic telegrams, watchdog, delayed replies, the plant
//   while (auto f = drive.take_frame()) bus.send(*f);  // or take_frame(CanFrame&)
//   drive.next_deadline();        // when step() next has something to do
//
// Time is passed in; nothing inside reads a clock or starts a thread. receive, step, take_frame
// and next_deadline allocate nothing and throw nothing; power_on (re)builds the node from the
// parameters (address, layout), which allocates its outbox - a mains reset is not the frame path.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "ibs/canlust/node.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/devices/cda3000/parameters.hpp"
#include "ibs/devices/cda3000/plant.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/base/time.hpp"

namespace ibs::devices::cda3000 {

struct DeviceConfig {
  // 2.1: the address coded on the connector, 0..7; used when 571-CLADR is 0.
  std::uint8_t connector_address = 0;
  canlust::IdentifierMap ids{};
  PlantConfig plant{};
  // 4.3.3: "data backup takes a few hundred milliseconds": the reply to 150-SAVE = 1 comes then.
  Duration save_time = 300ms;
  // p. 13: the reply to 04-PROG = 1 comes "only when the command is complete" (time invented).
  Duration prog_time = 500ms;
  // 4.x: the reply to 80-SLOAD = -2 comes once the whole data set is checked and, when valid, in
  // the EEPROM (time invented, as the MC6000's 200 ms of the LUSTBUS manual 11.4; D39).
  Duration download_check_time = 200ms;
  // The reaction to the bus watchdog (574-CAWDG) is no setting here but the drive's parameter
  // 525-ROP2 (6.1: programmable per error; the watchdog reports E-OP2, D15): put it in `saved`.
  // Flash values other than the factory settings (a commissioned drive), e.g. {571, 1}; checked
  // by the constructor like a write.
  std::vector<std::pair<std::uint16_t, std::uint32_t>> saved{};
  std::size_t outbox_capacity = 32;
};

// The parameters of a drive commissioned for the bus as 7.1.2 does it: 151-ASTPR / 152-ASTER
// BUS_1 (which selects 260-CLSEL, 280-RSSL1 and 180-FISA0 = OPTN2), 571-CLADR and 492-CACNF.
std::vector<std::pair<std::uint16_t, std::uint32_t>> commissioned_for_bus(std::uint8_t address,
                                                                          std::uint8_t cacnf = 2);

struct DeviceCounters {
  std::uint32_t controls_executed = 0;  // control telegrams executed (at once or at the Start)
  std::uint32_t controls_ignored = 0;   // 260-CLSEL is not OPTN2: the bus is not the control location
  std::uint32_t watchdog_trips = 0;
  std::uint32_t writes = 0;             // accepted value and string writes
  std::uint32_t device_faults = 0;      // faults injected with inject_fault
};

// The terminals of X2 that CANLust manual names (2.3, 3.1, 7.1.2 step 6): ENPO (X2-8) the hardware
// enable of the power stage, ISD00 (X2-9) a digital input whose function the seed does not give.
enum class Input : std::uint8_t { enpo, isd00 };
std::optional<Input> find_input(std::string_view name);  // "ENPO", "ISD00" (any case)
std::string_view to_string(Input i);

// The warnings of 6.3 ("parameterizable warnings on the CAN") whose text the seed keeps: the bit
// (mask) in 577-CAWRN and 576-CAWMK, the name the bench raises it by, the seed's text (CAN-E17).
struct WarningInfo {
  std::uint16_t mask;
  std::string_view name;
  std::string_view text;
};
inline constexpr std::uint16_t kWarningI2t = 0x0004;
inline constexpr std::uint16_t kWarningMotorTemperature = 0x0008;
inline constexpr std::uint16_t kWarningHeatSink = 0x0010;
inline constexpr std::array<WarningInfo, 3> kWarnings{{
    {kWarningI2t, "W-I2T", "I2t integrator of the device active"},
    {kWarningMotorTemperature, "W-TM", "motor temperature above 502-WLTM"},
    {kWarningHeatSink, "W-TH", "heat sink temperature above its warning level"},
}};
// By name ("W-TM", "TM", any case) or mask ("0008H", "0x0008").
const WarningInfo* find_warning(std::string_view text);

// Load torque limits (D35): +-300 % of the motor's rated torque.
inline constexpr double kMaxLoadPercent = 300.0;

class Cda3000 final : public canlust::DriveProcess, public canlust::ParameterAccess {
 public:
  // Throws std::invalid_argument for a connector address above 7 or a saved value the table
  // refuses (naming the parameter, the value and the limit).
  explicit Cda3000(const DeviceConfig& config);

  // Mains on (or a mains reset): flash -> settings, the node rebuilt with 571-CLADR (or the
  // connector's address), 492-CACNF, 574-CAWDG and 575-CASCY; DRIVECOM from NOT READY.
  void power_on(Time now);
  void power_off();
  void receive(const canlust::CanFrame& f, Time now);
  void step(Time now);
  // The next frame into `out`; false when there is none (mains off included). Inline (issue
  // 26: asked until it has nothing, twice a parameter read at least).
  bool take_frame(canlust::CanFrame& out) { return node_ && node_->take_frame(out); }
  std::optional<canlust::CanFrame> take_frame() {
    if (!node_) return std::nullopt;
    return node_->take_frame();
  }
  [[nodiscard]] Time next_deadline() const;

  // ---- observation --------------------------------------------------------------------------
  [[nodiscard]] bool powered() const { return node_.has_value(); }
  [[nodiscard]] canlust::Address address() const { return address_; }
  [[nodiscard]] const canlust::ProcessLayout& layout() const { return layout_; }
  // 489-CLBDR in bit/s as the node runs (from the last power-on).
  [[nodiscard]] std::uint32_t bitrate() const { return bitrate_; }
  [[nodiscard]] canlust::SystemState system_state() const;

  // ---- plant and fault events (issue 24; D34-D36) ---------------------------------------------
  // A device fault with its cause, an error number of table 5.9 (6.2): the drive takes its
  // default error response (6.1: the power stage is disabled, DRIVECOM FAULT), sends the error
  // telegram (number, location 0, reaction) and keeps it in 95-ERR1. false: mains off or a number
  // the table lacks (nothing changes).
  // The response is the error's parameter (520-ROTI .. 525-ROP2, 6.1, CAN-E16): WRN shows the
  // warning bit until acknowledged, STOP / QSTOP stop the motor and then FAULT, PWOFF FAULT at once.
  bool inject_fault(std::uint8_t number, Time now);
  // A warning of 6.3 (a mask of kWarnings) present until acknowledged like an error (6.5: the
  // error reset bit, System Start -> Stop) or a mains reset (CAN-E17). false: mains off.
  bool raise_warning(std::uint16_t mask, Time now);
  // 577-CAWRN: the warnings present, whether the mask reports them or not; 0004H (I2t) also
  // while the power stage drives a load above 100 % of the rated torque.
  [[nodiscard]] std::uint16_t warnings() const;
  // The load torque in % of the motor's rated torque (D35): the motor slips below the output
  // frequency, 3 Hz at 100 %; kept over mains resets (it is mechanical).
  void set_load(double percent, Time now);
  [[nodiscard]] double load() const { return load_percent_; }
  // A terminal's level; kept over mains resets (it is wiring).
  void set_input(Input i, bool high, Time now);
  [[nodiscard]] bool input(Input i) const { return i == Input::enpo ? enpo_ : isd00_; }
  [[nodiscard]] canlust::ErrStruc last_error() const { return last_error_; }
  [[nodiscard]] drivecom::State state() const { return sm_.state(); }
  // When the DRIVECOM state last changed.
  [[nodiscard]] Time state_since() const { return state_since_; }
  [[nodiscard]] ibs::Word status_word() const;
  [[nodiscard]] double actual_hz(Time now) const { return plant_.hz(now); }
  // The reference the drive follows (0 unless 280-RSSL1 = OPTN2), limited to +-fmax.
  [[nodiscard]] double reference_hz() const;
  // Status bit 7 (DRIVECOM and EasyDrive): the watchdog's or an error's WRN response, or a warning
  // of 577-CAWRN that 576-CAWMK reports on the CAN.
  [[nodiscard]] bool warning() const;
  // 80-SLOAD = -1 opened a data set download that has not ended (the power stage is blocked).
  [[nodiscard]] bool downloading() const { return download_open_; }
  [[nodiscard]] std::optional<canlust::ErrorReaction> fault() const { return fault_; }
  // A parameter's setting (the wire image) / text; nullopt for numbers the table lacks.
  [[nodiscard]] std::optional<std::uint32_t> value(std::uint16_t number) const;
  // Its copy in flash (what 150-SAVE stored, what a mains reset loads); nullopt also for a
  // parameter the table keeps in RAM (04-PROG, 80-SLOAD, 150-SAVE, the read-only values).
  [[nodiscard]] std::optional<std::uint32_t> saved_value(std::uint16_t number) const;
  [[nodiscard]] std::string_view text(std::uint16_t number) const;
  [[nodiscard]] std::string_view saved_text(std::uint16_t number) const;
  [[nodiscard]] const canlust::Node* node() const { return node_ ? &*node_ : nullptr; }
  [[nodiscard]] const DeviceCounters& counters() const { return counters_; }
  [[nodiscard]] const DeviceConfig& config() const { return config_; }

  // ---- canlust::DriveProcess -------------------------------------------------------------------
  void execute(const canlust::ControlTelegram& t, Time now) override;
  canlust::StatusTelegram status(Time now) override;
  std::optional<canlust::ErrorTelegram> watchdog_expired(const canlust::WatchdogEvent& e) override;
  void system_state_changed(canlust::SystemState s, Time now) override;

  // ---- canlust::ParameterAccess ----------------------------------------------------------------
  canlust::ValueResult read(std::uint16_t number, std::uint8_t index, Time now) override;
  canlust::AccessResult write(std::uint16_t number, std::uint8_t index, std::uint32_t value, Time now) override;
  canlust::ValueResult describe(std::uint16_t number, std::uint8_t item, Time now) override;
  canlust::StringResult read_string(std::uint16_t number, std::span<char> out, Time now) override;
  canlust::AccessResult begin_string_write(std::uint16_t number, Time now) override;
  canlust::AccessResult write_string(std::uint16_t number, std::string_view text, Time now) override;

 private:
  using Values = std::array<std::uint32_t, kParameters.size()>;
  [[nodiscard]] std::uint32_t get(std::uint16_t number) const;
  // value() of the table's row i (not a STRING). Inlined into read() and value() (issue 26).
  [[gnu::always_inline]] [[nodiscard]] inline std::uint32_t value_at(std::size_t i) const;
  void set(std::uint16_t number, std::uint32_t value);
  void apply_live(std::uint16_t number, Time now);
  void load_preset(std::uint32_t data_set, Time now);
  void advance(Time now);
  void sample(Time now);
  void drive_plant(Time now);
  [[nodiscard]] ibs::Word easydrive_control(bool stopped) const;
  [[nodiscard]] ibs::Word easydrive_status(Time now) const;
  [[nodiscard]] bool awaiting_stop() const;
  [[nodiscard]] bool bus_controls() const;
  [[nodiscard]] canlust::ErrorReaction response(std::uint8_t error) const;
  canlust::AccessResult download(std::uint32_t code, Time now);
  void acknowledge_warnings();

  DeviceConfig config_;
  Values current_{};
  Values saved_{};
  canlust::FixedString name_{};
  canlust::FixedString name_saved_{};
  std::optional<canlust::Node> node_;
  canlust::Address address_ = 0;
  canlust::ProcessLayout layout_{};
  std::uint32_t bitrate_ = 500'000;
  drivecom::DeviceStateMachine sm_{drivecom::EmergencyStopExit::automatic_when_stopped};
  ibs::Word control_ = 0;
  ibs::Word easy_word_ = 0;  // 492-CACNF = 4: the EasyDrive bits as received
  Time state_since_{};
  double reference_hz_ = 0.0;  // as received, before the +-fmax limit
  SpeedPlant plant_{};
  bool warning_ = false;        // the watchdog's WRN response, until the next control telegram
  bool error_warning_ = false;  // an error with the WRN response, until acknowledged
  std::uint16_t warnings_raised_ = 0;  // 6.3 warnings raised by the bench, until acknowledged
  std::optional<canlust::ErrorReaction> fault_;
  DeviceCounters counters_{};
  double load_percent_ = 0.0;
  bool enpo_ = true;   // 7.1.2 step 6: the hardware enable is wired for bus operation
  bool isd00_ = false;
  canlust::ErrStruc last_error_{};
  std::optional<Time> first_power_on_;
  bool download_open_ = false;  // 80-SLOAD = -1 until -2 or 0: the data set being received
  Values pending_{};  // the operating hours of 95-ERR1 count from here
};

}  // namespace ibs::devices::cda3000
