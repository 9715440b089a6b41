// The master's side of the CANLust parameter channel (CANLust manual 4.5): a sans-I/O client with a
// request queue, at most one request per drive at a time (CAL: every request gets exactly one
// reply), a timeout per request, and string reads and writes as one call each.
//
//   client.submit(read(1, 360));          // queued
//   client.step(now);                      // starts requests, times them out
//   while (auto f = client.take_frame()) bus.send(*f);
//                                          // or: CanFrame f; while (client.take_frame(f)) ...
//   client.receive(frame, now);            // every frame from the bus (others are ignored)
//   client.poll(id)                        // queued / active / done + the outcome
//
// submit, step, take_frame and receive allocate nothing and throw nothing: the queue, the
// per-drive slots, the outbox and the ring of outcomes are allocated by the constructor.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "ibs/canlust/frame.hpp"
#include "ibs/canlust/identifiers.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/base/bounded_queue.hpp"
#include "ibs/base/time.hpp"

namespace ibs::canlust {

struct ClientConfig {
  IdentifierMap ids{};
  // A whole single-value request, from its request telegram to the reply (4.3.3: 150-SAVE takes
  // "a few hundred ms"; give such a request its own timeout).
  Duration timeout = 250ms;
  // A whole string transfer (up to 27 telegram pairs).
  Duration string_timeout = 2s;
  std::size_t queue_capacity = 32;
  std::size_t completed_capacity = 64;
  std::size_t outbox_capacity = 16;
};

enum class RequestKind : std::uint8_t { read, write, describe, read_string, write_string };
std::string_view to_string(RequestKind k);

struct Request {
  RequestKind kind = RequestKind::read;
  Address address = 0;
  std::uint16_t parameter = 0;
  std::uint8_t index = 0;       // byte 7: field index (read/write) or description item
  std::uint32_t value = 0;      // write: bytes 3-6
  FixedString text{};           // write_string
  bool text_too_long = false;   // write_string(): the text had more than 99 characters
  std::optional<Duration> timeout;
};
// Inline, like submit's numeric part (issue 26): no call for building a request.
inline Request read(Address a, std::uint16_t parameter, std::uint8_t index = 0) {
  Request r;
  r.kind = RequestKind::read;
  r.address = a;
  r.parameter = parameter;
  r.index = index;
  return r;
}
inline Request write(Address a, std::uint16_t parameter, std::uint32_t value, std::uint8_t index = 0) {
  Request r = read(a, parameter, index);
  r.kind = RequestKind::write;
  r.value = value;
  return r;
}
inline Request describe(Address a, std::uint16_t parameter, std::uint8_t item) {
  Request r = read(a, parameter, item);
  r.kind = RequestKind::describe;
  return r;
}
inline Request read_string(Address a, std::uint16_t parameter) {
  Request r = read(a, parameter);
  r.kind = RequestKind::read_string;
  return r;
}
Request write_string(Address a, std::uint16_t parameter, std::string_view text);

enum class OutcomeKind : std::uint8_t {
  done,               // status 0: `value` (read, describe, write echo) or `text` (read_string)
  refused,            // the drive answered with status bits `status` (and the transfer ended)
  timeout,            // no (complete) answer within the request's timeout
  checksum_mismatch,  // string read: List_End's checksum is not the XOR of the blocks received
  bad_reply,          // a reply that breaks the sequence: a write block not echoed, List_End
                      // before the terminator, data after it, more than 100 bytes
  aborted,            // abort_all()
};
std::string_view to_string(OutcomeKind k);

struct Outcome {
  OutcomeKind kind = OutcomeKind::aborted;
  std::uint8_t status = 0;
  std::uint32_t value = 0;
  FixedString text{};
  std::uint8_t telegrams = 0;  // request telegrams sent
  Time started{};              // when its first telegram was handed out
  Time finished{};
};
std::string describe(const Outcome& o);  // allocates: for reports

using RequestId = std::uint32_t;
enum class SubmitError : std::uint8_t { none, queue_full, invalid_address, text_too_long, invalid_timeout };
std::string_view to_string(SubmitError e);
struct Submitted {
  RequestId id = 0;
  SubmitError error = SubmitError::none;
  explicit operator bool() const { return error == SubmitError::none; }
};
enum class RequestState : std::uint8_t { queued, active, done, unknown };
struct Poll {
  RequestState state = RequestState::unknown;
  const Outcome* outcome = nullptr;  // when done; valid until completed_capacity more finish
};

struct ClientCounters {
  std::uint32_t stray_replies = 0;  // replies no active request waited for
  std::uint32_t timeouts = 0;
  std::uint32_t dropped_frames = 0;  // outbox full (frames not taken): the request times out
};

struct ParameterClientProbe;  // tests: submit's general path (tests/canlust/shortcuts_test.cpp)

class ParameterClient {
 public:
  explicit ParameterClient(const ClientConfig& config = {});

  // Inline for the numeric requests (issue 26): the same checks in the same order as the
  // general path, which a string write takes (its text is copied).
  Submitted submit(const Request& r) {
    if (r.kind == RequestKind::write_string) return submit_general(r);
    if (r.address > config_.ids.max_address) return {0, SubmitError::invalid_address};
    if (r.timeout && *r.timeout <= Duration::zero()) return {0, SubmitError::invalid_timeout};
    if (queued_ == queue_capacity_) return {0, SubmitError::queue_full};
    const RequestId id = next_id_++;
    Queued& q = queue_[queued_++];
    q.id = id;
    copy_numeric(q.request, r);
    return {id, SubmitError::none};
  }
  void step(Time now);
  // The next frame into `out`; false when there is none. Inline: asked until it has nothing
  // (issue 26: the frame is not carried out in an optional).
  bool take_frame(CanFrame& out) {
    if (outbox_.empty()) return false;
    out = outbox_.front();
    outbox_.pop();
    return true;
  }
  std::optional<CanFrame> take_frame() {
    CanFrame f;
    if (!take_frame(f)) return std::nullopt;
    return f;
  }
  // Any frame; parameter replies of drives with an active request are taken, others ignored.
  void receive(const CanFrame& f, Time now);
  [[nodiscard]] Time next_deadline() const;

  // Inline: the newest outcome first, the one a request is mostly polled for right after it
  // finished (issue 26); else the general walk. An id is in one place only (queued, active or
  // done), so where it is looked for first does not change the answer.
  [[nodiscard]] Poll poll(RequestId id) const {
    const Completed& newest = completed_[completed_next_ == 0 ? completed_capacity_ - 1 : completed_next_ - 1];
    if (id != 0 && newest.id == id) return {RequestState::done, &newest.outcome};
    return poll_general(id);
  }
  [[nodiscard]] bool idle() const;
  [[nodiscard]] const ClientConfig& config() const { return config_; }
  [[nodiscard]] const ClientCounters& counters() const { return counters_; }
  // Ends every queued and active request with `aborted`.
  void abort_all(Time now);

 private:
  struct Active {
    bool busy = false;
    std::uint8_t listed_at = 0;    // its place in busy_ while busy
    RequestId id = 0;
    Request request{};
    Time started{};
    Time deadline{};
    std::uint8_t block = 0;        // of the telegram awaiting its reply
    std::uint8_t telegrams = 0;
    std::uint32_t sent_data = 0;   // of that telegram (echo check)
    std::uint32_t checksum = 0;
    std::size_t bytes = 0;         // string read: bytes received; write: bytes to send
    bool terminator = false;       // string read: the 0 has arrived
    std::uint8_t awaiting_mode = 0;
    // config_.ids.id of this address's parameter requests, -1 for none: found once by the
    // constructor (issue 26), the map does not change.
    std::int32_t request_id = -1;
    FixedString text{};
  };
  struct Queued {
    RequestId id = 0;
    Request request{};
  };
  struct Completed {
    RequestId id = 0;
    Outcome outcome{};
  };

  // Inlined into their callers in parameter_client.cpp (issue 26: start into step, on_reply into
  // receive, send into both; one call fewer per frame each).
  [[gnu::always_inline]] inline void start(Active& a, Time now);
  [[gnu::always_inline]] inline void send(Active& a, std::uint8_t mode, std::uint32_t data,
                                          std::uint8_t block, Time now);
  void finish(Active& a, OutcomeKind kind, Time now, std::uint8_t status = 0, std::uint32_t value = 0);
  [[gnu::always_inline]] inline void on_reply(Active& a, const ParameterTelegram& t, Time now);
  void send_write_block(Active& a, Time now);
  void list_busy(Active& a, Address address);
  void unlist_busy(Active& a);

  friend struct ParameterClientProbe;
  void dequeue(std::size_t k);
  // submit()'s general path, for every kind; the inline part hands it a string write.
  Submitted submit_general(const Request& r);
  // poll()'s general path: active, queued, then the outcomes newest first.
  [[nodiscard]] Poll poll_general(RequestId id) const;
  // A request with its text's characters only (copy_numeric, and a string write's text).
  static void copy_request(Request& to, const Request& from);
  // A request without its text: what every kind but a string write needs (the text's length 0).
  static void copy_numeric(Request& to, const Request& from) {
    to.kind = from.kind;
    to.address = from.address;
    to.parameter = from.parameter;
    to.index = from.index;
    to.value = from.value;
    to.text_too_long = from.text_too_long;
    to.timeout = from.timeout;
    to.text.length = 0;
  }

  ClientConfig config_;
  KindMatcher replies_;  // config_.ids' parameter replies
  // The first queued_ entries, in submission order; sized by the constructor, so that queueing
  // neither constructs nor zeroes a request with its text buffer (issue 26).
  std::vector<Queued> queue_;
  std::size_t queue_capacity_ = 0;  // queue_.size()
  std::size_t queued_ = 0;
  std::vector<Active> active_;  // one per address 0..max_address
  // The addresses whose slot is busy, in no order (issue 26: step, poll and next_deadline touch
  // only the drives with a request, not all 100 slots); capacity reserved by the constructor.
  std::vector<Address> busy_;
  BoundedQueue<CanFrame> outbox_;
  std::vector<Completed> completed_;  // ring
  std::size_t completed_capacity_ = 1;  // completed_.size(), kept (no division for it)
  std::size_t completed_next_ = 0;
  RequestId next_id_ = 1;
  ClientCounters counters_{};
};

}  // namespace ibs::canlust
