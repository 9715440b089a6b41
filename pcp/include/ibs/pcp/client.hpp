// The master's PCP client for one MC6000 (one communication reference): Initiate, Read, Write,
// Get-OV long, Identify, Status and Abort over the parameter channel (INTERBUS manual 3.2.2 and 4.2).
//
// Asynchronous: a request is submitted (one at a time per communication reference), the cycle
// loop calls step() once per bus cycle with the servo's channel words and the time, and the
// result is taken with take_result(). Every request ends in exactly one result: a confirmation,
// or timeout / link reset / abort / protocol error. A timeout or protocol error aborts the
// channel, which ends the association: the next request needs a new Initiate.
//
// The cycle path (submissions, step, take_result, take_result_view) allocates nothing, throws
// nothing. The interface it shares with the client over a controller board's mailbox
// (mailbox_client.hpp), for a driver that runs over either, is parameter_client.hpp.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/pcp/data_types.hpp"
#include "ibs/pcp/link.hpp"
#include "ibs/pcp/parameter_client.hpp"
#include "ibs/pcp/parameters.hpp"
#include "ibs/pcp/pdu.hpp"

namespace ibs::pcp {

struct ClientConfig {
  int channel_words = 1;  // 1, 2 or 4 (405-SUPI)
  // The communication reference the master's KBL gives the servo (chosen default).
  std::uint8_t communication_reference = 2;
  Kbl kbl = kDefaultClientKbl;
  std::uint16_t password = 0;
  std::uint16_t access_groups = 0;
  Duration request_timeout = 500ms;  // submit -> confirmation, unless a request says otherwise
  Duration link_ack_timeout = 100ms;
};

struct ClientStats {
  std::uint32_t requests = 0;
  std::uint32_t confirmations = 0;
  std::uint32_t timeouts = 0;
  std::uint32_t link_resets = 0;
  std::uint32_t protocol_errors = 0;
  std::uint32_t aborts_received = 0;
};

class Client final : public ParameterClient {
 public:
  // Refuses KBL max PDU sizes outside 20..134 bytes (ErrorCode::channel_pdu_size_invalid), a
  // request_timeout that is not positive (ErrorCode::channel_timeout_not_positive), then what
  // Link::validate refuses of the channel width and link_ack_timeout.
  [[nodiscard]] static Error validate(const ClientConfig& cfg);
  // A client of a configuration validate() accepts: otherwise it throws std::invalid_argument with
  // validate()'s message (configuration time), or, in the embedded build, aborts.
  explicit Client(const ClientConfig& cfg);

  // Submissions. `timeout` zero means the configured request_timeout.
  SubmitStatus initiate(Time now, Duration timeout = Duration::zero()) override;
  SubmitStatus read(Time now, ParameterRef p, Duration timeout = Duration::zero()) override;
  SubmitStatus read(Time now, ParameterRef p, DataType expected,
                    Duration timeout = Duration::zero()) override;
  SubmitStatus read_subindex(Time now, ParameterRef p, std::uint8_t subindex,
                             Duration timeout = Duration::zero());
  SubmitStatus write(Time now, ParameterRef p, Value v, Duration timeout = Duration::zero()) override;
  // Engineering value converted to the type (LUSTBUS manual 2.3.2).
  SubmitStatus write(Time now, ParameterRef p, DataType t, double value,
                     Duration timeout = Duration::zero());
  SubmitStatus write_bytes(Time now, ParameterRef p, std::span<const std::uint8_t> data,
                           std::uint8_t subindex = 0, Duration timeout = Duration::zero());
  SubmitStatus get_ov(Time now, ParameterRef p, Duration timeout = Duration::zero()) override;
  SubmitStatus identify(Time now, Duration timeout = Duration::zero());
  SubmitStatus status(Time now, Duration timeout = Duration::zero());
  // Abort (unconfirmed): ends the association. An outstanding request ends as `aborted` and
  // the channel is reset; otherwise the Abort message is sent.
  void abort(Time now) override;

  // One bus cycle: reads the servo's channel words, writes the master's.
  void step(Time now, std::span<const Word> s2m, std::span<Word> m2s) override;
  // The frame the master shows before its first step (a trace's m2s[0]).
  void show(Time now, std::span<Word> m2s);

  [[nodiscard]] bool busy() const override { return outstanding_; }
  [[nodiscard]] bool associated() const override { return associated_; }
  std::optional<Result> take_result();
  // take_result() without copying the Result (312 bytes): the client's own, valid until the
  // client is next used (step, a submission, abort); nullptr when no result is ready.
  [[nodiscard]] const Result* take_result_view() override {
    if (!result_ready_) return nullptr;
    result_ready_ = false;
    return &result_;
  }
  std::optional<InformationReport> take_information_report();

  [[nodiscard]] const Link& link() const { return link_; }
  [[nodiscard]] const ClientStats& stats() const { return stats_; }
  [[nodiscard]] const ClientConfig& config() const { return cfg_; }
  // The server's KBL from the last positive Initiate.
  [[nodiscard]] const Kbl& peer_kbl() const { return peer_kbl_; }

 private:
  SubmitStatus submit(Time now, RequestPdu& req, Duration timeout, bool needs_association);
  void complete(Time now, ResultKind kind);
  void reset_result();  // result_ as a fresh Result (the submission's fields are set after)
  void handle_message(Time now, std::span<const std::uint8_t> msg);
  void fail_protocol(Time now);

  ClientConfig cfg_;
  Link link_;
  bool associated_ = false;
  Kbl peer_kbl_{};
  std::uint8_t next_invoke_id_ = 0;

  bool outstanding_ = false;
  bool sent_ = false;
  // What a confirmation must match of the outstanding request (its PDU is in pdu_).
  ServiceCode request_service_ = ServiceCode::read;
  std::uint8_t request_invoke_id_ = 0;
  std::uint8_t request_cr_ = 0;
  std::optional<DataType> expected_type_;
  Pdu pdu_{};
  RequestPdu read_request_{};  // the Read requests' (read_subindex)
  Time deadline_{};
  Result result_{};
  bool result_ready_ = false;

  bool abort_pending_ = false;
  Pdu abort_pdu_{};

  ResponsePdu response_{};  // the message handle_message() decodes, reused

  InformationReport report_{};
  bool report_ready_ = false;
  ClientStats stats_{};
};

}  // namespace ibs::pcp
