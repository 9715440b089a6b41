// The VF1000's LUSTBUS face (LUSTBUS manual): a Responder over the drive core (drive.hpp), which holds
// the parameters, 85-SIOF (6, 9.2), the storing times (3; 10 exceptions 1 and 4), control from
// 3-CNTL / 5-FSSIO (7.1), the 11-STAT reset and its self-test (8.1.1) and the network watchdog of
// 5.2. The face keeps only what is LUSTBUS's: the standard CODEs S0DPP (2.4.1), four-digit VALUEs,
// the 26-character description (11.1), the reaction times of 10, the reset's cut answer (8.1.1)
// and the line rate taking effect at the next start (11.5). It may share its drive with the
// INTERBUS face (device.hpp). The byte path (enquiry, select, ...) allocates nothing and throws
// nothing.
#pragma once

#include <cstdint>
#include <memory>

#include "ibs/devices/vf1000/drive.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/drive/parameters.hpp"
#include "ibs/lustbus/device_state.hpp"
#include "ibs/lustbus/responder.hpp"
#include "ibs/lustbus/value.hpp"
#include "ibs/drive/data_types.hpp"

namespace ibs::devices::vf1000 {

// How a table type of the VF1000 (drive::DataType) reads as a LUSTBUS VALUE (LUSTBUS manual 2.3.1).
lustbus::DataType lustbus_type(drive::DataType t);

// LUSTBUS manual 10's table: the inverter reacts within 1...60 ms with a KEYPAD, 1...30 ms without,
// drawn from `seed` (LB-D18).
constexpr lustbus::ReactionModel lustbus_reaction(bool keypad, std::uint64_t seed) {
  return lustbus::ReactionModel::uniform(std::chrono::milliseconds(1), std::chrono::milliseconds(keypad ? 60 : 30), seed);
}

struct LustbusTiming {
  // Reaction time of 10: fixed 2 ms unless told (lustbus_reaction(keypad, seed) draws
  // from 10's "1...60 ms" with KEYPAD, "1...30 ms" without; LB-D18). The time the drive takes to
  // store a value (10 exceptions 1 and 4) is the drive's (DriveConfig::storing) and adds to it.
  lustbus::ReactionModel reaction = lustbus::ReactionModel::fixed(std::chrono::milliseconds(2));
  // 8.1.1: "the Inverter's ACK-answer telegram, under certain circumstances, is not sent in
  // full": cut (ADR only) unless told (ack or none).
  lustbus::Reply reset_answer = lustbus::Reply::cut;
  // The inverter's serial interface is RS-485 (not RS-232): LUSTBUS manual 4, "SMARTDRIVE Inverters
  // with the RS-485 interface must additionally have the parameter 61-SOUTA = 7 set. This
  // activates the data direction switch of the internal interface software driver." Without it the
  // face hears nothing (VF-E20). Off unless told: the tests' direct line; the emulator sets it.
  bool rs485 = false;
};

class LustbusDevice final : public lustbus::Responder {
 public:
  // A drive of its own (`drive` its configuration: self-test, storing times), started as after
  // a power-on whose initialisation is done: the power-on bit set (6). A drive on LUSTBUS alone
  // runs the standard software, not the INTERBUS package: its factory values are
  // standalone_parameters()'s (INTERBUS manual 3.1.1, LUSTBUS manual 4.1; VF-E20), whatever
  // drive.interbus_software says. Allocates.
  explicit LustbusDevice(LustbusTiming timing = {}, const DriveConfig& drive = {});
  // The LUSTBUS face of an existing drive, which another face may serve too. Allocates nothing.
  LustbusDevice(std::shared_ptr<Drive> drive, LustbusTiming timing = {});
  // A copy is an independent inverter: the face with a copy of its drive.
  LustbusDevice(const LustbusDevice& other);
  LustbusDevice& operator=(const LustbusDevice&) = delete;
  ~LustbusDevice() override;

  lustbus::EnquiryAnswer enquiry(const lustbus::Code& code, const lustbus::Context& ctx) override;
  lustbus::SelectAnswer select(const lustbus::Code& code, const lustbus::Value& value,
                               const lustbus::Context& ctx) override;
  void checksum_error(const lustbus::Context& ctx) override;
  void telegram_received(const lustbus::Context& ctx) override;

  // Time passes without a telegram: the drive samples, the watchdog of 5.2 may run out.
  void advance(Time now);
  // A new start without the initialisation time: EEPROM values back, RAM values to their
  // defaults, the power-on bit set, 81-SIOC's rate taken (11.5).
  void restart(Time now);
  // 8.1.1: deaf while the drive initialises or boots after a reset; INTERBUS manual 6.1: deaf while the
  // drive operates on the INTERBUS with 1-MODE = 4 (VF-E16); LUSTBUS manual 4: on RS-485 deaf unless
  // 61-SOUTA = 7 (VF-E20); LUSTBUS manual 10 exception 2: deaf while a SMARTCARD is read or written
  // (VF-E21).
  [[nodiscard]] bool listening(Time now) const override {
    return !drive_->initialising(now) && !drive_->card_busy(now) && !drive_->serial_locked() &&
           (!timing_.rs485 || drive_->value(pnr::kSouta) == kSoutaRs485);
  }
  // In the self-test after a reset; at its end the drive is back as after power-on.
  [[nodiscard]] bool booting() const { return drive_->starting(); }
  // A fault of the inverter (tests, the emulator): the power stage blocks (8), 11-STAT shows it.
  void set_fault(bool present, Time now);

  // The inverter's state, for tests and the emulator: the stored values (RAM, EEPROM).
  [[nodiscard]] Word value(std::uint16_t number) const { return drive_->value(number); }
  [[nodiscard]] Word eeprom_value(std::uint16_t number) const { return drive_->eeprom_value(number); }
  [[nodiscard]] std::uint8_t siof() const { return drive_->siof(); }
  // The power stage runs (DRIVECOM OPERATION ENABLED or braking); EEPROM parameters are then not
  // writable (LB-D19).
  [[nodiscard]] bool power_stage_enabled() const { return drive_->power_stage_enabled(); }
  [[nodiscard]] drivecom::State drive_state() const { return drive_->state(); }
  // The rotary-field frequency (Hz, signed by direction), which 12 reads.
  [[nodiscard]] double frequency_hz() const { return drive_->frequency_hz(); }
  // 11-STAT as read (LB-D19): 01H ready, 02H power stage on, 04H counter-clockwise, 80H error.
  [[nodiscard]] Word status() const { return drive_->status(); }
  // The rate the line runs at: 81-SIOC as of the last start (11.5).
  [[nodiscard]] std::uint32_t line_baud() const { return line_baud_; }
  // The inverter as configured for `baud` (81-SIOC, active at once): false for a rate other
  // than 2400, 4800, 9600 (LUSTBUS manual 4).
  bool set_line_baud(std::uint32_t baud);
  // The watchdog ran out (5.2): the inverter is in its error state until 11-STAT = 000FH.
  [[nodiscard]] bool watchdog_fault() const { return drive_->serial_watchdog_fault(); }
  [[nodiscard]] const drive::ParameterTable& table() const { return drive_->table(); }
  // The drive behind this face.
  [[nodiscard]] const Drive& drive() const { return *drive_; }
  [[nodiscard]] Drive& drive() { return *drive_; }
  [[nodiscard]] const std::shared_ptr<Drive>& shared_drive() const { return drive_; }

 private:
  const drive::ParameterInfo* resolve(const lustbus::Code& code, bool& description) const;
  lustbus::SelectAnswer refuse(drive::SiofBit b);
  Duration reaction() { return reactions_.next(); }
  void follow_starts();

  LustbusTiming timing_;
  std::shared_ptr<Drive> drive_;
  lustbus::ReactionTimes reactions_;
  std::uint32_t seen_starts_ = 0;  // the drive's starts() whose end the line rate followed
  std::uint32_t line_baud_ = 9600;
};


}  // namespace ibs::devices::vf1000
