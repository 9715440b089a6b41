// PCP through a controller board's mailbox (docs/ddi.md, "PCP over the mailbox"; docs/pcp.md,
// "Through a board's mailbox"). On an INTERBUS controller board the firmware holds the devices'
// PCP channels -- segmentation, link, the channel words -- and the application exchanges whole
// PMS messages with it through the mailbox: requests `code | count | InvokeID, CR | ...` in the
// public layouts, confirmations `code | 8000H` with a result word, and the board's indications
// when it ends an association by itself. This is the master's side of one communication
// reference there: the same interface as the client over the words (parameter_client.hpp), so
// that a driver runs over either.
//
// Sans-I/O: a submission leaves its request message in an outgoing slot; the carrier (the DDI
// adapter, master/ddi/, once per cycle) sends outgoing() to the board and calls sent(), and hands
// every message of this CR back with receive(). step() runs the request timeout. Nothing here
// allocates, throws, locks or reads a clock.
//
// The rules (the words' client's, where they apply):
// - one request at a time; Read / Write / Get-OV need an association (Initiate);
// - every request ends in one Result: its confirmation (positive, negative, typed Read of the
//   wrong length: type_mismatch), an Abort indication of the board (timeout, link reset,
//   protocol error, aborted by the device or by the stop of the data transfer), the request
//   timeout, or a protocol error;
// - a timeout, a protocol error and abort() end the association and send Abort for the CR, so
//   that the board drops the request and the next Initiate starts afresh;
// - a confirmation for the invoke ID of the request that ended last (one that came too late) is
//   ignored; one for any other invoke ID, or of another service, while a request waits, ends that
//   request as a protocol error.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/base/error.hpp"
#include "ibs/pcp/parameter_client.hpp"

namespace ibs::pcp {

// The board's own message codes for PCP (ibs's virtual board, ddi/include/ibs/ddi.h: the same
// values as S_PCP_ABORT_IND and S_PCP_INFO_REPORT_IND).
namespace mailbox {
inline constexpr std::uint16_t kAbortIndication = 0x408D;              // [CR][reason]
inline constexpr std::uint16_t kInformationReportIndication = 0x4085;  // [CR][index][length][data]
// Why the board ended an association (the Abort indication's reason).
enum class AbortCause : std::uint16_t {
  timeout = 1,           // the board's own request timeout
  link_reset = 2,        // the channel was reset (the device restarted, its link timed out)
  protocol = 3,          // the device broke the protocol
  by_device = 4,         // the device sent Abort
  transfer_stopped = 5,  // Stop_Data_Transfer
};
// The communication reference a board message is for: the low byte of its first parameter for a
// PCP confirmation or one of the indications above; nullopt for any other message (a firmware
// service's confirmation).
std::optional<std::uint8_t> communication_reference(std::span<const Word> message);
}  // namespace mailbox

struct MailboxConfig {
  // The board's communication reference of the device: 2, 3, ... for the PCP devices in ring
  // order (docs/ddi.md).
  std::uint8_t communication_reference = 2;
  std::uint16_t password = 0;
  std::uint16_t access_groups = 0;
  Duration request_timeout = 500ms;  // submit -> confirmation, unless a request says otherwise
};

struct MailboxStats {
  std::uint32_t requests = 0;
  std::uint32_t confirmations = 0;
  std::uint32_t timeouts = 0;
  std::uint32_t abort_indications = 0;
  std::uint32_t late_confirmations = 0;  // for the request that ended last: ignored
  std::uint32_t protocol_errors = 0;     // unexpected confirmations, malformed messages
};

class MailboxClient final : public ParameterClient {
 public:
  // The longest message this client sends: a Write of the largest value it takes.
  static constexpr std::size_t kMaxMessageWords = 5 + (kMaxDataSize + 1) / 2;

  // Refuses a communication reference below 2 (the board's numbering starts there) and a request
  // timeout that is not positive.
  [[nodiscard]] static Error validate(const MailboxConfig& cfg);
  // Of a configuration validate() accepts: otherwise std::invalid_argument (the embedded build
  // aborts).
  explicit MailboxClient(const MailboxConfig& cfg);

  SubmitStatus initiate(Time now, Duration timeout = Duration::zero()) override;
  SubmitStatus read(Time now, ParameterRef p, Duration timeout = Duration::zero()) override;
  SubmitStatus read(Time now, ParameterRef p, DataType expected, Duration timeout = Duration::zero()) override;
  SubmitStatus write(Time now, ParameterRef p, Value v, Duration timeout = Duration::zero()) override;
  SubmitStatus write_bytes(Time now, ParameterRef p, std::span<const std::uint8_t> data, std::uint8_t subindex = 0,
                           Duration timeout = Duration::zero());
  SubmitStatus get_ov(Time now, ParameterRef p, Duration timeout = Duration::zero()) override;
  void abort(Time now) override;
  // The request timeout; the words are not this client's (empty spans, or any: untouched).
  void step(Time now, std::span<const Word> s2m, std::span<Word> m2s) override;

  [[nodiscard]] bool busy() const override { return outstanding_; }
  [[nodiscard]] bool associated() const override { return associated_; }
  [[nodiscard]] const Result* take_result_view() override {
    if (!result_ready_) return nullptr;
    result_ready_ = false;
    return &result_;
  }
  std::optional<InformationReport> take_information_report();

  // The carrier's side. The message to hand to the board now -- an Abort first, then the request
  // -- as big-endian words `code, count, parameters`; empty when there is none.
  [[nodiscard]] std::span<const Word> outgoing() const;
  // outgoing() was handed to the board.
  void sent();
  // A message of the board for this client's CR (mailbox::communication_reference): a
  // confirmation or an indication.
  void receive(Time now, std::span<const Word> message);

  [[nodiscard]] const MailboxConfig& config() const { return cfg_; }
  [[nodiscard]] const MailboxStats& stats() const { return stats_; }

 private:
  SubmitStatus submit(Time now, ServiceCode service, std::uint16_t index, Duration timeout, bool needs_association);
  void complete(Time now, ResultKind kind);
  // Ends the association; an Abort goes to the board when it knows of one or of a request.
  void end_association(bool tell_board);
  void confirmation(Time now, std::span<const Word> m);
  void indication(Time now, std::span<const Word> m);
  void fail_protocol(Time now);

  MailboxConfig cfg_;
  bool associated_ = false;
  std::uint8_t next_invoke_id_ = 0;

  bool outstanding_ = false;
  bool sent_ = false;  // the request left (the board has it)
  ServiceCode request_service_ = ServiceCode::read;
  std::uint8_t request_invoke_id_ = 0;
  std::optional<DataType> expected_type_;
  Time deadline_{};
  std::array<Word, kMaxMessageWords> request_{};
  std::size_t request_words_ = 0;
  // The request that ended last, whose confirmation may still come (and is then ignored).
  std::optional<std::uint8_t> ended_invoke_id_;

  bool abort_pending_ = false;
  std::array<Word, 4> abort_{};

  Result result_{};
  bool result_ready_ = false;
  InformationReport report_{};
  bool report_ready_ = false;
  MailboxStats stats_{};
};

}  // namespace ibs::pcp
