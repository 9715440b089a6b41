// What the device side of LUSTBUS needs from a drive: answers to ENQUIRY and SELECT telegrams
// (LUSTBUS manual 3, 6.1, 6.2). The receiver (receiver.hpp) parses the bytes and calls these; the drive
// owns its parameters, the 85-SIOF/SERR latch, EEPROM timing and descriptions, and knows its
// family's CODE coding (code.hpp helpers). Called on the byte path: implementations must not
// allocate or throw.
#pragma once

#include <cstdint>

#include "ibs/base/time.hpp"
#include "ibs/lustbus/chars.hpp"
#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::lustbus {

// The telegram's circumstances.
struct Context {
  Address address = 0;  // as received: 0 (any device), the device's own, or 31 (broadcast)
  Time now{};           // when the last character (ENQ / BCC) arrived
  [[nodiscard]] constexpr bool broadcast() const { return address == kAddressBroadcast; }
};

enum class Reply : std::uint8_t {
  text,      // ENQUIRY: ADR STX CODE = VALUE ETX BCC
  ack,       // SELECT: ADR ACK
  nak,       // ADR NAK
  deferred,  // the drive answers later through Receiver::deliver_* (10.2, EEPROM)
  none,      // no answer at all
  cut,       // SELECT: only ADR goes out, the ACK is lost (a drive resetting itself at once,
             // 8.1: "the ACK-answer telegram, under certain circumstances, is not sent in full")
};
std::string_view to_string(Reply r);

struct EnquiryAnswer {
  Reply reply = Reply::nak;  // text, nak, deferred or none
  Duration reaction{};       // reaction time (10): last character received -> first one sent
  Value value{};             // the VALUE of a text answer

  static constexpr EnquiryAnswer text(const Value& v, Duration r = {}) {
    return {Reply::text, r, v};
  }
  static constexpr EnquiryAnswer nak(Duration r = {}) { return {Reply::nak, r, {}}; }
  static constexpr EnquiryAnswer deferred() { return {Reply::deferred, {}, {}}; }
};

struct SelectAnswer {
  Reply reply = Reply::nak;  // ack, nak, deferred or none (ignored for a broadcast)
  Duration reaction{};

  static constexpr SelectAnswer ack(Duration r = {}) { return {Reply::ack, r}; }
  static constexpr SelectAnswer nak(Duration r = {}) { return {Reply::nak, r}; }
  static constexpr SelectAnswer deferred() { return {Reply::deferred, {}}; }
  static constexpr SelectAnswer cut(Duration r = {}) { return {Reply::cut, r}; }
};

class Responder {
 public:
  virtual ~Responder() = default;

  // 6.1: a syntactically valid ENQUIRY at this device (address 0 or its own; never 31). The answer
  // is the VALUE (a value, an 11.1/11.2 description, an 11.3 substitution text, PosMOD1 data) or
  // NAK for an improper CODE or read-protected data (3). A NAK on an ENQUIRY enters no cause in
  // 85-SIOF (6.1 note); reading 85 clears the bits it returned (9.2): both are the drive's.
  virtual EnquiryAnswer enquiry(const Code& code, const Context& ctx) = 0;

  // 6.2: a valid SELECT (syntax, address, BCC). The drive takes `value` whole or not at all.
  // NAK for an improper CODE, access disallowed or an improper VALUE, with the cause in 85-SIOF
  // (9.2). For a broadcast (ctx.broadcast()) the answer is not sent (4.2).
  virtual SelectAnswer select(const Code& code, const Value& value, const Context& ctx) = 0;

  // 3 and 9.2 bit 3: a SELECT at this device whose BCC is wrong. The receiver answers NAK (not for
  // a broadcast) and the value goes nowhere; the drive sets its checksum bit.
  virtual void checksum_error(const Context& ctx) = 0;

  // 5.2: a valid ENQUIRY or SELECT arrived, which resets the drive's 84-SIOT watchdog. Called
  // before enquiry() / select(). Default: nothing.
  virtual void telegram_received(const Context& ctx) { (void)ctx; }

  // False while the drive cannot communicate at all (8.1: "the connection is broken for the
  // duration of the boot-up"; 10 exception 2): a telegram completed at `now` gets no answer and
  // reaches none of the calls above, a wrong BCC included. Default: always listening.
  [[nodiscard]] virtual bool listening(Time now) const {
    (void)now;
    return true;
  }
};

}  // namespace ibs::lustbus
