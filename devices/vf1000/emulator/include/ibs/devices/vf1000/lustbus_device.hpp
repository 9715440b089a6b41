// The VF1000 as a LUSTBUS device (seed 000): a Responder serving the wing's parameter table
// (parameters.hpp) through the drive-neutral table and store, with the inverter's own rules:
// standard CODEs S0DPP (2.4.1), four-digit VALUEs, the 26-character description (11.1), the
// 85-SIOF latch (6, 9.2), EEPROM parameters answered only once stored (3; 10 exception 4), 71-PROG
// = 1 loading the factory defaults (10 exception 1), control from 3-CNTL / 5-FSSIO through the
// DRIVECOM state machine and ramp generator of the process-data model (7.1), 11-STAT = 000FH
// resetting a fault with a self-test during which the inverter is deaf (8.1.1), the network
// watchdog of 5.2, a baud rate taking effect at the next start (11.5) and the reaction times of
// 10. The byte path (enquiry, select, ...) allocates nothing and throws nothing.
#pragma once

#include <cstdint>

#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/devices/vf1000/pd_device.hpp"
#include "ibs/drive/parameters.hpp"
#include "ibs/lustbus/device_state.hpp"
#include "ibs/lustbus/responder.hpp"
#include "ibs/lustbus/value.hpp"
#include "ibs/drive/data_types.hpp"

namespace ibs::devices::vf1000 {

// How a table type of the VF1000 (drive::DataType) reads as a LUSTBUS VALUE (seed 000, 2.3.1).
lustbus::DataType lustbus_type(drive::DataType t);

struct LustbusTiming {
  // Reaction time of 10: fixed 2 ms unless told (ReactionModel::inverter(keypad, seed) draws
  // from 10's "1...60 ms" with KEYPAD, "1...30 ms" without; LB-D18).
  lustbus::ReactionModel reaction = lustbus::ReactionModel::fixed(std::chrono::milliseconds(2));
  // 10 exception 4: a changed EEPROM value adds about 120 ms (two bytes) or 60 ms (one byte).
  Duration eeprom_two_bytes = std::chrono::milliseconds(120);
  Duration eeprom_one_byte = std::chrono::milliseconds(60);
  // 10 exception 1: "up to 10 seconds" for 71-PROG = 1; 1.5 s here (LB-D18).
  Duration factory_defaults = std::chrono::milliseconds(1500);
  // 8.1.1: the boot-up (self test) after 11-STAT = 000FH, during which "the connection to the
  // Inverter is broken"; 6.1's ~4 s, as the process-data model's software reset (D13).
  Duration self_test = std::chrono::seconds(4);
  // 8.1.1: "the Inverter's ACK-answer telegram, under certain circumstances, is not sent in
  // full": cut (ADR only) unless told (ack or none).
  lustbus::Reply reset_answer = lustbus::Reply::cut;
};

class LustbusDevice final : public lustbus::Responder {
 public:
  explicit LustbusDevice(LustbusTiming timing = {});  // allocates (the store)

  lustbus::EnquiryAnswer enquiry(const lustbus::Code& code, const lustbus::Context& ctx) override;
  lustbus::SelectAnswer select(const lustbus::Code& code, const lustbus::Value& value,
                               const lustbus::Context& ctx) override;
  void checksum_error(const lustbus::Context& ctx) override;
  void telegram_received(const lustbus::Context& ctx) override;

  // Time passes without a telegram: the watchdog of 5.2 may run out.
  void advance(Time now);
  // A new start (power on, the end of 8.1.1's self-test): EEPROM values back, RAM values to
  // their defaults, the power-on bit set, 81-SIOC's rate taken (11.5).
  void restart(Time now);
  // 8.1.1: deaf while booting after a reset.
  [[nodiscard]] bool listening(Time now) const override { return now >= boot_until_; }
  // In the self-test after a reset; at its end the RAM values go back to their defaults.
  [[nodiscard]] bool booting() const { return booting_; }
  // A fault of the inverter (tests, the emulator): the power stage blocks (8), 11-STAT shows it.
  void set_fault(bool present, Time now);

  // The inverter's state, for tests and the emulator.
  [[nodiscard]] Word value(std::uint16_t number) const;
  [[nodiscard]] Word eeprom_value(std::uint16_t number) const;
  [[nodiscard]] std::uint8_t siof() const { return siof_.bits(); }
  // The power stage runs (DRIVECOM OPERATION ENABLED or braking): from 3-CNTL's start bit (80H
  // clockwise, 40H counter-clockwise) with 1-MODE = 0 and 2-CSEL = 3 and no fault, and after
  // the start bit is gone until the ramp reaches 0 Hz. EEPROM parameters are then not writable
  // (LB-D19).
  [[nodiscard]] bool power_stage_enabled() const;
  [[nodiscard]] drivecom::State drive_state() const { return pd_.state(); }
  // The rotary-field frequency (Hz, signed by direction), which 12 reads.
  [[nodiscard]] double frequency_hz() const { return pd_.frequency_hz(); }
  // 11-STAT as read (LB-D19): 01H ready, 02H power stage on, 04H counter-clockwise, 80H error.
  [[nodiscard]] Word status() const;
  // The rate the line runs at: 81-SIOC as of the last start (11.5).
  [[nodiscard]] std::uint32_t line_baud() const { return line_baud_; }
  // The inverter as configured for `baud` (81-SIOC, active at once): false for a rate other
  // than 2400, 4800, 9600 (seed 000, 4).
  bool set_line_baud(std::uint32_t baud);
  // The watchdog ran out (5.2): the inverter is in its error state until 11-STAT = 000FH.
  [[nodiscard]] bool watchdog_fault() const { return watchdog_fault_; }
  [[nodiscard]] const drive::ParameterTable& table() const { return table_; }

 private:
  const drive::ParameterInfo* resolve(const lustbus::Code& code, bool& description) const;
  lustbus::SelectAnswer refuse(drive::SiofBit b);
  Duration reaction() { return reactions_.next(); }
  // The DRIVECOM control word 3-CNTL stands for, and the reference word of 5-FSSIO (7.1).
  [[nodiscard]] Word control_word() const;
  void run_samples(Time now);
  void sample(Duration dt);  // one sample of the process-data model over `dt`
  void sample_now();         // one sample without time passing: a fault acts at once

  LustbusTiming timing_;
  drive::ParameterTable table_;
  drive::ParameterStore store_;
  lustbus::SiofLatch siof_;
  lustbus::SerialWatchdog watchdog_;
  bool watchdog_fault_ = false;
  bool fault_ = false;
  lustbus::ReactionTimes reactions_;
  Vf1000PdDevice pd_;
  Time pd_time_{};
  Time boot_until_{};
  bool booting_ = false;
  std::uint32_t line_baud_ = 9600;
};

// 81-SIOC's codes (its table row: 0 2400, 1 4800, 2 9600 Bd).
constexpr std::uint32_t sioc_baud(Word code) {
  return code == 0 ? 2400U : code == 1 ? 4800U : 9600U;
}

// 8.1.1: the VALUE of 11-STAT that resets a fault.
inline constexpr Word kStatReset = 0x000F;
// 11-STAT bits as read (LB-D19, chosen).
inline constexpr Word kStatReady = 0x01;
inline constexpr Word kStatRunning = 0x02;
inline constexpr Word kStatCounterClockwise = 0x04;
inline constexpr Word kStatError = 0x80;

}  // namespace ibs::devices::vf1000
