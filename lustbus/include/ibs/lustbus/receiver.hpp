// The device's receiver: the state machine of the LUSTBUS manual, section 3, fed one character at a time.
// "strictly as a state-machine without timeout monitoring"; EOT sets it back to the start; it
// answers exactly as section 3 lists:
//
//   ENQUIRY  no answer   improper construction, wrong control character, another address, or 31
//            ADR NAK     improper CODE, read-protected (the Responder says so)
//            ADR STX text  valid
//   SELECT   no answer   improper construction, wrong control character, another address;
//                        address 31 (taken by every device, never answered, 4.2)
//            ADR NAK     wrong BCC (this receiver), improper CODE / access / VALUE (Responder)
//            ADR ACK     valid
//
// Transitions (any state: EOT -> idle, dropping any answer not yet sent; except in select_bcc,
// where the byte after ETX is the BCC whatever its value, 2.2):
//
//   state          character                      next            action
//   idle           ADR of 0, 31 or own            address         remember the ADR
//   idle           ADR of another device          ignoring
//   address        STX                            select_code     (6.2)
//   address        digit                          enquiry_code    first CODE digit (6.1)
//   enquiry_code   digit (5 in all)               enquiry_end
//   enquiry_end    ENQ                            answering       Responder::enquiry (31: ignoring)
//   select_code    digit (5 in all)               select_equals   BCC starts with the CODE
//   select_equals  '='                            select_value
//   select_value   VALUE character (<= 100)       select_value
//   select_value   ETX                            select_bcc
//   select_bcc     any byte                       answering       BCC wrong: NAK + checksum_error;
//                                                                 right: Responder::select
//   answering      anything but EOT               answering       (the answer is sent once due)
//   ignoring       anything but EOT               ignoring
//   any other pair                                ignoring        no answer (3: improper construction)
//
// A fragment -- a telegram begun (ADR seen) and not complete -- followed by a silence longer than
// the inter-character timeout is dropped before the next character is taken (counted in
// `fragments`): a host that dies mid-telegram must not have its telegram completed by the next
// host's bytes (LB-D23; LUSTBUS manual 3's device has no timeout monitoring, and the EOT a next host
// opens with would be taken as the BCC of a cut SELECT, 2.2).
//
// A character with a parity/framing error (>= 80H) is a wrong character. A VALUE longer than 100
// characters is an improper construction (no answer, LB-D4). receive(), take_answer() and
// deliver_*() allocate nothing and throw nothing.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "ibs/base/time.hpp"
#include "ibs/lustbus/responder.hpp"
#include "ibs/lustbus/telegram.hpp"
#include "ibs/lustbus/timing.hpp"

namespace ibs::lustbus {

enum class ReceiverState : std::uint8_t {
  idle,
  address,
  enquiry_code,
  enquiry_end,
  select_code,
  select_equals,
  select_value,
  select_bcc,
  deferred,   // the Responder answers later (deliver_*)
  answering,  // an answer is due or sent; waiting for EOT
  ignoring,   // not for this device, or broken: waiting for EOT
};
std::string_view to_string(ReceiverState s);

// What the last character completed.
enum class ReceiverEvent : std::uint8_t {
  none,
  reset,           // EOT
  enquiry,         // a valid ENQUIRY went to the Responder
  select,          // a valid SELECT went to the Responder
  broadcast,       // a valid SELECT at 31 went to the Responder (no answer)
  checksum_error,  // a SELECT with a wrong BCC
  dropped,         // an improper telegram: nothing until EOT, no answer
};
std::string_view to_string(ReceiverEvent e);

struct ReceiverCounters {
  std::uint32_t enquiries = 0;
  std::uint32_t selects = 0;
  std::uint32_t broadcasts = 0;
  std::uint32_t checksum_errors = 0;
  std::uint32_t dropped = 0;
  std::uint32_t answers = 0;
  std::uint32_t fragments = 0;  // telegram fragments dropped after a silence (LB-D23)
  // Answers never sent: the host's EOT came before they were due or delivered (3: EOT drops an
  // answer not yet sent) -- a host whose response timeout is shorter than the drive's reaction.
  std::uint32_t cut_answers = 0;
};

class Receiver {
 public:
  // `own` is the device's special address 1..30 (82-SIOA/SADDR), or 0 when it has none set.
  Receiver(Responder& responder, Address own);

  // Takes effect with the next telegram (the drive decides when a new 82 applies).
  void set_address(Address own) { own_ = own; }
  [[nodiscard]] Address address() const { return own_; }

  // The silence after which a fragment is dropped (inter_char_timeout() of the line's rate; the
  // factory 9600 Bd's until set). Zero: never, as the LUSTBUS manual 3 describes the device.
  void set_inter_char_timeout(Duration d) { gap_ = d; }
  [[nodiscard]] Duration inter_char_timeout() const { return gap_; }

  // One character from the line.
  void receive(std::uint8_t b, Time now);
  // Characters that arrived together at `now`, as many calls of receive(b, now) in order (the
  // transports read a port in chunks); last_event() is then the last character's.
  void receive(std::span<const std::uint8_t> bytes, Time now);

  // When the pending answer is due (nullopt: none).
  [[nodiscard]] std::optional<Time> answer_due() const;
  // The pending answer's bytes once it is due (empty before, or when there is none); the
  // receiver then waits for EOT. The span stays valid until the next receive().
  std::span<const std::uint8_t> take_answer(Time now);

  // A deferred answer (10.2). false when the receiver no longer waits for it (EOT came first,
  // the telegram was a broadcast): the answer is dropped; the drive's action stands.
  bool deliver_enquiry(const EnquiryAnswer& a, Time now);
  bool deliver_select(const SelectAnswer& a, Time now);

  // Power-on: back to idle, nothing pending.
  void power_on();

  [[nodiscard]] ReceiverState state() const { return state_; }
  [[nodiscard]] ReceiverEvent last_event() const { return event_; }
  [[nodiscard]] const ReceiverCounters& counters() const { return counters_; }

 private:
  // The members one character changes, held in locals over a chunk (receiver.cpp).
  struct Cursor {
    ReceiverState state;
    ReceiverEvent event;
    std::uint8_t code_pos;
    std::uint8_t bcc;
  };
  [[nodiscard]] Cursor cursor() const { return {state_, event_, code_pos_, bcc_}; }
  void put(const Cursor& c) {
    state_ = c.state;
    event_ = c.event;
    code_pos_ = c.code_pos;
    bcc_ = c.bcc;
  }

  void silence(Time now);
  void receive_one(Cursor& c, std::uint8_t b, Time now);
  bool whole_enquiry(Cursor& c, const std::uint8_t* p, Time now);
  void drop(Cursor& c);
  void drop();
  void finish_enquiry(Time now);
  void finish_select(std::uint8_t bcc_received, Time now);
  void prepare(const EnquiryAnswer& a, Time now);
  void prepare(const SelectAnswer& a, Time now);

  Responder* responder_;
  Address own_;
  ReceiverState state_ = ReceiverState::idle;
  ReceiverEvent event_ = ReceiverEvent::none;
  ReceiverCounters counters_{};
  bool deferred_enquiry_ = false;

  Address address_ = 0;  // of the telegram being received
  Code received_code_{};  // the CODE digits as they arrive
  std::uint8_t code_pos_ = 0;
  Code code_{};
  Value value_{};
  std::uint8_t bcc_ = 0;

  Frame answer_{};
  bool answer_pending_ = false;
  Time answer_at_{};

  Duration gap_ = lustbus::inter_char_timeout(kFactoryBaud);
  Time last_char_at_{};
};

}  // namespace ibs::lustbus
