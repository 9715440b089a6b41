// PMS messages of PCP 2.0 as they cross the MC6000's parameter channel: big-endian words
// `code | count | InvokeID, CR | parameters...`, count = number of words after the count word
// (message layouts, service codes and error classes: ../shared/notes/public-facts.md, PCP).
// Fields the public layouts do not show (Write's data, Get-OV's description, Identify, Status,
// the KBL inside Initiate, Abort's reason) are this project's and documented in docs/pcp.md.
// Encoding and decoding are allocation-free and usable on the cycle path.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>

#include "ibs/base/words.hpp"
#include "ibs/pcp/data_types.hpp"
#include "ibs/pcp/parameters.hpp"

namespace ibs::pcp {

inline constexpr std::size_t kMaxPduSize = 134;  // INTERBUS manual 4.2.2: the MC6000's KBL, both ways
inline constexpr std::size_t kMinPduSize = 6;    // code, count, InvokeID/CR
inline constexpr std::size_t kMaxDataSize = kMaxPduSize - 10;

// Request codes; a confirmation carries the request code | 8000H (public-facts.md, DDI).
enum class ServiceCode : std::uint16_t {
  read = 0x0081,
  write = 0x0082,
  information_report = 0x0085,  // not in the public list: the next free code below Status
  status = 0x0086,
  identify = 0x0087,
  get_ov = 0x0088,
  initiate = 0x008B,
  abort = 0x088D,  // unconfirmed
};
inline constexpr std::uint16_t kConfirmationBit = 0x8000;
std::string_view to_string(ServiceCode s);
bool is_known_service(std::uint16_t code);

// Error class / code / additional code of a negative confirmation (public-facts.md, PCP errors).
struct PcpError {
  std::uint8_t error_class = 0;
  std::uint8_t error_code = 0;
  std::uint16_t additional_code = 0;
  friend bool operator==(const PcpError&, const PcpError&) = default;
};
std::string to_string(const PcpError& e);

namespace errors {
inline constexpr PcpError kNoAccess{6, 3, 0};
inline constexpr PcpError kInvalidSubindex{6, 5, 0};
inline constexpr PcpError kDataLength{6, 5,
                                      1};  // "data too long / too short"; additional 1 is ours
inline constexpr PcpError kNotAParameter{6, 6, 0};
inline constexpr PcpError kObjectDoesNotExist{6, 7, 0};
inline constexpr PcpError kServiceNotExecutable{8, 0, 0x00};
inline constexpr PcpError kNotExecutableNow{8, 0, 0x20};
inline constexpr PcpError kValueTooHigh{8, 0, 0x31};
inline constexpr PcpError kValueTooLow{8, 0, 0x32};
}  // namespace errors

// The supported-services bytes of a KBL entry (INTERBUS manual 4.2.2): bytes 0..2 client functionality,
// 3..5 server functionality; per byte the three services of the KBL's line. Bit values are ours.
struct ServiceBit {
  std::uint8_t byte = 0;
  std::uint8_t mask = 0;
};
inline constexpr ServiceBit kSvcGetOvLong{0, 0x04};
inline constexpr ServiceBit kSvcPutOv{0, 0x02};
inline constexpr ServiceBit kSvcDomain{0, 0x01};
inline constexpr ServiceBit kSvcProgramInvocation{1, 0x04};
inline constexpr ServiceBit kSvcRead{1, 0x02};
inline constexpr ServiceBit kSvcWrite{1, 0x01};
inline constexpr ServiceBit kSvcInformationReport{2, 0x04};
inline constexpr ServiceBit kSvcVariableList{2, 0x02};
inline constexpr ServiceBit kSvcAlarm{2, 0x01};

struct Services {
  std::array<std::uint8_t, 6> bytes{};

  constexpr Services& client(ServiceBit b) {
    bytes[b.byte] = static_cast<std::uint8_t>(bytes[b.byte] | b.mask);
    return *this;
  }
  constexpr Services& server(ServiceBit b) {
    bytes[b.byte + 3U] = static_cast<std::uint8_t>(bytes[b.byte + 3U] | b.mask);
    return *this;
  }
  [[nodiscard]] constexpr bool has_client(ServiceBit b) const {
    return (bytes[b.byte] & b.mask) != 0;
  }
  [[nodiscard]] constexpr bool has_server(ServiceBit b) const {
    return (bytes[b.byte + 3U] & b.mask) != 0;
  }
  friend bool operator==(const Services&, const Services&) = default;
};

// The PMS part of a communication-links-list entry: the largest PDU this station sends
// (requests as a client, responses as a server) and receives, and its services.
struct Kbl {
  std::uint16_t max_pdu_sending = kMaxPduSize;
  std::uint16_t max_pdu_receiving = kMaxPduSize;
  Services services{};
  friend bool operator==(const Kbl&, const Kbl&) = default;
};

// A parameter server's entry: 134 bytes each way; server for Get-OV long, Read, Write,
// Information Report (the MC6000's of the INTERBUS manual 4.2.2).
inline constexpr Kbl kDefaultServerKbl{kMaxPduSize, kMaxPduSize,
                                Services{}
                                    .server(kSvcGetOvLong)
                                    .server(kSvcRead)
                                    .server(kSvcWrite)
                                    .server(kSvcInformationReport)};
// The master's default entry: uses Get-OV long, Read and Write as a client.
inline constexpr Kbl kDefaultClientKbl{
    kMaxPduSize, kMaxPduSize, Services{}.client(kSvcGetOvLong).client(kSvcRead).client(kSvcWrite)};

enum class KblMismatch : std::uint8_t {
  none,
  client_sends_too_much,  // client's max sending > server's max receiving
  server_sends_too_much,  // server's max sending > client's max receiving
  service_not_supported,  // a client service the server does not serve
  pdu_size_out_of_range,  // a size outside kMinPduSize..kMaxPduSize
};
std::string_view to_string(KblMismatch m);
// The check both sides make at Initiate (docs/pcp.md, "Initiate").
KblMismatch check_kbl(const Kbl& client, const Kbl& server);

enum class AbortReason : std::uint8_t {
  user = 0,           // the client's user asked for it
  not_initiated = 1,  // a request outside an association
  protocol = 2,       // a message that breaks the protocol (wrong size, second request, ...)
  kbl_mismatch = 3,   // the client refused the server's KBL
};
std::string_view to_string(AbortReason r);

template <std::size_t N>
struct FixedBytes {
  std::array<std::uint8_t, N> data{};
  std::size_t size = 0;
  [[nodiscard]] std::span<const std::uint8_t> view() const { return {data.data(), size}; }
  bool assign(std::span<const std::uint8_t> in) {
    if (in.size() > N) return false;
    for (std::size_t i = 0; i < in.size(); ++i) data[i] = in[i];
    size = in.size();
    return true;
  }
  // Back to a fresh (all-zero) one, for one whose bytes past size are zeros (a fresh one after
  // assign(), or one emptied so): zeros over the first size bytes only, by 8-byte stores (the
  // last ends at the array's end), cheaper than a memset call for a value's few bytes.
  void clear_zero_tail() {
    static_assert(N >= 8);
    constexpr std::uint64_t kZero = 0;
    for (std::size_t i = 0; i < size; i += 8) {
      std::memcpy(data.data() + (i < N - 8 ? i : N - 8), &kZero, sizeof kZero);
    }
    size = 0;
  }
  friend bool operator==(const FixedBytes& a, const FixedBytes& b) {
    if (a.size != b.size) return false;
    for (std::size_t i = 0; i < a.size; ++i) {
      if (a.data[i] != b.data[i]) return false;
    }
    return true;
  }
};
using DataBytes = FixedBytes<kMaxDataSize>;

template <std::size_t N>
struct FixedString {
  std::array<char, N> data{};
  std::size_t size = 0;
  [[nodiscard]] std::string_view view() const { return {data.data(), size}; }
  static FixedString from(std::string_view s) {
    FixedString f;
    f.size = s.size() < N ? s.size() : N;
    for (std::size_t i = 0; i < f.size; ++i) f.data[i] = s[i];
    return f;
  }
  friend bool operator==(const FixedString& a, const FixedString& b) {
    return a.view() == b.view();
  }
};
using Name = FixedString<16>;

// Object description returned by Get-OV long (layout in docs/pcp.md): index, object code
// (7 = simple variable), data type, length, category, attributes, min, max, default, name.
struct ObjectDescription {
  std::uint16_t index = 0;
  std::uint8_t object_code = 7;
  DataType type = DataType::usign16;
  std::uint8_t length = 0;
  Category category = Category::ram_control;
  std::uint16_t attributes = 0;
  std::int32_t min = 0;  // signed_raw numbers, FLOAT_IEEE as bit pattern
  std::int32_t max = 0;
  std::int32_t default_value = 0;
  FixedString<5> name;
  friend bool operator==(const ObjectDescription&, const ObjectDescription&) = default;
};
inline constexpr std::size_t kObjectDescriptionSize = 26;
ObjectDescription describe(const ParameterInfo& p);
std::size_t encode(const ObjectDescription& d, std::span<std::uint8_t> out);
bool decode(std::span<const std::uint8_t> in, ObjectDescription& d);

struct IdentifyInfo {
  Name vendor;
  Name model;
  Name revision;
  friend bool operator==(const IdentifyInfo&, const IdentifyInfo&) = default;
};

// Status: logical status (0 ready for communication), physical status (0 operational,
// 1 partially operational = device fault), local detail (low byte: 85-SERR as is, not cleared).
struct StatusInfo {
  std::uint8_t logical = 0;
  std::uint8_t physical = 0;
  std::uint16_t local_detail = 0;
  friend bool operator==(const StatusInfo&, const StatusInfo&) = default;
};

// One encoded message, at most kMaxPduSize bytes.
struct Pdu {
  std::array<std::uint8_t, kMaxPduSize> bytes{};
  std::size_t size = 0;
  [[nodiscard]] std::span<const std::uint8_t> view() const { return {bytes.data(), size}; }
};

// What a client sends: a request, or Abort.
struct RequestPdu {
  ServiceCode service = ServiceCode::read;
  std::uint8_t invoke_id = 0;
  std::uint8_t cr = 0;
  std::uint16_t index = 0;     // read, write, get_ov
  std::uint8_t subindex = 0;   // read, write
  DataBytes data;              // write
  std::uint16_t password = 0;  // initiate
  std::uint16_t access_groups = 0;
  Kbl kbl{};                               // initiate: the client's entry
  AbortReason reason = AbortReason::user;  // abort
};

// What a server sends: a confirmation, Abort, or an Information Report.
struct ResponsePdu {
  enum class Kind : std::uint8_t { confirmation, abort, information_report };
  Kind kind = Kind::confirmation;
  ServiceCode service = ServiceCode::read;
  std::uint8_t invoke_id = 0;
  std::uint8_t cr = 0;
  bool positive = true;
  PcpError error{};
  DataBytes data;  // read: the value; get_ov: the description; information report: the value
  std::uint16_t index = 0;    // information report
  std::uint8_t subindex = 0;  // information report
  Kbl kbl{};                  // initiate (positive and negative): the server's entry
  StatusInfo status{};
  IdentifyInfo identity{};
  AbortReason reason = AbortReason::user;
};

enum class PduError : std::uint8_t {
  none,
  too_short,        // fewer than kMinPduSize bytes
  too_long,         // more than kMaxPduSize bytes
  count_mismatch,   // size != 4 + 2 * count
  unknown_service,  // a code this side does not know (the decoders say which side)
  malformed,        // a field that does not fit the service's layout
};
std::string_view to_string(PduError e);

// The three header words; `error` is too_short / too_long / count_mismatch or none.
struct PduHeader {
  std::uint16_t code = 0;
  std::uint16_t count = 0;
  std::uint8_t invoke_id = 0;
  std::uint8_t cr = 0;
};
PduError decode_header(std::span<const std::uint8_t> in, PduHeader& h);

// Encoders return false when the message does not fit (data too long for kMaxPduSize).
bool encode(const RequestPdu& r, Pdu& out);
bool encode(const ResponsePdu& r, Pdu& out);
PduError decode(std::span<const std::uint8_t> in, RequestPdu& r);
PduError decode(std::span<const std::uint8_t> in, ResponsePdu& r);

// A multi-line, human-readable reading of a message, for logs and trace remarks (allocates).
std::string explain_pdu(std::span<const std::uint8_t> pdu);

}  // namespace ibs::pcp
