// The host side of LUSTBUS (LUSTBUS manual): a sans-I/O client. Requests are queued and run one
// transaction at a time; every telegram is sent as EOT + telegram and every sequence ends with
// EOT (3); a response timeout runs from the host's last character to the first answer character
// and an inter-character timeout between answer characters; after a NAK on a SELECT the host
// reads 85-SIOF/SERR at once and reports the cause (6, 6.2, 9.2); retries only where the manual
// allows them (LB-D5). Also: the network scan of 5.2, broadcast (4.2), and the procedures a
// device may offer -- a download through a handshake parameter (11.4), texts indexed through a
// parameter (11.3), block transfers over one CODE (11.6) -- as single requests, each run as the
// device's description (DeviceProcedures, from its wing) says. The baud scan of 5.1 is `BaudScan`.
//
// The caller moves bytes and time:
//   host.step(now);                       // timeouts; starts the next telegram
//   auto out = host.take_output();        // send these; then, when the last one is on the line:
//   host.output_done(now);
//   host.receive(bytes, now);             // the characters from the line (or one at a time)
//   host.next_deadline();                 // when step() next has something to do
// submit(), step(), take_output(), output_done() and receive() allocate nothing and throw
// nothing; the queue and the ring of finished outcomes are allocated by the constructor.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "ibs/base/time.hpp"
#include "ibs/lustbus/telegram.hpp"
#include "ibs/lustbus/timing.hpp"

namespace ibs::lustbus {

struct HostConfig {
  // 10: reaction up to 60 ms, +120 ms for a VF1000 EEPROM write (exception 4).
  Duration response_timeout = 250ms;
  // Silence between answer characters that ends an answer as incomplete (and, after a broken
  // answer, tells that the line is quiet before the EOT).
  Duration inter_char_timeout = 20ms;
  // One exchange ends, however the line behaves, by its response timeout and then the longest
  // telegram with every gap at the inter-character limit: a device that keeps sending (each
  // character restarting that timer) cannot hold the host (AnswerError::line_busy, LB-D24).
  [[nodiscard]] Duration exchange_limit(Duration response) const {
    return response + static_cast<Duration::rep>(kMaxTelegramLength) * inter_char_timeout;
  }
  // 10, step 4: the host's reaction before its EOT (the tables use 2 ms).
  Duration turnaround = 0ms;
  // ENQUIRY repeated after no answer or a broken one; never for 85-SIOF, whose read clears it.
  std::uint8_t enquiry_retries = 2;
  // SELECT repeated when the 85-SIOF read after its NAK allows it (select_may_be_repeated).
  std::uint8_t select_retries = 3;
  // 10.2.2: before a SELECT to an EEPROM parameter of a device that saves in the background (the
  // servo, 3), the host waits until the device's last EEPROM save is done: "memory time =
  // parameter data width · 3 · 5 ms", and "wait time = memory time - telegram duration" of the
  // sequence that wrote it, "if ... positive" (Request::eeprom_width says which SELECTs are such).
  Duration eeprom_write_time = 5ms;
  // 9.2's "EEPROM busy: wait (> 60 ms) and repeat telegram": only for a device slower than 10.2.2
  // (or a SELECT its caller did not say was an EEPROM one).
  Duration eeprom_busy_wait = 70ms;
  Duration scan_response_timeout = 100ms;
  Duration download_poll_interval = 100ms;
  Duration download_timeout = 10s;  // 11.4, step 4
  std::size_t queue_capacity = 16;
  std::size_t completed_capacity = 64;
};

enum class RequestKind : std::uint8_t {
  enquiry,         // 6.1
  select,          // 6.2
  broadcast,       // SELECT at 31 (4.2): taken by every device, never answered
  scan,            // 5.2: ENQUIRY 00091 at 1..30, then 20091 to tell servos from inverters
  download,        // 11.4: handshake = start, the records, handshake = end, poll the handshake
  indexed_text,    // 11.3: SELECT the index parameter = index, ENQUIRY the parameter's text CODE
  block_transfer,  // 11.6: SELECT the CODE = user data, ENQUIRY it when the data asks an answer
};
std::string_view to_string(RequestKind k);

// One parameter of a download (11.4, step 2).
struct Assignment {
  Code code{};
  Value value{};
};

// ---- The procedures of the LUSTBUS manual 11 a device may offer ------------------------------------------
// The host runs them; the parameter or CODE each runs through, its values and its limits are the
// device's, described by its wing (docs/lustbus.md, "Procedures"). A request keeps a pointer to
// the description: it must live until the request is done (the wings' are static).

// 11.4: a dataset download through one handshake parameter. SELECT it = `start`, one SELECT per
// record, SELECT it = `end`; then ENQUIRY it every HostConfig::download_poll_interval until it
// reads 0 (taken), a positive number (the first invalid parameter, download_rejected) or
// HostConfig::download_timeout runs out; a negative value: still testing and saving. The
// handshake's values are INTEGER16, in the family's VALUE format.
struct DownloadProcedure {
  Family family = Family::enhanced;
  std::uint16_t parameter = 0;  // the handshake parameter; its CODE by parameter_code()
  std::int16_t start = 0;
  std::int16_t end = 0;
};

// 11.3: a text indexed through a parameter. SELECT `index_parameter` = the value whose text is
// wanted (USIGN, the family's format), then ENQUIRY the text CODE of the parameter the value
// belongs to (text_code()).
struct IndexedTextProcedure {
  Family family = Family::enhanced;
  std::uint16_t index_parameter = 0;
};

// 11.6: a block transfer over one CODE. With user data: SELECT `code` = the data, then, when the
// data asks for an answer, ENQUIRY `code`, whose answer is the outcome's value; without: the
// ENQUIRY alone (the next block of a multiblock answer). After a NAK: SELECT `code` =
// `error_read` and ENQUIRY, whose answer is the error (the outcome is `nak`).
struct BlockTransferProcedure {
  Code code{};
  std::size_t max_user_data = 0;
  Value error_read{};
  // What the first character of the user data makes the telegram: nullopt, one the device cannot
  // take (submit() refuses it); otherwise whether an answer is to be fetched with the ENQUIRY.
  std::optional<bool> (*asks_answer)(char first) = nullptr;
};

// The procedures one device offers (none: an empty optional).
struct DeviceProcedures {
  std::optional<DownloadProcedure> download;
  std::optional<IndexedTextProcedure> indexed_text;
  std::optional<BlockTransferProcedure> block_transfer;
};

// The CODE an IndexedTextProcedure asks the text of `parameter` by: 6 1 ppp of 2.4.2 in the
// enhanced family; nullopt where the family's CODEs carry no texts or `parameter` is above 999.
std::optional<Code> text_code(Family f, unsigned parameter);

struct Request {
  RequestKind kind = RequestKind::enquiry;
  Address address = 0;
  Code code{};
  Value value{};
  // Overrides HostConfig::response_timeout (e.g. 10 s for PROG = 1, 10 exception 1).
  std::optional<Duration> response_timeout;
  // select / broadcast: the data width in bytes of the EEPROM parameter it writes on a device
  // that saves in the background after its ACK (the servo: LUSTBUS manual 3, 10.2.2); 0 for a RAM
  // parameter or a device that answers only once its EEPROM is written (the inverter, 10.2.1).
  // The host waits 10.2.2's wait time before such a SELECT (HostConfig::eeprom_write_time).
  std::uint8_t eeprom_width = 0;
  // download: the records, kept alive by the caller until the request is done.
  std::span<const Assignment> records;
  // indexed_text: the parameter and the value whose text is wanted.
  // block_transfer: `value` holds the user data (empty: ENQUIRY only).
  std::uint16_t parameter = 0;
  std::uint32_t text_index = 0;
  // block_transfer: user data the VALUE cannot hold (submit() answers invalid_request).
  bool unfit = false;
  // The description of the procedure the request runs (see DownloadProcedure ff.).
  const DownloadProcedure* download = nullptr;
  const IndexedTextProcedure* indexed_text = nullptr;
  const BlockTransferProcedure* block_transfer = nullptr;
};
// The CODE a host asks a parameter's value by or, with `description`, its description: on a
// VF1000 S0DPP with device digit 1, specifier 0 or 1 (2.4.1, 11.1); on an MC6000 2 0 ppp or
// 3 0 ppp (2.4.2, 11.2). nullopt for a number the family's CODEs cannot carry (VF1000 above 99,
// MC6000 above 999).
std::optional<Code> parameter_code(Family f, unsigned parameter, bool description = false);
// What a device of the family is, as a scan tells them apart (5.2): "inverter" (the SMARTDRIVE
// VF1000) or "servo" (the MASTERCONTROL MC6000/7000).
std::string_view device_kind(Family f);

Request enquiry(Address a, const Code& c);
Request select(Address a, const Code& c, const Value& v);
Request broadcast(const Code& c, const Value& v);
Request network_scan();
// 11.4 at device `a` as `p` describes it (`p` and `records` kept alive until the request is done).
Request download(const DownloadProcedure& p, Address a, std::span<const Assignment> records);
// 11.3: the text of value `index` of `parameter`.
Request indexed_text_request(const IndexedTextProcedure& p, Address a, std::uint16_t parameter,
                             std::uint32_t index);
// 11.6: one block exchange. With `user_data` (at most p.max_user_data characters, its first one
// accepted by p.asks_answer): SELECT; when the data asks for an answer, then the ENQUIRY whose
// answer is the outcome's `value`. Without: the ENQUIRY alone (the next block of a multiblock
// answer). A NAK is followed by the error read (p.error_read): the outcome is `nak` with the
// error answer in `value` (empty when that read failed too). No telegram of it is repeated: the
// ENQUIRY moves on to the next block, and a repeated SELECT would be a second command.
Request block_transfer_request(const BlockTransferProcedure& p, Address a,
                               std::string_view user_data);

enum class OutcomeKind : std::uint8_t {
  value,              // text answer: `value`
  acknowledged,       // ACK
  sent,               // broadcast sent
  nak,                // NAK; for a SELECT `siof` holds the 85 read after it (nullopt: it failed)
  no_answer,          // nothing within the response timeout, after the retries allowed
  bad_answer,         // an answer that failed the checks (`answer_error`); after a SELECT,
                      // 85 is read too (`siof`), since the device may have refused it
  scan,               // `scan`
  downloaded,         // 11.4: SLOAD went to 0
  download_refused,   // a SELECT of the download failed: `failed_step`, `siof`, `answer_error`
  download_rejected,  // 11.4: SLOAD > 0 = `rejected_parameter`, the first invalid one
  download_timeout,   // SLOAD did not reach 0 within the timeout
  aborted,            // restart()
};
std::string_view to_string(OutcomeKind k);

struct ScanEntry {
  Address address = 0;
  std::optional<Family> family;  // nullopt: the 20091 probe got no clear answer
  std::uint32_t type = 0;        // 91-TYPE, its VALUE read as hex (either family's format)
};
struct ScanResult {
  std::array<ScanEntry, kLastDeviceAddress> devices{};
  std::uint8_t count = 0;
  [[nodiscard]] std::span<const ScanEntry> found() const { return {devices.data(), count}; }
};

inline constexpr std::int32_t kDownloadStartStep = -1;

struct Outcome {
  OutcomeKind kind = OutcomeKind::aborted;
  Value value{};
  AnswerError answer_error = AnswerError::none;
  std::optional<std::uint8_t> siof;
  std::uint8_t attempts = 0;  // telegrams of the request's own (last) step
  // 10.2.2: how long the host waited before the SELECT for the device's EEPROM save.
  Duration eeprom_wait{};
  ScanResult scan{};
  std::int32_t failed_step = 0;  // download: kDownloadStartStep, 0..n-1 a record, n the end
  std::uint32_t rejected_parameter = 0;
  Time started{};
  Time finished{};
};
// "nak, 85-SIOF 80H: invalid value" (allocates: for reports).
std::string describe(const Outcome& o);

using RequestId = std::uint32_t;
enum class SubmitError : std::uint8_t { none, queue_full, invalid_address, invalid_request };
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

enum class HostState : std::uint8_t {
  idle,        // nothing to do
  pausing,     // waiting before a repetition or a poll (9.2, 11.4)
  sending,     // telegram handed out, not yet on the line
  awaiting,    // response timeout running
  receiving,   // answer characters arriving
  draining,    // a broken answer: waiting for the line to go quiet
  turnaround,  // answer complete; EOT after the host's reaction time
  closing,     // EOT handed out
};
std::string_view to_string(HostState s);

class Host {
 public:
  explicit Host(const HostConfig& config = {});

  Submitted submit(const Request& r);
  void step(Time now);
  std::span<const std::uint8_t> take_output();
  void output_done(Time now);
  void receive(std::uint8_t b, Time now);
  // Characters that arrived together at `now`: the same as receive(b, now) for each in order.
  void receive(std::span<const std::uint8_t> bytes, Time now);
  // When step() next has something to do; Time::max() when nothing.
  [[nodiscard]] Time next_deadline() const;
  [[nodiscard]] bool output_pending() const { return out_size_ > 0; }

  [[nodiscard]] Poll poll(RequestId id) const;
  [[nodiscard]] const Outcome* outcome(RequestId id) const;
  [[nodiscard]] HostState state() const { return state_; }
  [[nodiscard]] bool idle() const { return state_ == HostState::idle && queued_ == 0; }
  [[nodiscard]] const HostConfig& config() const { return config_; }

  // Aborts the active and queued requests (outcome aborted) and sends an EOT.
  void restart(Time now);

 private:
  enum class Phase : std::uint8_t {
    main,                 // the request's own telegram
    siof_read,            // ENQUIRY 00085 after a NAK / broken answer on a SELECT
    scan_type,            // ENQUIRY 00091 at scan_address_
    scan_probe,           // ENQUIRY 20091 at scan_address_
    dl_start,             // SELECT handshake = start
    dl_record,            // SELECT records[record_]
    dl_end,               // SELECT handshake = end
    dl_poll,              // ENQUIRY handshake
    text_select,          // SELECT index parameter = index
    text_enquiry,         // ENQUIRY the text CODE
    block_select,         // SELECT CODE = user data
    block_enquiry,        // ENQUIRY CODE
    block_error_select,   // SELECT CODE = error read after a NAK
    block_error_enquiry,  // ENQUIRY CODE: the error
  };
  struct Tx {
    Address address = 0;
    Code code{};
    Value value{};
    bool enquiry = true;
    Duration timeout{};
  };
  struct Slot {
    RequestId id = 0;
    Request request{};
  };
  struct Finished {
    RequestId id = 0;
    Outcome outcome{};
  };

  void start_job(Time now);
  void send(const Tx& tx, Time now);
  void send_later(const Tx& tx, Time at);
  void transmit_tx(Time now);
  void start_eot(Time now);
  void tx_done(Time now);
  void on_select_like_ack(Time now);
  void on_select_like_failure(OutcomeKind k, Time now);
  void select_phase(Phase p, const Code& c, const Value& v, Time now);
  // 10.2.2: the time the device at `a` is done saving its EEPROM, and its record after an
  // acknowledged (or broadcast) EEPROM SELECT of the active request.
  [[nodiscard]] Time eeprom_free_at(Address a) const;
  // send(tx), after 10.2.2's wait when `own_step` is the request's own EEPROM SELECT.
  void send_select(const Tx& tx, bool own_step, Time now);
  void note_eeprom_save();
  void enquiry_phase(Phase p, Address a, const Code& c, Duration timeout, Time now);
  void next_scan_address(Time now);
  void finish(OutcomeKind k, Time now);
  void finish_unanswered(Time now);
  void read_block_error(Time now);
  [[nodiscard]] Code handshake_code() const;
  Finished& slot_of(RequestId id) { return done_[(id - 1) % done_.size()]; }
  [[nodiscard]] const Request& request() const { return job_->request; }
  [[nodiscard]] Duration timeout_of(const Request& r) const;

  HostConfig config_;
  // Ring of capacity + 1: the active request keeps its slot (just behind head_) until it ends.
  std::vector<Slot> queue_;
  std::size_t capacity_ = 0;
  std::size_t head_ = 0;
  std::size_t queued_ = 0;
  // Ring of finished outcomes. Requests end in submission order, so request id N ends in slot
  // (N - 1) % size; the active one is written in place there.
  std::vector<Finished> done_;
  RequestId next_id_ = 1;

  HostState state_ = HostState::idle;
  bool active_ = false;
  const Slot* job_ = nullptr;
  Outcome* out_ = nullptr;
  Phase phase_ = Phase::main;
  Phase select_return_ = Phase::main;  // the SELECT step a siof_read belongs to
  Tx tx_{};
  Tx select_tx_{};  // the SELECT to repeat
  std::uint8_t tx_attempts_ = 0;
  std::uint8_t select_attempts_ = 0;
  OutcomeKind select_failure_ = OutcomeKind::nak;
  AnswerError select_error_ = AnswerError::none;
  Address scan_address_ = 0;
  std::size_t record_ = 0;
  Time poll_started_{};

  AnswerDecoder decoder_{};
  AnswerKind answer_kind_ = AnswerKind::none;
  AnswerError answer_error_ = AnswerError::none;

  Frame out_frame_{};
  std::uint8_t out_size_ = 0;     // bytes handed out by take_output() still to be confirmed
  bool out_taken_ = false;
  Time deadline_ = Time::max();
  Time exchange_ends_ = Time::max();  // the overall deadline of the exchange on the line
  Time tx_started_{};                 // when the telegram of the exchange was handed out
  // 10.2.2: when each address's last background EEPROM save is done (0 and 31: every device's).
  std::array<Time, kAddressBroadcast + 1> eeprom_free_{};
  Time last_now_{};
};

// 5.1: stand-alone start at address 0, trying the factory rate first and then every other.
// The caller sets its line to current(), runs request() through a Host, and report()s the
// outcome; an answer stops the scan.
class BaudScan {
 public:
  explicit BaudScan(std::span<const std::uint32_t> rates = kBaudScanOrder);
  // The rate to try now; nullopt once finished.
  [[nodiscard]] std::optional<std::uint32_t> current() const;
  [[nodiscard]] Request request() const;  // ENQUIRY 00091 at address 0
  void report(const Outcome& o);
  [[nodiscard]] std::optional<std::uint32_t> found() const { return found_; }
  [[nodiscard]] bool finished() const { return found_.has_value() || next_ >= rates_.size(); }
  [[nodiscard]] std::size_t attempts() const { return next_ + (found_ ? 1U : 0U); }

 private:
  std::span<const std::uint32_t> rates_;
  std::size_t next_ = 0;
  std::optional<std::uint32_t> found_;
};

}  // namespace ibs::lustbus
