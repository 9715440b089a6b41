// The MC6000's LUSTBUS face (LUSTBUS manual): a Responder over the drive core (drive.hpp). It owns only
// what belongs to the telegrams: the enhanced CODEs S0PPP and the shared 000xx (2.4.2, 5.2), hex
// VALUEs of the type's full width, the 43-character description (11.2), substitution texts via
// 108-STEXT and 61xxx (11.3), the reaction times of 10, the line's baud rate (81-SBAUD, 4-PROG =
// 111: 11.5) and the PosMOD1 option on 49999 (11.6). Everything else -- the store, 85-SERR, the
// write checks, EEPROM busy, 4-PROG = 1, the 80-SLOAD download, control from 416-SCTL1 / 428-RSIO
// and its reset bit 7, the watchdog of 5.2, the plant -- is the core's, which an INTERBUS face may
// serve at the same time. The byte path allocates nothing and throws nothing.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "ibs/devices/mc6000/drive.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/posmod.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/lustbus/device_state.hpp"
#include "ibs/lustbus/responder.hpp"
#include "ibs/lustbus/value.hpp"
#include "ibs/pcp/data_types.hpp"

namespace ibs::devices::mc6000 {

// How a table type of the MC6000 (pcp::DataType) reads as a LUSTBUS VALUE (LUSTBUS manual 2.3.2).
lustbus::DataType lustbus_type(pcp::DataType t);

// LUSTBUS manual 10's table: the servo reacts within 1...30 ms with a KEYPAD, 1...25 ms without,
// drawn from `seed` (LB-D18).
constexpr lustbus::ReactionModel lustbus_reaction(bool keypad, std::uint64_t seed) {
  return lustbus::ReactionModel::uniform(std::chrono::milliseconds(1), std::chrono::milliseconds(keypad ? 30 : 25), seed);
}

struct LustbusTiming {
  // Reaction time of 10: fixed 2 ms unless told (lustbus_reaction(keypad, seed) draws from
  // 10's "1...30 ms" with KEYPAD, "1...25 ms" without; LB-D18).
  lustbus::ReactionModel reaction = lustbus::ReactionModel::fixed(std::chrono::milliseconds(2));
  // The drive's own timing, for a core this face makes itself (a face on a given core takes
  // that core's): drive_parameters.hpp, DriveTiming (docs/errata.md MC-D1, MC-D2).
  Duration eeprom_per_byte = DriveTiming{}.eeprom_per_byte;
  Duration factory_defaults = DriveTiming{}.factory_defaults;
  Duration download_check = DriveTiming{}.download_check;
};

class LustbusDevice final : public lustbus::Responder {
 public:
  // A servo of its own (a drive core started initialised: 85-SERR shows the power-on bit).
  explicit LustbusDevice(LustbusTiming timing = {});  // allocates (the core)
  // The LUSTBUS face of an existing drive core, shared with other faces.
  explicit LustbusDevice(std::shared_ptr<Drive> drive, LustbusTiming timing = {});

  lustbus::EnquiryAnswer enquiry(const lustbus::Code& code, const lustbus::Context& ctx) override;
  lustbus::SelectAnswer select(const lustbus::Code& code, const lustbus::Value& value,
                               const lustbus::Context& ctx) override;
  void checksum_error(const lustbus::Context& ctx) override;
  void telegram_received(const lustbus::Context& ctx) override;
  // Without mains the servo answers nothing (MC-D6), nor while it boots after a reaction-5 error
  // reset (LUSTBUS manual 8.1.2: "the connection ... is broken for the duration of the boot-up"), nor
  // while a SMARTCARD is read or written (LUSTBUS manual 10 exception 2; MC-D9).
  [[nodiscard]] bool listening(Time now) const override {
    return drive_->powered() && !drive_->booting(now) && !drive_->card_busy(now);
  }

  // Time passes without a telegram: the watchdog of 5.2, the end of a download test.
  void advance(Time now);
  // A new start: EEPROM values back, RAM values to their defaults, the power-on bit set, the
  // baud rate of 81-SBAUD taken (11.5).
  void restart(Time now);

  [[nodiscard]] Drive& drive() { return *drive_; }
  [[nodiscard]] const Drive& drive() const { return *drive_; }
  [[nodiscard]] const std::shared_ptr<Drive>& shared_drive() const { return drive_; }

  // The servo's state as bit patterns (a 32-bit type's two's complement), for tests and tools.
  [[nodiscard]] std::uint32_t value(std::uint16_t number) const { return drive_->parameters().raw(number); }
  [[nodiscard]] std::uint32_t eeprom_value(std::uint16_t number) const;
  [[nodiscard]] std::uint8_t serr() const { return drive_->parameters().serr(); }
  // The power stage runs: DRIVECOM OPERATION ENABLED, reached from 416-SCTL1 bit 0 with the
  // control location on the serial interface (402-CLSEL = SIO) and no fault (7.2).
  [[nodiscard]] bool running() const { return drive_->running(); }
  [[nodiscard]] drivecom::State drive_state() const { return drive_->state(); }
  // The motor speed of the plant (rpm), which 77-SPEED reads.
  [[nodiscard]] double speed_rpm() const { return drive_->actual_rpm(); }
  // The speed reference the reference selectors 417..420 give (rpm): 428-RSIO where one selects
  // RSIO (3), 0 for RCON; other sources are not fitted here.
  [[nodiscard]] double reference_rpm() const { return drive_->serial_reference_rpm(); }
  // The rate the servo's line runs at: 81-SBAUD as of the last start, or of 4-PROG = 111 (11.5).
  [[nodiscard]] std::uint32_t line_baud() const { return line_baud_; }
  // The servo as configured for `baud` (81-SBAUD, RAM and EEPROM, active at once): false for a
  // rate outside 2400..57600 (LUSTBUS manual 4).
  bool set_line_baud(std::uint32_t baud);
  [[nodiscard]] const PosMod& posmod() const { return posmod_; }
  [[nodiscard]] bool watchdog_fault() const { return drive_->serial_watchdog_fault(); }
  [[nodiscard]] bool downloading() const { return drive_->parameters().downloading(); }
  [[nodiscard]] Time eeprom_busy_until() const { return drive_->parameters().eeprom_busy_until(); }

 private:
  const pcp::ParameterInfo* resolve(const lustbus::Code& code, bool& description) const;
  lustbus::EnquiryAnswer describe(const pcp::ParameterInfo& p);
  lustbus::EnquiryAnswer substitution_text(std::uint16_t parameter);
  Duration reaction() { return reactions_.next(); }
  // The servo started anew (restart, or a reaction-5 reset's boot): what the face takes then.
  void started(Time now);

  std::shared_ptr<Drive> drive_;
  lustbus::ReactionTimes reactions_;
  std::uint32_t line_baud_ = 9600;
  std::uint32_t baud_activations_ = 0;  // the core's count of 4-PROG = 111 this face has acted on
  PosMod posmod_;
};

}  // namespace ibs::devices::mc6000
