// What a master's user of PCP needs of one communication reference, whatever carries the
// messages: the project's own channel in process-data words (client.hpp: segmentation and link,
// stepped with the channel's words every bus cycle), or a controller board's mailbox, whose
// firmware holds the channel and takes whole messages (mailbox_client.hpp). A device driver
// (the MC6000's) is written once against this interface and runs over either.
//
// The same contract for both: one request at a time (busy), Read / Write / Get-OV need an
// association (Initiate), every submitted request ends in exactly one Result (a confirmation, or
// timeout / link reset / abort / protocol error), taken with take_result_view(). A timeout or a
// protocol error ends the association. step() once per master cycle, time passed in; nothing
// here allocates, throws or locks.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/pcp/data_types.hpp"
#include "ibs/pcp/parameters.hpp"
#include "ibs/pcp/pdu.hpp"

namespace ibs::pcp {

enum class SubmitStatus : std::uint8_t {
  accepted,
  busy,              // a request is outstanding
  not_initiated,     // Read, Write, Get-OV, Identify, Status need an association
  invalid_argument,  // a value that does not convert, or data too long for the PDU
};
std::string_view to_string(SubmitStatus s);

enum class ResultKind : std::uint8_t {
  ok,              // positive confirmation
  negative,        // negative confirmation: Result::error
  incompatible,    // Initiate: the server's KBL does not fit ours (Result::mismatch); aborted
  type_mismatch,   // typed Read: the data length is not the type's
  aborted,         // Abort from the server (Result::abort_reason) or by our user
  link_reset,      // the channel was reset (servo restart, its timeout) before the confirmation
  timeout,         // no confirmation in time; the client aborted the channel
  protocol_error,  // a message that does not answer the request; the client aborted the channel
};
std::string_view to_string(ResultKind k);

struct Result {
  ServiceCode service = ServiceCode::read;
  ResultKind kind = ResultKind::ok;
  std::uint16_t index = 0;  // Read, Write, Get-OV: the object
  std::uint8_t invoke_id = 0;
  PcpError error{};
  AbortReason abort_reason = AbortReason::user;
  KblMismatch mismatch = KblMismatch::none;
  DataBytes data;                 // Read: the value's bytes
  std::optional<Value> value;     // typed Read: the value
  ObjectDescription description;  // Get-OV
  IdentifyInfo identity;          // Identify
  StatusInfo status;              // Status
  Kbl peer_kbl{};                 // Initiate (also when negative or incompatible)
  Time submitted_at{};
  Time completed_at{};

  [[nodiscard]] bool ok() const { return kind == ResultKind::ok; }
};

struct InformationReport {
  std::uint16_t index = 0;
  DataBytes data;
  Time at{};
};

class ParameterClient {
 public:
  virtual ~ParameterClient() = default;

  // Submissions; `timeout` zero means the client's configured request timeout.
  virtual SubmitStatus initiate(Time now, Duration timeout = Duration::zero()) = 0;
  virtual SubmitStatus read(Time now, ParameterRef p, Duration timeout = Duration::zero()) = 0;
  // A typed Read: the result's value in `expected` (type_mismatch for data of another length).
  virtual SubmitStatus read(Time now, ParameterRef p, DataType expected, Duration timeout = Duration::zero()) = 0;
  virtual SubmitStatus write(Time now, ParameterRef p, Value v, Duration timeout = Duration::zero()) = 0;
  virtual SubmitStatus get_ov(Time now, ParameterRef p, Duration timeout = Duration::zero()) = 0;
  // Ends the association: an outstanding request ends as `aborted`; otherwise Abort is sent.
  virtual void abort(Time now) = 0;

  // One master cycle at `now`: the channel's words when it is carried in process data (the
  // device's to the master, the master's to the device); a mailbox client has none and takes
  // empty spans. Runs the request timeout.
  virtual void step(Time now, std::span<const Word> s2m, std::span<Word> m2s) = 0;

  [[nodiscard]] virtual bool busy() const = 0;
  [[nodiscard]] virtual bool associated() const = 0;
  // The next result, the client's own: valid until the client is next used (step, a
  // submission, abort); nullptr when none is ready.
  [[nodiscard]] virtual const Result* take_result_view() = 0;

 protected:
  ParameterClient() = default;
  ParameterClient(const ParameterClient&) = default;
  ParameterClient& operator=(const ParameterClient&) = default;
};

}  // namespace ibs::pcp
