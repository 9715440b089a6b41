// The VF1000 as a LUSTBUS device (seed 000): a Responder serving the wing's parameter table
// (parameters.hpp) through the drive-neutral table and store, with the inverter's own rules:
// standard CODEs S0DPP (2.4.1), four-digit VALUEs, the 26-character description (11.1), the
// 85-SIOF latch (6, 9.2), EEPROM parameters answered only once stored (3; 10 exception 4), 71-PROG
// = 1 loading the factory defaults (10 exception 1), 11-STAT = 000FH resetting a fault (8.1.1) and
// the network watchdog of 5.2. The byte path (enquiry, select, ...) allocates nothing and throws
// nothing.
#pragma once

#include <cstdint>

#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/drive/parameters.hpp"
#include "ibs/lustbus/device_state.hpp"
#include "ibs/lustbus/responder.hpp"
#include "ibs/lustbus/value.hpp"
#include "ibs/drive/data_types.hpp"

namespace ibs::devices::vf1000 {

// How a table type of the VF1000 (drive::DataType) reads as a LUSTBUS VALUE (seed 000, 2.3.1).
lustbus::DataType lustbus_type(drive::DataType t);

struct LustbusTiming {
  // Reaction time of 10 ("1...30 ms" without KEYPAD): 2 ms, a modelling choice (LB-D18).
  Duration reaction = std::chrono::milliseconds(2);
  // 10 exception 4: a changed EEPROM value adds about 120 ms (two bytes) or 60 ms (one byte).
  Duration eeprom_two_bytes = std::chrono::milliseconds(120);
  Duration eeprom_one_byte = std::chrono::milliseconds(60);
  // 10 exception 1: "up to 10 seconds" for 71-PROG = 1; 1.5 s here (LB-D18).
  Duration factory_defaults = std::chrono::milliseconds(1500);
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
  // A new start (power on, the reset of 8.1.1): EEPROM values back, RAM values to their defaults,
  // the power-on bit set.
  void restart(Time now);

  // The inverter's state, for tests and the emulator.
  [[nodiscard]] Word value(std::uint16_t number) const;
  [[nodiscard]] Word eeprom_value(std::uint16_t number) const;
  [[nodiscard]] std::uint8_t siof() const { return siof_.bits(); }
  // The power stage runs while 3-CNTL holds a start command (bit 7 clockwise, bit 6
  // counter-clockwise) and no fault is set; EEPROM parameters are then not writable (LB-D19).
  [[nodiscard]] bool power_stage_enabled() const;
  // The watchdog ran out (5.2): the inverter is in its error state until 11-STAT = 000FH.
  [[nodiscard]] bool watchdog_fault() const { return watchdog_fault_; }
  [[nodiscard]] const drive::ParameterTable& table() const { return table_; }

 private:
  const drive::ParameterInfo* resolve(const lustbus::Code& code, bool& description) const;
  lustbus::SelectAnswer refuse(drive::SiofBit b);

  LustbusTiming timing_;
  drive::ParameterTable table_;
  drive::ParameterStore store_;
  lustbus::SiofLatch siof_;
  lustbus::SerialWatchdog watchdog_;
  bool watchdog_fault_ = false;
};

// 8.1.1: the VALUE of 11-STAT that resets a fault.
inline constexpr Word kStatReset = 0x000F;

}  // namespace ibs::devices::vf1000
