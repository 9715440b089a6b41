// The MC6000 as a LUSTBUS device (seed 000): a Responder serving the wing's parameter table
// (parameters.hpp) with the servo's rules: enhanced CODEs S0PPP and the shared 000xx (2.4.2, 5.2),
// hex VALUEs without leading zeros, the 43-character description (11.2), the 85-SERR latch (6,
// 9.2), EEPROM parameters taken into RAM at once and stored in the background at 15 ms per byte
// with 04H "EEPROM busy" when overloaded (3, 10.2.2), 4-PROG = 1 loading the factory defaults (10
// exception 1) and 111 activating a new 81-SBAUD (11.5), the download handshake on 80-SLOAD of
// the CardWriteable parameters (11.4), substitution texts via 108-STEXT and 61xxx (11.3), the
// PosMOD1 on 49999 (11.6), control from 416-SCTL1 / 428-RSIO through the DRIVECOM state machine
// and the speed plant (7.2), the reset bit 7 of 416-SCTL1 (8.1.2), the network watchdog of 5.2
// and the reaction times of 10. The byte path allocates nothing and throws nothing.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/plant.hpp"
#include "ibs/devices/mc6000/posmod.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/lustbus/device_state.hpp"
#include "ibs/lustbus/responder.hpp"
#include "ibs/lustbus/value.hpp"
#include "ibs/pcp/data_types.hpp"

namespace ibs::devices::mc6000 {

// How a table type of the MC6000 (pcp::DataType) reads as a LUSTBUS VALUE (seed 000, 2.3.2).
lustbus::DataType lustbus_type(pcp::DataType t);

struct LustbusTiming {
  // Reaction time of 10: fixed 2 ms unless told (ReactionModel::servo(keypad, seed) draws from
  // 10's "1...30 ms" with KEYPAD, "1...25 ms" without; LB-D18).
  lustbus::ReactionModel reaction = lustbus::ReactionModel::fixed(std::chrono::milliseconds(2));
  // 3, 10.2.2: "every byte is saved three times", 15 ms per byte.
  Duration eeprom_per_byte = std::chrono::milliseconds(15);
  // 10 exception 1: "up to 10 seconds" for 4-PROG = 1; 2 s here (LB-D18).
  Duration factory_defaults = std::chrono::milliseconds(2000);
  // 11.4 step 4: the plausibility test after SLOAD = -2; 200 ms here (LB-D18).
  Duration download_check = std::chrono::milliseconds(200);
};

class LustbusDevice final : public lustbus::Responder {
 public:
  explicit LustbusDevice(LustbusTiming timing = {});  // allocates (the values)

  lustbus::EnquiryAnswer enquiry(const lustbus::Code& code, const lustbus::Context& ctx) override;
  lustbus::SelectAnswer select(const lustbus::Code& code, const lustbus::Value& value,
                               const lustbus::Context& ctx) override;
  void checksum_error(const lustbus::Context& ctx) override;
  void telegram_received(const lustbus::Context& ctx) override;

  // Time passes without a telegram: the watchdog of 5.2, the end of a download test.
  void advance(Time now);
  // A new start: EEPROM values back, RAM values to their defaults, the power-on bit set, the
  // baud rate of 81-SBAUD taken (11.5).
  void restart(Time now);

  // The servo's state as bit patterns (a 32-bit type's two's complement), for tests and tools.
  [[nodiscard]] std::uint32_t value(std::uint16_t number) const;
  [[nodiscard]] std::uint32_t eeprom_value(std::uint16_t number) const;
  [[nodiscard]] std::uint8_t serr() const { return serr_.bits(); }
  // The power stage runs: DRIVECOM OPERATION ENABLED, reached from 416-SCTL1 bit 0 with the
  // control location on the serial interface (402-CLSEL = SIO) and no fault (7.2).
  [[nodiscard]] bool running() const;
  [[nodiscard]] drivecom::State drive_state() const { return machine_.state(); }
  // The motor speed of the plant (rpm), which 77-SPEED reads.
  [[nodiscard]] double speed_rpm() const { return plant_.speed_rpm(); }
  // The speed reference the reference selectors 417..420 give (rpm): 428-RSIO where one selects
  // RSIO (3), 0 for RCON; other sources are not fitted here.
  [[nodiscard]] double reference_rpm() const;
  // The rate the servo's line runs at: 81-SBAUD as of the last start, or of 4-PROG = 111 (11.5).
  [[nodiscard]] std::uint32_t line_baud() const { return line_baud_; }
  // The servo as configured for `baud` (81-SBAUD, RAM and EEPROM, active at once): false for a
  // rate outside 2400..57600 (seed 000, 4).
  bool set_line_baud(std::uint32_t baud);
  [[nodiscard]] const PosMod& posmod() const { return posmod_; }
  [[nodiscard]] bool watchdog_fault() const { return watchdog_fault_; }
  [[nodiscard]] bool downloading() const { return download_ != Download::idle; }
  [[nodiscard]] Time eeprom_busy_until() const { return eeprom_busy_until_; }

 private:
  enum class Download : std::uint8_t { idle, receiving, testing };
  const pcp::ParameterInfo* resolve(const lustbus::Code& code, bool& description) const;
  lustbus::SelectAnswer refuse(drive::SiofBit b);
  lustbus::EnquiryAnswer describe(const pcp::ParameterInfo& p);
  lustbus::EnquiryAnswer substitution_text(std::uint16_t parameter);
  [[nodiscard]] int slot(std::uint16_t number) const;
  void finish_download(Time now);
  // The DRIVECOM machine takes 416-SCTL1 (at most a few transitions; 8.1.2's reset edge once).
  void drive_control(bool reset_edge);
  Duration reaction() { return reactions_.next(); }

  LustbusTiming timing_;
  std::span<const pcp::ParameterInfo> table_;
  std::vector<std::uint32_t> ram_;
  std::vector<std::uint32_t> eeprom_;
  std::vector<std::uint32_t> saved_;  // the dataset a rejected download brings back (11.4)
  lustbus::SiofLatch serr_;
  lustbus::SerialWatchdog watchdog_;
  bool watchdog_fault_ = false;
  Time eeprom_busy_until_{};
  Download download_ = Download::idle;
  Time download_ready_{};
  lustbus::ReactionTimes reactions_;
  drivecom::DeviceStateMachine machine_{drivecom::EmergencyStopExit::on_block_power_only,
                                        drivecom::State::start_up_inhibit};
  DrivePlant plant_;
  Time plant_time_{};
  std::uint32_t line_baud_ = 9600;
  PosMod posmod_;
};

// 8.1.2: the bit of 416-SCTL1 that resets an error; 7.2.1: bit 0 starts the drive.
inline constexpr std::uint32_t kSctl1Start = 0x0001;
inline constexpr std::uint32_t kSctl1Reset = 0x0080;

}  // namespace ibs::devices::mc6000
