#include "ibs/pcp/pdu.hpp"

#include <cstdio>
#include <memory>
#include <type_traits>

namespace ibs::pcp {

// The decoders build their result anew in place (std::construct_at over the caller's object):
// right for types whose old value needs no destruction.
static_assert(std::is_trivially_destructible_v<RequestPdu>);
static_assert(std::is_trivially_destructible_v<ResponsePdu>);

std::string_view to_string(ServiceCode s) {
  switch (s) {
    case ServiceCode::read:
      return "Read";
    case ServiceCode::write:
      return "Write";
    case ServiceCode::information_report:
      return "Information-Report";
    case ServiceCode::status:
      return "Status";
    case ServiceCode::identify:
      return "Identify";
    case ServiceCode::get_ov:
      return "Get-OV";
    case ServiceCode::initiate:
      return "Initiate";
    case ServiceCode::abort:
      return "Abort";
  }
  return "?";
}

bool is_known_service(std::uint16_t code) {
  switch (static_cast<ServiceCode>(code)) {
    case ServiceCode::read:
    case ServiceCode::write:
    case ServiceCode::information_report:
    case ServiceCode::status:
    case ServiceCode::identify:
    case ServiceCode::get_ov:
    case ServiceCode::initiate:
    case ServiceCode::abort:
      return true;
  }
  return false;
}

std::string to_string(const PcpError& e) {
  std::string what = "?";
  if (e == errors::kNoAccess) what = "no access";
  if (e == errors::kInvalidSubindex) what = "invalid subindex";
  if (e == errors::kDataLength) what = "data too long or too short";
  if (e == errors::kNotAParameter) what = "object is not a parameter";
  if (e == errors::kObjectDoesNotExist) what = "object does not exist";
  if (e == errors::kServiceNotExecutable) what = "service cannot be executed";
  if (e == errors::kNotExecutableNow) what = "not executable now";
  if (e == errors::kValueTooHigh) what = "value too high";
  if (e == errors::kValueTooLow) what = "value too low";
  char buf[64];
  std::snprintf(buf, sizeof buf, "class %u code %u additional %02XH (", e.error_class, e.error_code,
                e.additional_code);
  return buf + what + ")";
}

std::string_view to_string(KblMismatch m) {
  switch (m) {
    case KblMismatch::none:
      return "compatible";
    case KblMismatch::client_sends_too_much:
      return "client's max PDU sending exceeds server's receiving";
    case KblMismatch::server_sends_too_much:
      return "server's max PDU sending exceeds client's receiving";
    case KblMismatch::service_not_supported:
      return "a client service the server does not serve";
    case KblMismatch::pdu_size_out_of_range:
      return "a max PDU size outside 6..134 bytes";
  }
  return "?";
}

KblMismatch check_kbl(const Kbl& client, const Kbl& server) {
  for (const std::uint16_t s : {client.max_pdu_sending, client.max_pdu_receiving,
                                server.max_pdu_sending, server.max_pdu_receiving}) {
    if (s < kMinPduSize || s > kMaxPduSize) return KblMismatch::pdu_size_out_of_range;
  }
  if (client.max_pdu_sending > server.max_pdu_receiving) return KblMismatch::client_sends_too_much;
  if (server.max_pdu_sending > client.max_pdu_receiving) return KblMismatch::server_sends_too_much;
  for (std::size_t i = 0; i < 3; ++i) {
    if ((client.services.bytes[i] & ~server.services.bytes[i + 3U]) != 0) {
      return KblMismatch::service_not_supported;
    }
  }
  return KblMismatch::none;
}

std::string_view to_string(AbortReason r) {
  switch (r) {
    case AbortReason::user:
      return "user";
    case AbortReason::not_initiated:
      return "not initiated";
    case AbortReason::protocol:
      return "protocol violation";
    case AbortReason::kbl_mismatch:
      return "KBL mismatch";
  }
  return "?";
}

std::string_view to_string(PduError e) {
  switch (e) {
    case PduError::none:
      return "none";
    case PduError::too_short:
      return "shorter than 6 bytes";
    case PduError::too_long:
      return "longer than 134 bytes";
    case PduError::count_mismatch:
      return "size does not match the count word";
    case PduError::unknown_service:
      return "unknown service code";
    case PduError::malformed:
      return "fields do not fit the service";
  }
  return "?";
}

namespace {

class Writer {
 public:
  explicit Writer(Pdu& p) : p_(p) { p_.size = 0; }
  void word(std::uint16_t w) {
    byte(high_byte(w));
    byte(low_byte(w));
  }
  void byte(std::uint8_t b) {
    if (p_.size < p_.bytes.size()) {
      p_.bytes[p_.size] = b;
      ++p_.size;
    } else {
      overflow_ = true;
    }
  }
  void bytes(std::span<const std::uint8_t> b) {
    for (const std::uint8_t x : b) byte(x);
  }
  void pad() {
    if (p_.size % 2 != 0) byte(0);
  }
  // Writes the count word (number of words after it) and reports whether everything fitted.
  bool finish() {
    pad();
    if (overflow_ || p_.size < 4) return false;
    const auto count = static_cast<std::uint16_t>((p_.size - 4U) / 2U);
    p_.bytes[2] = high_byte(count);
    p_.bytes[3] = low_byte(count);
    return true;
  }

 private:
  Pdu& p_;
  bool overflow_ = false;
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> in) : in_(in) {}
  bool word(std::uint16_t& w) {
    std::uint8_t h = 0;
    std::uint8_t l = 0;
    if (!byte(h) || !byte(l)) return false;
    w = make_word(h, l);
    return true;
  }
  bool byte(std::uint8_t& b) {
    if (pos_ >= in_.size()) return false;
    b = in_[pos_];
    ++pos_;
    return true;
  }
  bool bytes(std::size_t n, std::span<const std::uint8_t>& out) {
    if (in_.size() - pos_ < n) return false;
    out = in_.subspan(pos_, n);
    pos_ += n;
    return true;
  }
  // True when only a padding byte of zero (or nothing) is left.
  [[nodiscard]] bool at_end_padded() const {
    const std::size_t left = in_.size() - pos_;
    return left == 0 || (left == 1 && in_[pos_] == 0);
  }
  [[nodiscard]] std::size_t pos() const { return pos_; }

 private:
  std::span<const std::uint8_t> in_;
  std::size_t pos_ = 0;
};

void write_header(Writer& w, std::uint16_t code, std::uint8_t invoke_id, std::uint8_t cr) {
  w.word(code);
  w.word(0);  // count, filled in by finish()
  w.word(make_word(invoke_id, cr));
}

void write_kbl(Writer& w, const Kbl& k) {
  w.word(k.max_pdu_sending);
  w.word(k.max_pdu_receiving);
  for (std::size_t i = 0; i < 6; i += 2)
    w.word(make_word(k.services.bytes[i], k.services.bytes[i + 1]));
}

bool read_kbl(Reader& r, Kbl& k) {
  std::uint16_t w = 0;
  if (!r.word(k.max_pdu_sending) || !r.word(k.max_pdu_receiving)) return false;
  for (std::size_t i = 0; i < 6; i += 2) {
    if (!r.word(w)) return false;
    k.services.bytes[i] = high_byte(w);
    k.services.bytes[i + 1] = low_byte(w);
  }
  return true;
}

void write_name(Writer& w, const Name& n) {
  w.byte(static_cast<std::uint8_t>(n.size));
  for (std::size_t i = 0; i < n.size; ++i) w.byte(static_cast<std::uint8_t>(n.data[i]));
}

bool read_name(Reader& r, Name& n) {
  std::uint8_t len = 0;
  if (!r.byte(len) || len > n.data.size()) return false;
  n.size = len;
  for (std::size_t i = 0; i < len; ++i) {
    std::uint8_t c = 0;
    if (!r.byte(c)) return false;
    n.data[i] = static_cast<char>(c);
  }
  return true;
}

// Data preceded by its length: `Subindex<<8 | length` (write, information report) or a whole
// length word (read confirmation, get-ov confirmation).
bool read_data(Reader& r, std::size_t len, DataBytes& d) {
  std::span<const std::uint8_t> b;
  if (len > kMaxDataSize || !r.bytes(len, b)) return false;
  d.assign(b);
  return r.at_end_padded();
}

}  // namespace

PduError decode_header(std::span<const std::uint8_t> in, PduHeader& h) {
  if (in.size() < kMinPduSize) return PduError::too_short;
  if (in.size() > kMaxPduSize) return PduError::too_long;
  h.code = make_word(in[0], in[1]);
  h.count = make_word(in[2], in[3]);
  h.invoke_id = in[4];
  h.cr = in[5];
  if (in.size() != 4U + 2U * h.count) return PduError::count_mismatch;
  return PduError::none;
}

bool encode(const RequestPdu& r, Pdu& out) {
  Writer w(out);
  const std::uint8_t iid = r.service == ServiceCode::abort ? 0 : r.invoke_id;
  write_header(w, static_cast<std::uint16_t>(r.service), iid, r.cr);
  switch (r.service) {
    case ServiceCode::read:
      w.word(r.index);
      w.word(make_word(r.subindex, 0));
      break;
    case ServiceCode::write:
      if (r.data.size > 0xFF) return false;
      w.word(r.index);
      w.word(make_word(r.subindex, static_cast<std::uint8_t>(r.data.size)));
      w.bytes(r.data.view());
      break;
    case ServiceCode::get_ov:
      w.word(r.index);
      break;
    case ServiceCode::identify:
    case ServiceCode::status:
      break;
    case ServiceCode::initiate:
      w.word(r.password);
      w.word(r.access_groups);
      write_kbl(w, r.kbl);
      break;
    case ServiceCode::abort:
      w.word(static_cast<std::uint16_t>(r.reason));
      break;
    case ServiceCode::information_report:
      return false;  // a server's message
  }
  return w.finish();
}

PduError decode(std::span<const std::uint8_t> in, RequestPdu& r) {
  PduHeader h;
  if (const PduError e = decode_header(in, h); e != PduError::none) return e;
  if (!is_known_service(h.code) ||
      h.code == static_cast<std::uint16_t>(ServiceCode::information_report)) {
    return PduError::unknown_service;
  }
  std::construct_at(&r);  // r = RequestPdu{}, built in place rather than copied from a temporary
  r.service = static_cast<ServiceCode>(h.code);
  r.invoke_id = h.invoke_id;
  r.cr = h.cr;
  Reader rd(in.subspan(6));
  std::uint16_t w = 0;
  switch (r.service) {
    case ServiceCode::read:
      if (h.count != 3 || !rd.word(r.index) || !rd.word(w) || low_byte(w) != 0)
        return PduError::malformed;
      r.subindex = high_byte(w);
      return PduError::none;
    case ServiceCode::write:
      if (!rd.word(r.index) || !rd.word(w)) return PduError::malformed;
      r.subindex = high_byte(w);
      return read_data(rd, low_byte(w), r.data) ? PduError::none : PduError::malformed;
    case ServiceCode::get_ov:
      return h.count == 2 && rd.word(r.index) ? PduError::none : PduError::malformed;
    case ServiceCode::identify:
    case ServiceCode::status:
      return h.count == 1 ? PduError::none : PduError::malformed;
    case ServiceCode::initiate:
      if (h.count != 8 || !rd.word(r.password) || !rd.word(r.access_groups) ||
          !read_kbl(rd, r.kbl)) {
        return PduError::malformed;
      }
      return PduError::none;
    case ServiceCode::abort:
      if (h.count != 2 || !rd.word(w)) return PduError::malformed;
      r.reason = static_cast<AbortReason>(low_byte(w));
      return PduError::none;
    case ServiceCode::information_report:
      break;
  }
  return PduError::unknown_service;
}

bool encode(const ResponsePdu& r, Pdu& out) {
  Writer w(out);
  if (r.kind == ResponsePdu::Kind::abort) {
    write_header(w, static_cast<std::uint16_t>(ServiceCode::abort), 0, r.cr);
    w.word(static_cast<std::uint16_t>(r.reason));
    return w.finish();
  }
  if (r.kind == ResponsePdu::Kind::information_report) {
    if (r.data.size > 0xFF) return false;
    write_header(w, static_cast<std::uint16_t>(ServiceCode::information_report), 0, r.cr);
    w.word(r.index);
    w.word(make_word(r.subindex, static_cast<std::uint8_t>(r.data.size)));
    w.bytes(r.data.view());
    return w.finish();
  }
  if (r.service == ServiceCode::abort || r.service == ServiceCode::information_report) return false;
  write_header(w,
               static_cast<std::uint16_t>(static_cast<std::uint16_t>(r.service) | kConfirmationBit),
               r.invoke_id, r.cr);
  if (!r.positive) {
    w.word(make_word(r.error.error_class, r.error.error_code));
    w.word(r.error.additional_code);
    if (r.service == ServiceCode::initiate) write_kbl(w, r.kbl);
    return w.finish();
  }
  w.word(0x0000);  // result: positive
  switch (r.service) {
    case ServiceCode::read:
    case ServiceCode::get_ov:
      w.word(static_cast<std::uint16_t>(r.data.size));
      w.bytes(r.data.view());
      break;
    case ServiceCode::write:
      break;
    case ServiceCode::status:
      w.word(make_word(r.status.logical, r.status.physical));
      w.word(r.status.local_detail);
      break;
    case ServiceCode::identify:
      write_name(w, r.identity.vendor);
      write_name(w, r.identity.model);
      write_name(w, r.identity.revision);
      break;
    case ServiceCode::initiate:
      write_kbl(w, r.kbl);
      break;
    case ServiceCode::abort:
    case ServiceCode::information_report:
      return false;
  }
  return w.finish();
}

PduError decode(std::span<const std::uint8_t> in, ResponsePdu& r) {
  PduHeader h;
  if (const PduError e = decode_header(in, h); e != PduError::none) return e;
  std::construct_at(&r);  // r = ResponsePdu{}, built in place rather than copied from a temporary
  r.invoke_id = h.invoke_id;
  r.cr = h.cr;
  Reader rd(in.subspan(6));
  std::uint16_t w = 0;
  if (h.code == static_cast<std::uint16_t>(ServiceCode::abort)) {
    r.kind = ResponsePdu::Kind::abort;
    r.service = ServiceCode::abort;
    if (h.count != 2 || !rd.word(w)) return PduError::malformed;
    r.reason = static_cast<AbortReason>(low_byte(w));
    return PduError::none;
  }
  if (h.code == static_cast<std::uint16_t>(ServiceCode::information_report)) {
    r.kind = ResponsePdu::Kind::information_report;
    r.service = ServiceCode::information_report;
    if (!rd.word(r.index) || !rd.word(w)) return PduError::malformed;
    r.subindex = high_byte(w);
    return read_data(rd, low_byte(w), r.data) ? PduError::none : PduError::malformed;
  }
  const auto request_code = static_cast<std::uint16_t>(h.code & ~kConfirmationBit);
  if ((h.code & kConfirmationBit) == 0 || !is_known_service(request_code) ||
      request_code == static_cast<std::uint16_t>(ServiceCode::abort) ||
      request_code == static_cast<std::uint16_t>(ServiceCode::information_report)) {
    return PduError::unknown_service;
  }
  r.kind = ResponsePdu::Kind::confirmation;
  r.service = static_cast<ServiceCode>(request_code);
  std::uint16_t result = 0;
  if (!rd.word(result)) return PduError::malformed;
  if (result != 0) {
    r.positive = false;
    r.error.error_class = high_byte(result);
    r.error.error_code = low_byte(result);
    if (!rd.word(r.error.additional_code)) return PduError::malformed;
    if (r.service == ServiceCode::initiate) {
      return h.count == 8 && read_kbl(rd, r.kbl) ? PduError::none : PduError::malformed;
    }
    return h.count == 3 ? PduError::none : PduError::malformed;
  }
  switch (r.service) {
    case ServiceCode::read:
    case ServiceCode::get_ov:
      if (!rd.word(w)) return PduError::malformed;
      return read_data(rd, w, r.data) ? PduError::none : PduError::malformed;
    case ServiceCode::write:
      return h.count == 2 ? PduError::none : PduError::malformed;
    case ServiceCode::status:
      if (h.count != 4 || !rd.word(w) || !rd.word(r.status.local_detail))
        return PduError::malformed;
      r.status.logical = high_byte(w);
      r.status.physical = low_byte(w);
      return PduError::none;
    case ServiceCode::identify:
      if (!read_name(rd, r.identity.vendor) || !read_name(rd, r.identity.model) ||
          !read_name(rd, r.identity.revision) || !rd.at_end_padded()) {
        return PduError::malformed;
      }
      return PduError::none;
    case ServiceCode::initiate:
      return h.count == 7 && read_kbl(rd, r.kbl) ? PduError::none : PduError::malformed;
    case ServiceCode::abort:
    case ServiceCode::information_report:
      break;
  }
  return PduError::unknown_service;
}

ObjectDescription describe(const ParameterInfo& p) {
  ObjectDescription d;
  d.index = p.index();
  d.type = p.type;
  d.length = static_cast<std::uint8_t>(size_of(p.type));
  d.category = p.category;
  d.attributes = p.attributes;
  d.min = static_cast<std::int32_t>(p.min);
  d.max = static_cast<std::int32_t>(p.max);
  d.default_value = static_cast<std::int32_t>(p.default_value);
  d.name = FixedString<5>::from(p.name);
  return d;
}

std::size_t encode(const ObjectDescription& d, std::span<std::uint8_t> out) {
  if (out.size() < kObjectDescriptionSize) return 0;
  std::size_t i = 0;
  auto put = [&](std::uint8_t b) { out[i++] = b; };
  auto put32 = [&](std::int32_t v) {
    const auto u = static_cast<std::uint32_t>(v);
    put(static_cast<std::uint8_t>(u >> 24U));
    put(static_cast<std::uint8_t>((u >> 16U) & 0xFFU));
    put(static_cast<std::uint8_t>((u >> 8U) & 0xFFU));
    put(static_cast<std::uint8_t>(u & 0xFFU));
  };
  put(high_byte(d.index));
  put(low_byte(d.index));
  put(d.object_code);
  put(static_cast<std::uint8_t>(d.type));
  put(d.length);
  put(static_cast<std::uint8_t>(d.category));
  put(high_byte(d.attributes));
  put(low_byte(d.attributes));
  put32(d.min);
  put32(d.max);
  put32(d.default_value);
  for (std::size_t k = 0; k < 6; ++k)
    put(k < d.name.size ? static_cast<std::uint8_t>(d.name.data[k]) : 0);
  return i;
}

bool decode(std::span<const std::uint8_t> in, ObjectDescription& d) {
  if (in.size() != kObjectDescriptionSize) return false;
  auto get32 = [&](std::size_t at) {
    const std::uint32_t u = (static_cast<std::uint32_t>(in[at]) << 24U) |
                            (static_cast<std::uint32_t>(in[at + 1]) << 16U) |
                            (static_cast<std::uint32_t>(in[at + 2]) << 8U) | in[at + 3];
    return static_cast<std::int32_t>(u);
  };
  const auto type = data_type_from_code(in[3]);
  const std::uint8_t cat = in[5];
  if (!type || (cat != '0' && cat != '1' && cat != '2') || in[25] != 0) return false;
  d.index = make_word(in[0], in[1]);
  d.object_code = in[2];
  d.type = *type;
  d.length = in[4];
  d.category = static_cast<Category>(cat);
  d.attributes = make_word(in[6], in[7]);
  d.min = get32(8);
  d.max = get32(12);
  d.default_value = get32(16);
  d.name.size = 0;
  for (std::size_t k = 0; k < 5 && in[20 + k] != 0; ++k) {
    d.name.data[k] = static_cast<char>(in[20 + k]);
    d.name.size = k + 1;
  }
  return true;
}

std::string explain_pdu(std::span<const std::uint8_t> pdu) {
  PduHeader h;
  if (const PduError e = decode_header(pdu, h); e != PduError::none) {
    return std::string("malformed message: ") + std::string(to_string(e));
  }
  char buf[96];
  std::string out;
  const bool conf =
      (h.code & kConfirmationBit) != 0 && h.code != static_cast<std::uint16_t>(ServiceCode::abort);
  const auto base = static_cast<std::uint16_t>(conf ? (h.code & ~kConfirmationBit) : h.code);
  const std::string name = is_known_service(base)
                               ? std::string(to_string(static_cast<ServiceCode>(base)))
                               : std::string("unknown service");
  std::snprintf(buf, sizeof buf, "%04X %s%s, InvokeID %u, CR %u", h.code, name.c_str(),
                conf ? ".conf"
                     : (base == static_cast<std::uint16_t>(ServiceCode::abort) ||
                                base == static_cast<std::uint16_t>(ServiceCode::information_report)
                            ? ""
                            : ".req"),
                h.invoke_id, h.cr);
  out = buf;
  if (conf) {
    ResponsePdu r;
    if (decode(pdu, r) != PduError::none) return out + ": malformed";
    if (!r.positive) return out + ": negative, " + to_string(r.error);
    out += ": positive";
    if (r.service == ServiceCode::read) {
      out += ", data";
      for (const std::uint8_t b : r.data.view()) {
        std::snprintf(buf, sizeof buf, " %02X", b);
        out += buf;
      }
    }
    return out;
  }
  RequestPdu q;
  if (base == static_cast<std::uint16_t>(ServiceCode::information_report)) {
    ResponsePdu r;
    if (decode(pdu, r) != PduError::none) return out + ": malformed";
    std::snprintf(buf, sizeof buf, ": index %04XH", r.index);
    return out + buf;
  }
  if (decode(pdu, q) != PduError::none) return out + ": malformed";
  switch (q.service) {
    case ServiceCode::read:
    case ServiceCode::write:
    case ServiceCode::get_ov: {
      const auto n = number_of(q.index);
      std::snprintf(buf, sizeof buf, ": index %04XH", q.index);
      out += buf;
      if (n) out += " (parameter " + std::to_string(*n) + ")";
      if (q.service == ServiceCode::write) {
        out += ", data";
        for (const std::uint8_t b : q.data.view()) {
          std::snprintf(buf, sizeof buf, " %02X", b);
          out += buf;
        }
      }
      break;
    }
    case ServiceCode::abort:
      out += std::string(": reason ") + std::string(to_string(q.reason));
      break;
    default:
      break;
  }
  return out;
}

}  // namespace ibs::pcp
