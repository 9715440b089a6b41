// The one interface a drive serves its parameters through, to every bus: the communication word,
// PCP, LUSTBUS, CANLust and the DFS-1 faces each turn their telegram into a slot and a Raw (their
// codec), ask here, and turn the answer back into their bytes (a NAK and its 85-SIOF bit, a PCP
// error class and code, a CANLust status). The drive owns its store, its checks, 85-SIOF/SERR and
// its timing, so that every bus of one drive sees the same values (../shared/design.md, "One
// drive, many faces"). It replaces drive::ParameterAccess, canlust::ParameterAccess,
// pcp::ServedParameters and mc6000::DriveAccess.
//
// Every call is on the cycle path: no allocation, no exception, no lock; time is passed in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "ibs/base/time.hpp"
#include "ibs/od/dictionary.hpp"
#include "ibs/od/siof.hpp"

namespace ibs::od {

// Why a drive refused an access. Each refusal but `none` and `latched` enters its bit in
// 85-SIOF/SERR (error_flag) where the drive keeps one (LUSTBUS manual 9.2); a codec maps it to its
// bus's answer.
enum class Refusal : std::uint8_t {
  none,
  latched,       // a bit of 85-SIOF/SERR is set: "all further SELECT-telegrams are rejected" (9.2)
  no_parameter,  // 20H: no such parameter
  read_only,     // 40H: a RAM actual value, or a value only the drive sets
  not_now,     // 40H: not in this state (EEPROM with the power stage on, SLOAD while running, ...)
  wrong_kind,  // 40H: a text read or written as a number, or a number as a text
  busy,        // 04H: the last EEPROM value is still being saved (LUSTBUS manual 3)
  transfer_error,  // 08H: an error in the data transfer (the comm word: unintended control bits)
  bad_value,       // 80H: the bus's value is no value of the type
  too_high,        // 80H: above the maximum (or an SLOAD value the host may not write)
  too_low,         // 80H: below the minimum
  not_a_choice,    // 80H: none of the substitution texts where only those are values
};
std::string_view to_string(Refusal r);  // "no parameter", "above the maximum", ...

// The 85-SIOF/SERR bit a refusal enters (LUSTBUS manual 9.2 table; 0 for none and latched).
constexpr std::uint8_t error_flag(Refusal r) {
  switch (r) {
    case Refusal::none:
    case Refusal::latched:
      return 0;
    case Refusal::no_parameter:
      return siof_mask(SiofBit::no_parameter);
    case Refusal::read_only:
    case Refusal::not_now:
    case Refusal::wrong_kind:
      return siof_mask(SiofBit::no_change);
    case Refusal::busy:
      return siof_mask(SiofBit::eeprom_busy);
    case Refusal::transfer_error:
      return siof_mask(SiofBit::checksum);
    case Refusal::bad_value:
    case Refusal::too_high:
    case Refusal::too_low:
    case Refusal::not_a_choice:
      return siof_mask(SiofBit::invalid_value);
  }
  return 0;
}
// The refusal a value's fit() is.
constexpr Refusal refusal_of(Fit f) {
  switch (f) {
    case Fit::ok:
      return Refusal::none;
    case Fit::wrong_type:
      return Refusal::bad_value;
    case Fit::too_low:
      return Refusal::too_low;
    case Fit::too_high:
      return Refusal::too_high;
    case Fit::not_a_choice:
      return Refusal::not_a_choice;
  }
  return Refusal::bad_value;
}

// What a write (or a face's refusal) did.
struct Answer {
  Refusal refusal = Refusal::none;  // none: done
  Duration after{};                 // how long the drive works before it can answer (EEPROM, PROG)
  bool restarted = false;           // the drive restarted at once: the answer may not go out whole
  bool kept_changed = false;        // the EEPROM/flash copy took another value
  bool init_control = false;        // an attr::kInitControl parameter was written (11.2.1)
  [[nodiscard]] constexpr bool ok() const { return refusal == Refusal::none; }
};

// What a read returned: eight bytes, so that it comes back in a register.
struct Reading {
  Raw raw = 0;
  Refusal refusal = Refusal::none;
  [[nodiscard]] constexpr bool ok() const { return refusal == Refusal::none; }
};

// A text read's outcome: the characters copied, or why none.
struct TextAnswer {
  std::size_t size = 0;
  Refusal refusal = Refusal::none;
  [[nodiscard]] constexpr bool ok() const { return refusal == Refusal::none; }
};

class ServedParameters {
 public:
  virtual ~ServedParameters() = default;

  [[nodiscard]] virtual const Dictionary& dictionary() const = 0;
  // Time passes: background work of the drive may end (an EEPROM save, a download's test).
  virtual void advance(Time now) = 0;
  // A read that may act (reading 85-SIOF/SERR clears the bits it returns). kNoSlot: refused
  // no_parameter, entering nothing (LUSTBUS manual 6.1 note; INTERBUS manual 4.1.4).
  virtual Reading read(Slot s, Time now) = 0;
  // The value as it stands, without acting (an Information Report, a latched comm-word value;
  // 0 for kNoSlot).
  [[nodiscard]] virtual Raw peek(Slot s) const = 0;
  // The factory default as this drive has it -- its wing's overlay may change the entry's (VF-E20,
  // MC-D10) -- for a description (the comm word's record, PCP's Get-OV, LUSTBUS 11.1/11.2).
  [[nodiscard]] virtual Raw factory_default(Slot s) const {
    return s < dictionary().size() ? dictionary()[s].default_raw() : 0;
  }
  // Would a write be taken now? nullopt: the access only (the comm word's PNR, INTERBUS manual
  // 4.1.3.2.1), else the value too. Enters nothing.
  [[nodiscard]] virtual Refusal check(Slot s, std::optional<Raw> r, Time now) const = 0;
  // A write of the Raw a codec made (from_bus): checked again (a refusal enters its bit), then
  // taken.
  virtual Answer write(Slot s, Raw r, Time now) = 0;
  // A face's own refusal (a PCP subindex, a LUSTBUS CODE that only reads): latched while
  // 85-SIOF/SERR holds a bit, else it enters the refusal's bit.
  virtual Answer refuse(Refusal r) = 0;
  // 85-SIOF/SERR (0 for a drive that keeps none).
  [[nodiscard]] virtual std::uint8_t error_flags() const = 0;
  // The device's own causes (the watchdog's 02H, a transfer error's 08H): entered whatever is set.
  virtual void raise_error_flags(std::uint8_t bits) = 0;
  // A read of 85-SIOF/SERR returned `bits`: they are erased, bits set since stay (9.2).
  virtual void clear_error_flags(std::uint8_t bits) = 0;
  // The drive is in a fault (PCP Status; a CANLust status bit).
  [[nodiscard]] virtual bool fault() const = 0;
  // Texts (Type::string): the characters into `out` (at most its size) / a new text.
  virtual TextAnswer read_text(Slot s, std::span<char> out, Time now) {
    static_cast<void>(s), static_cast<void>(out), static_cast<void>(now);
    return {0, Refusal::wrong_kind};
  }
  virtual Answer write_text(Slot s, std::string_view text, Time now) {
    static_cast<void>(s), static_cast<void>(text), static_cast<void>(now);
    return {Refusal::wrong_kind};
  }

 protected:
  ServedParameters() = default;
  ServedParameters(const ServedParameters&) = default;
  ServedParameters& operator=(const ServedParameters&) = default;
};

}  // namespace ibs::od
