// The master side of the VF1000 parameter channel (INTERBUS manual 4.1.3 and 4.1.4): a queue of
// requests worked one transaction at a time through the communication word. The cycle loop calls
// step() once per cycle with the inverter's word and the time; the application submits requests
// and polls for their outcomes. Nothing here allocates after construction.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/base/bounded_queue.hpp"
#include "ibs/base/error.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/vf1000_channel/comm_word.hpp"
#include "ibs/vf1000_channel/description.hpp"

namespace ibs::vf1000_channel {

enum class RequestKind : std::uint8_t { value_inquiry, value_transfer, description_scan };
std::string_view to_string(RequestKind k);

struct Request {
  RequestKind kind = RequestKind::value_inquiry;
  std::uint16_t number = 0;  // 0..3FFH
  Word value = 0;            // value transfer: the raw value
  Duration timeout{0};       // for this transaction; 0: ClientConfig::timeout
};
constexpr Request value_inquiry(std::uint16_t number) {
  return {RequestKind::value_inquiry, number, 0, Duration{0}};
}
constexpr Request value_transfer(std::uint16_t number, Word value) {
  return {RequestKind::value_transfer, number, value, Duration{0}};
}
constexpr Request description_scan(std::uint16_t number) {
  return {RequestKind::description_scan, number, 0, Duration{0}};
}

enum class OutcomeKind : std::uint8_t {
  value,               // value inquiry answered: Outcome::value
  written,             // value transfer acknowledged: the value took effect
  description,         // description scan answered: Outcome::description
  nak,                 // the inverter refused: Outcome::nak_cause (and siof for transfers)
  timeout,             // no complete answer within the transaction's timeout
  inverter_restarted,  // the inverter showed RESET distinction 0 during the transaction
  aborted,             // the master restarted (Client::restart) before the transaction ended
  protocol_error,      // the inverter's answer fits no row of the cycle tables
};
std::string_view to_string(OutcomeKind k);

enum class NakCause : std::uint8_t {
  none,
  // A value inquiry or description scan was refused: the parameter does not exist (4.1.3.1).
  // Such NAKs leave no entry in 85-SIOF (4.1.4), so there is nothing more to read.
  no_parameter,
  // A value inquiry or description scan refused after its parameter number was accepted: of the
  // causes in 4.1.4 only unintended control bits (a disturbed word) remain. No 85-SIOF entry.
  control_bits,
  // A value transfer was refused and 85-SIOF was read right after it (4.1.4): Outcome::siof.
  siof,
  // A value transfer was refused but reading 85-SIOF failed; it is read before the next transfer.
  siof_unread,
};
std::string_view to_string(NakCause c);

struct Outcome {
  OutcomeKind kind = OutcomeKind::timeout;
  NakCause nak_cause = NakCause::none;
  std::uint8_t siof = 0;  // nak_cause == siof: 85-SIOF as read after the NAK
  // Where the transaction ended: answers taken from the inverter in its last telegram
  // (0 = the start word was never answered).
  std::uint8_t answers = 0;
  Word value = 0;                   // value: the value read; written: the value written
  DescriptionRecord description{};  // description: the 18 bytes; zeros otherwise
};
// "value 03E8H", "NAK: 85-SIOF 80H: invalid value", "timeout after 1 answers" (allocates).
std::string describe(const Outcome& o);

using RequestId = std::uint32_t;  // 0 is never a valid id

enum class SubmitError : std::uint8_t { none, queue_full, invalid_number };
std::string_view to_string(SubmitError e);
struct Submitted {
  RequestId id = 0;
  SubmitError error = SubmitError::none;
  explicit operator bool() const { return error == SubmitError::none; }
};

enum class RequestState : std::uint8_t {
  unknown,  // never submitted, or its outcome has been pushed out of the completed ring
  queued,
  active,
  done,
};
struct Poll {
  RequestState state = RequestState::unknown;
  Outcome outcome;  // valid when state == done
};

struct ClientConfig {
  // Per transaction, from the moment it becomes the active one until its outcome. The manual's
  // transfer times go up to 490 ms for a description scan (7.1); a refused transfer adds the
  // 85-SIOF read.
  Duration timeout = 2s;
  // How long the master holds CODE 0 before it trusts a wait-mode word after a timeout, a protocol
  // error or its own (re)start: long enough for the inverter to have seen the CODE 0 (more than one
  // inverter processing period plus one master cycle). Needed because a mid-telegram inverter word
  // (toggle 0, no ACK/NAK) looks exactly like wait mode.
  Duration resync_hold = 100ms;
  std::size_t queue_capacity = 16;  // requests, the active one included
  std::size_t completed_capacity = 16;
  // True when the channel is known to be at rest at start (master and inverter in wait mode, as
  // in row 0 of every cycle table): the first request goes out in the first step.
  bool start_synchronised = false;
};

enum class ClientState : std::uint8_t {
  resync,  // sending CODE 0 until the inverter is ready and in wait mode, and resync_hold passed
  idle,    // in the starting position, nothing to do
  exchanging,  // a telegram is running
  closing,     // CODE 0 sent after ACK/NAK: waiting for the inverter's wait mode
};
std::string_view to_string(ClientState s);

class Client {
 public:
  // Refuses an empty queue or completed ring (ErrorCode::channel_capacity_zero) and a timeout
  // that is not positive (ErrorCode::channel_timeout_not_positive).
  [[nodiscard]] static Error validate(const ClientConfig& config);
  // A client of a configuration validate() accepts: otherwise it throws std::invalid_argument with
  // validate()'s message, or, in the embedded build, aborts.
  explicit Client(const ClientConfig& config = {});

  // The master's word before its first step: the starting position.
  static constexpr Word initial_word() { return kMasterIdleWord; }

  // Queues a request (no allocation).
  Submitted submit(const Request& r);
  // One master cycle: reads the inverter's word, returns the master's. With `data_valid` false
  // (the bus delivered nothing: a corrupted or recovery cycle) the word is not read, the master's
  // word stays, transaction deadlines still run and a resync hold starts over.
  Word step(Word from_inverter, Time now, bool data_valid = true);
  [[nodiscard]] Poll poll(RequestId id) const;
  // The outcome in place, without a copy; nullptr while the request has none (or is unknown).
  // Valid until the next step() or restart().
  [[nodiscard]] const Outcome* outcome(RequestId id) const;

  // The master restarts: every queued and the active request end `aborted`, the channel resyncs.
  void restart(Time now);

  [[nodiscard]] ClientState state() const { return state_; }
  // Requests waiting behind the active one.
  [[nodiscard]] std::size_t queued() const { return queue_.size() - (active_ ? 1U : 0U); }
  [[nodiscard]] bool busy() const { return !queue_.empty(); }
  // 85-SIOF as last read by the client (its own reads and the application's).
  [[nodiscard]] std::optional<std::uint8_t> last_siof() const { return last_siof_; }
  // True when 85-SIOF may hold bits the master has not read (after it saw the inverter restart or
  // a refused transfer whose 85-SIOF read failed); the next transfer reads it first.
  [[nodiscard]] bool siof_unread() const { return siof_unread_; }

 private:
  // Which telegram the running exchange is.
  enum class Exchange : std::uint8_t {
    main,         // the request itself
    siof_before,  // 85-SIOF read before a transfer (after an inverter restart)
    siof_after,   // 85-SIOF read after a refused transfer (4.1.4)
  };
  struct Pending {
    RequestId id = 0;
    Request request;
  };
  struct Completed {
    RequestId id = 0;
    Outcome outcome;
  };

  Word start_exchange(Exchange e);
  Word answer(Word in, Time now);
  Word enter_resync(Time now);
  Word enter_closing();
  Word send_next(std::uint8_t data);
  // Ends the active request with an outcome of kind k, written in place; returns it for the
  // remaining fields.
  Outcome& complete(OutcomeKind k, std::uint8_t answers);
  // Ends it without an answer (timeout, restart, protocol error); a refused transfer whose
  // 85-SIOF read did not finish ends as NAK with cause siof_unread.
  void fail(OutcomeKind k, std::uint8_t answers);
  [[nodiscard]] std::uint8_t answers_so_far() const;
  void activate_next(Time now);
  [[nodiscard]] const Pending& current() const { return queue_.front(); }

  ClientConfig config_;
  BoundedQueue<Pending> queue_;  // the active request stays at the front until it completes
  std::vector<Completed> completed_;
  std::size_t completed_next_ = 0;
  RequestId next_id_ = 1;

  ClientState state_ = ClientState::resync;
  Time resync_since_{0};
  bool resync_started_ = false;  // resync_since_ is set at the first step in resync

  bool active_ = false;
  Time deadline_{0};
  bool transfer_refused_ = false;  // the active transfer got NAK; 85-SIOF read pending/running

  Exchange exchange_ = Exchange::main;
  Code code_ = Code::reset;
  bool toggle_ = false;
  std::uint8_t answers_ = 0;  // answers taken in this exchange
  std::uint8_t high_ = 0;     // DAT1 of a value inquiry
  DescriptionRecord record_{};
  Word out_ = kMasterIdleWord;

  bool siof_unread_ = false;
  std::optional<std::uint8_t> last_siof_;
};

}  // namespace ibs::vf1000_channel
