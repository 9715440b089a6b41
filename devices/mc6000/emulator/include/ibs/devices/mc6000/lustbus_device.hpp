// The MC6000 as a LUSTBUS device (seed 000): a Responder serving the wing's parameter table
// (parameters.hpp) with the servo's rules: enhanced CODEs S0PPP and the shared 000xx (2.4.2, 5.2),
// hex VALUEs without leading zeros, the 43-character description (11.2), the 85-SERR latch (6,
// 9.2), EEPROM parameters taken into RAM at once and stored in the background at 15 ms per byte
// with 04H "EEPROM busy" when overloaded (3, 10.2.2), 4-PROG = 1 loading the factory defaults (10
// exception 1), the download handshake on 80-SLOAD (11.4), the reset bit 7 of 416-SCTL1 (8.1.2)
// and the network watchdog of 5.2. The byte path allocates nothing and throws nothing.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/lustbus/device_state.hpp"
#include "ibs/lustbus/responder.hpp"
#include "ibs/lustbus/value.hpp"
#include "ibs/pcp/data_types.hpp"

namespace ibs::devices::mc6000 {

// How a table type of the MC6000 (pcp::DataType) reads as a LUSTBUS VALUE (seed 000, 2.3.2).
lustbus::DataType lustbus_type(pcp::DataType t);

struct LustbusTiming {
  // Reaction time of 10 ("1...25 ms" without KEYPAD): 2 ms, a modelling choice (LB-D18).
  Duration reaction = std::chrono::milliseconds(2);
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
  // A new start: EEPROM values back, RAM values to their defaults, the power-on bit set.
  void restart(Time now);

  // The servo's state as bit patterns (a 32-bit type's two's complement), for tests and tools.
  [[nodiscard]] std::uint32_t value(std::uint16_t number) const;
  [[nodiscard]] std::uint32_t eeprom_value(std::uint16_t number) const;
  [[nodiscard]] std::uint8_t serr() const { return serr_.bits(); }
  [[nodiscard]] bool running() const;  // 416-SCTL1 bit 0 and no fault (7.2.1)
  [[nodiscard]] bool watchdog_fault() const { return watchdog_fault_; }
  [[nodiscard]] bool downloading() const { return download_ != Download::idle; }
  [[nodiscard]] Time eeprom_busy_until() const { return eeprom_busy_until_; }

 private:
  enum class Download : std::uint8_t { idle, receiving, testing };
  const pcp::ParameterInfo* resolve(const lustbus::Code& code, bool& description) const;
  lustbus::SelectAnswer refuse(drive::SiofBit b);
  [[nodiscard]] int slot(std::uint16_t number) const;
  void finish_download(Time now);

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
};

// 8.1.2: the bit of 416-SCTL1 that resets an error; 7.2.1: bit 0 starts the drive.
inline constexpr std::uint32_t kSctl1Start = 0x0001;
inline constexpr std::uint32_t kSctl1Reset = 0x0080;

}  // namespace ibs::devices::mc6000
