// The CANLust parameter channel (CANLust manual 4.5; public-facts "CANLust", "Parameter channel",
// "String transfer"): what both sides share, the interface a drive implements to be served, and
// the drive's side (ParameterServer).
//
// Request 1101 + address / reply 1321 + address, 8 bytes: parameter number (low, high), mode or
// status, 32-bit data (Intel order), block counter / field index. Every request gets exactly one
// reply (CAL). The server's methods allocate nothing and throw nothing.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "ibs/canlust/data_types.hpp"
#include "ibs/canlust/telegrams.hpp"
#include "ibs/base/time.hpp"

namespace ibs::canlust {

// Modes, byte 2 of a request. They are decimal numbers (public-facts: 05, 02, 04, 08, 11, 16).
inline constexpr std::uint8_t kModeWrite = 2;          // SEL: write a value
inline constexpr std::uint8_t kModeDescribe = 4;       // ENQUIRY_List: one item of the description
inline constexpr std::uint8_t kModeRead = 5;           // ENQ: read a value
inline constexpr std::uint8_t kModeStringWrite = 8;    // SELECT_String
inline constexpr std::uint8_t kModeStringRead = 11;    // ENQUIRY_String (0BH)
inline constexpr std::uint8_t kModeListEnd = 16;       // List_End (10H): closes a string write
std::string_view mode_name(std::uint8_t mode);

// Reply status bits, byte 2 of a reply (4.5; public-facts). 0 = done.
inline constexpr std::uint8_t kStatusOk = 0x00;
inline constexpr std::uint8_t kStatusVacant = 0x01;             // bit 0: not used
inline constexpr std::uint8_t kStatusWatchdog = 0x02;           // bit 1
inline constexpr std::uint8_t kStatusUnknownMode = 0x04;        // bit 2
inline constexpr std::uint8_t kStatusReadNotPermitted = 0x08;   // bit 3
inline constexpr std::uint8_t kStatusRepeat = 0x10;             // bit 4
inline constexpr std::uint8_t kStatusUnknownParameter = 0x20;   // bit 5
inline constexpr std::uint8_t kStatusChangeNotPermitted = 0x40; // bit 6
inline constexpr std::uint8_t kStatusImpermissibleValue = 0x80; // bit 7
// The last reply of a string read carries List_End (16 = 10H) as its status: the same value as
// the "repeat" bit; within a string read after the terminator it means List_End (decision D9).
inline constexpr std::uint8_t kStatusListEnd = kModeListEnd;
// "repeat, impermissible value" (allocates: for reports and tests).
std::string describe_status(std::uint8_t status);

// 32-bit XOR of data bytes 3-6 (as one Intel-order word) over a string's blocks (4.5.x; D8).
constexpr std::uint32_t string_checksum_step(std::uint32_t sum, std::uint32_t block_data) {
  return sum ^ block_data;
}

// A string of at most 99 characters and its terminator (4.1.1: max 100 bytes incl. the 0).
struct FixedString {
  std::array<char, kMaxStringBytes> chars{};
  std::uint8_t length = 0;  // without the terminator

  static FixedString from(std::string_view s);  // truncates to 99 characters
  [[nodiscard]] std::string_view view() const { return {chars.data(), length}; }
  friend bool operator==(const FixedString& a, const FixedString& b) { return a.view() == b.view(); }
};

// ---- What a drive implements --------------------------------------------------------------

// Result of a value access. `status` is 0 or reply status bits; `delay` is the drive's reaction
// time: the reply goes out that long after the request (e.g. 150-SAVE takes a few hundred ms,
// 4.3.3; "a reply is sent only after successful entry of the new value", 4.5).
struct AccessResult {
  std::uint8_t status = kStatusOk;
  Duration delay{};
};
struct ValueResult {
  std::uint8_t status = kStatusOk;
  DataType type = DataType::usign32;  // the parameter's type; `value` must fit it (wire_fits)
  std::uint32_t value = 0;            // the 32-bit image of bytes 3-6 (data_types.hpp)
  Duration delay{};
};
struct StringResult {
  std::uint8_t status = kStatusOk;
  std::uint8_t length = 0;  // characters written to the buffer, without a terminator (<= 99)
  Duration delay{};
};

// The drive side of the parameter channel: called on the frame path; must not allocate or throw.
// `index` is data byte 7 of a single-value request (the index of a field parameter; 0 else).
class ParameterAccess {
 public:
  virtual ~ParameterAccess() = default;
  // Mode 05.
  virtual ValueResult read(std::uint16_t number, std::uint8_t index, Time now) = 0;
  // Mode 02: `value` is bytes 3-6 as received; the drive checks it against its type and range.
  virtual AccessResult write(std::uint16_t number, std::uint8_t index, std::uint32_t value,
                             Time now) = 0;
  // Mode 04: item `item` (byte 7) of the parameter's description; status kStatusListEnd when
  // there is no such item. What the items are is the drive's (decision D10).
  virtual ValueResult describe(std::uint16_t number, std::uint8_t item, Time now) = 0;
  // Mode 11, block 0: the whole string into `out` (99 bytes).
  virtual StringResult read_string(std::uint16_t number, std::span<char> out, Time now) = 0;
  // Mode 08, block 0 (the handshake): may this string be written? Default: yes.
  virtual AccessResult begin_string_write(std::uint16_t number, Time now) {
    (void)number;
    (void)now;
    return {};
  }
  // Mode 16 (List_End) with the right checksum: the whole text, without its terminator.
  virtual AccessResult write_string(std::uint16_t number, std::string_view text, Time now) = 0;
};

// ---- The drive's side ---------------------------------------------------------------------

enum class ServerState : std::uint8_t {
  idle,          // no string transfer open
  string_read,   // 4.5.x "Reading a string": serving blocks 1.. of a fetched string
  string_write,  // 4.5.x "Writing a string": collecting blocks after the block-0 handshake
};
std::string_view to_string(ServerState s);

struct ServerCounters {
  std::uint32_t requests = 0;
  std::uint32_t replies = 0;
  std::uint32_t busy = 0;               // requests while a reply was still pending
  std::uint32_t block_errors = 0;       // wrong block counter: string machine reset
  std::uint32_t checksum_errors = 0;    // string write closed with a wrong checksum
  std::uint32_t overlong_strings = 0;   // string write of more than 100 bytes
};

struct ParameterServerProbe;

class ParameterServer {
 public:
  explicit ParameterServer(ParameterAccess& drive) : drive_(&drive) {}

  // A request telegram (already decoded) at `now`. Inline for a read (4.5: mode 05) with no reply
  // pending (issue 26): what the general path does for it, without the call; every other
  // request, and a read while a reply is pending, goes the general path.
  void receive(const ParameterTelegram& request, Time now) {
    if (request.code != kModeRead || pending_) {
      receive_general(request, now);
      return;
    }
    ++counters_.requests;
    state_ = ServerState::idle;  // any other request than a string's abandons an open transfer
    const auto v = drive_->read(request.parameter, request.block, now);
    reply(request, v.status, v.status == kStatusOk ? v.value : 0U, now + v.delay);
  }
  // The reply once it is due (at once, or after the drive's delay). One at a time.
  // Into `out`: false when none is due. Inline: a node asks after every request and every
  // step (issue 26: the telegram is not carried out in an optional).
  bool take_reply(Time now, ParameterTelegram& out) {
    if (busy_reply_) {
      out = *busy_reply_;
      busy_reply_.reset();
      ++counters_.replies;
      return true;
    }
    if (pending_ && now >= pending_at_) {
      out = *pending_;
      pending_.reset();
      ++counters_.replies;
      return true;
    }
    return false;
  }
  std::optional<ParameterTelegram> take_reply(Time now) {
    ParameterTelegram t;
    if (!take_reply(now, t)) return std::nullopt;
    return t;
  }
  [[nodiscard]] Time next_deadline() const;
  [[nodiscard]] ServerState state() const { return state_; }
  [[nodiscard]] const ServerCounters& counters() const { return counters_; }
  // Power-on / communication reset: forgets open transfers and pending replies.
  void reset();

 private:
  friend struct ParameterServerProbe;  // tests: the general path (shortcuts_test.cpp)
  void receive_general(const ParameterTelegram& request, Time now);
  void reply(const ParameterTelegram& request, std::uint8_t status, std::uint32_t data, Time at) {
    pending_ = ParameterTelegram{request.parameter, status, data, request.block};
    pending_at_ = at;
  }
  void string_read(const ParameterTelegram& r, Time now);
  void string_write(const ParameterTelegram& r, Time now);
  void list_end(const ParameterTelegram& r, Time now);
  void block_error(const ParameterTelegram& r, Time now);

  ParameterAccess* drive_;
  ServerState state_ = ServerState::idle;
  std::optional<ParameterTelegram> pending_;
  Time pending_at_{};
  std::optional<ParameterTelegram> busy_reply_;
  // The open string transfer.
  std::uint16_t string_parameter_ = 0;
  std::uint8_t next_block_ = 0;
  std::array<char, kMaxStringBytes> buffer_{};
  std::size_t buffer_bytes_ = 0;   // read: length incl. terminator; write: bytes received
  std::uint32_t checksum_ = 0;
  bool overflow_ = false;
  ServerCounters counters_{};
};

}  // namespace ibs::canlust
