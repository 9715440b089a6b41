#include "ibs/lustbus/byte_log.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <sstream>
#include <vector>

#include "ibs/base/number_text.hpp"
#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/siof.hpp"
#include "ibs/lustbus/telegram.hpp"

namespace ibs::lustbus {

namespace {

// What a CODE names, for the reader: the family its digits say (2.4.1 / 2.4.2, 5.2) and the
// parameter's name from that family's table.
struct Named {
  std::string text;  // "VF1000 5-FSSIO", "MC6000 428-RSIO description", "PosMOD1"
  Family family = Family::standard;
  std::optional<ParameterFacts> param;
  bool description = false;
};

std::string label(const ParameterFacts& p) { return std::to_string(p.number) + "-" + p.name; }

Named name_code(const Code& c, const ParameterLookup& lookup) {
  Named n;
  if (c == kPosmodCode) {
    n.text = "MC6000 PosMOD1 (11.6)";
    return n;
  }
  const auto find = [&](Family f, std::uint16_t number) -> std::optional<ParameterFacts> {
    return lookup ? lookup(f, number) : std::nullopt;
  };
  if (const auto mc = as_mc_code(c); mc && mc->kind != McCodeKind::shared) {
    n.family = Family::enhanced;
    n.param = find(Family::enhanced, mc->parameter);
    const std::string what = mc->kind == McCodeKind::description         ? " description (11.2)"
                             : mc->kind == McCodeKind::substitution_text ? " substitution text (11.3)"
                             : mc->kind == McCodeKind::special           ? " special function"
                                                                         : "";
    n.description = mc->kind != McCodeKind::value;
    n.text = "MC6000 " + (n.param ? label(*n.param) : std::to_string(mc->parameter) + " (not in the table)") + what;
    return n;
  }
  if (const auto vf = as_vf_code(c)) {
    const bool shared = is_shared_parameter(vf->parameter) && c.digit(0) == '0' && c.digit(2) == '0';
    n.family = Family::standard;
    n.param = find(Family::standard, vf->parameter);
    n.description = vf->specifier == VfSpecifier::description;
    n.text = std::string(shared ? "VF1000/MC6000 " : "VF1000 ") +
             (n.param ? label(*n.param) : std::to_string(vf->parameter) + " (not in the table)") +
             (n.description ? " description (11.1)" : "");
    return n;
  }
  n.text = "no CODE of either family";
  return n;
}

std::string hex2(std::uint8_t b) { return hex_text(b, 2); }

// A shared CODE (00081..00085, 2.4.2 and 5.2) is answered by either family, each in its own VALUE
// form: the VF1000's 85-SIOF as four characters, the MC6000's 85-SERR as two hex digits (a binary
// value of 8 bits, 2.4.2). The log does not say which drive sits at the address, so the answer's
// form does: one the standard family cannot read but the enhanced one can is the MC6000's.
Named answered_by(Named n, std::string_view v, const Code& c, const ParameterLookup& lookup) {
  if (!n.param || n.description || n.family != Family::standard) return n;
  if (parse_typed(Family::standard, n.param->type, v).ok()) return n;
  const auto vf = as_vf_code(c);
  if (!vf || !is_shared_parameter(vf->parameter) || !lookup) return n;
  const auto mc = lookup(Family::enhanced, vf->parameter);
  if (!mc || !parse_typed(Family::enhanced, mc->type, v).ok()) return n;
  n.family = Family::enhanced;
  n.param = mc;
  n.text = "MC6000 " + label(*mc) + " (shared CODE)";
  return n;
}

// The VALUE as the parameter's type reads it.
std::string explain_value(const Named& n, std::string_view v) {
  if (!n.param || n.description) return "";
  const auto bits = parse_typed(n.family, n.param->type, v);
  if (!bits.ok()) {
    return " (" + std::string(to_string(bits.error)) + " for " + std::string(to_string(n.param->type)) + ")";
  }
  const std::string e = engineering_text(n.param->type, bits.value);
  return " " + (e.empty() ? std::to_string(bits.value) : e + (n.param->unit.empty() ? "" : " " + n.param->unit));
}

std::string printable(std::string_view v) {
  std::string out;
  for (const char c : v) {
    const auto b = static_cast<unsigned char>(c);
    out += b >= 0x20 && b < 0x7F ? std::string(1, c) : "<" + hex2(b) + ">";
  }
  return out;
}

// The byte stream of one side, split into telegrams (LUSTBUS manual 2.2, 6.1, 6.2).
class LogReader {
 public:
  LogReader(std::ostream& out, const ParameterLookup& lookup) : out_(out), lookup_(lookup) {}

  void host_byte(std::uint8_t b, const std::string& at) {
    if (b == kEot && step_ != Step::bcc) {
      flush_host("");
      out_ << at << " host  EOT\n";
      return;
    }
    if (host_.empty()) host_at_ = at;
    host_.push_back(static_cast<char>(b));
    if (step_ == Step::bcc) {
      finish_select();
      return;
    }
    if (b == kEtx) step_ = Step::bcc;
    if (b == kEnq) finish_enquiry();
  }

  void device_byte(std::uint8_t b, const std::string& at) {
    if (!answering_) {
      answer_at_ = at;
      answering_ = true;
      decoder_.start(addr_, code_, expect_, answer_binary_prefix(code_));
      raw_.clear();
    }
    raw_.push_back(static_cast<char>(b));
    if (decoder_.feed(b) == AnswerDecoder::Status::need_more) return;
    answering_ = false;
    if (decoder_.status() == AnswerDecoder::Status::error) {
      out_ << answer_at_ << " drive broken answer (" << to_string(decoder_.error()) << "): " << printable(raw_) << "\n";
      return;
    }
    switch (decoder_.kind()) {
      case AnswerKind::ack:
        out_ << answer_at_ << " drive " << address_char(addr_) << " ACK\n";
        return;
      case AnswerKind::nak:
        out_ << answer_at_ << " drive " << address_char(addr_) << " NAK"
             << (expect_ == AnswerDecoder::Expect::ack_or_nak && code_ != kPosmodCode
                     ? " (the cause is in 85-SIOF/SERR, 9.2)\n"
                     : "\n");
        return;
      default: {
        const std::string v(decoder_.value().view());
        const Named n = answered_by(name_code(code_, lookup_), v, code_, lookup_);
        out_ << answer_at_ << " drive " << address_char(addr_) << " " << code_.text() << "=" << printable(v)
             << " BCC ok: " << n.text << (n.param && !n.description ? " =" : "") << explain_value(n, v);
        if (reads_siof(code_)) {
          const auto bits = parse_raw(Family::enhanced, v);
          if (bits.ok()) out_ << " (" << describe_siof(static_cast<std::uint8_t>(bits.value)) << ")";
        }
        out_ << "\n";
        return;
      }
    }
  }

  void end() {
    flush_host(" (cut off at the end of the log)");
    if (answering_) out_ << answer_at_ << " drive incomplete answer: " << printable(raw_) << "\n";
  }

 private:
  enum class Step : std::uint8_t { text, bcc };

  void flush_host(const std::string& why) {
    if (!host_.empty()) {
      out_ << host_at_ << " host  broken telegram" << (why.empty() ? " (EOT before its end)" : why) << ": "
           << printable(host_) << "\n";
    }
    host_.clear();
    step_ = Step::text;
    answering_ = false;
  }

  // ADR CODE ENQ (6.1).
  void finish_enquiry() {
    const auto a = host_.empty() ? std::nullopt : address_from_char(static_cast<std::uint8_t>(host_[0]));
    const auto c = host_.size() == 7 ? Code::parse(std::string_view(host_).substr(1, 5)) : std::nullopt;
    if (!a || !c) {
      flush_host(" (no ENQUIRY of 6.1)");
      return;
    }
    addr_ = *a;
    code_ = *c;
    expect_ = AnswerDecoder::Expect::text_or_nak;
    out_ << host_at_ << " host  ENQUIRY " << host_[0] << " (address " << int{*a} << ") " << c->text() << ": "
         << name_code(*c, lookup_).text << "\n";
    host_.clear();
  }

  // ADR STX CODE = VALUE ETX BCC (6.2).
  void finish_select() {
    const std::string t = host_;
    host_.clear();
    step_ = Step::text;
    const auto a = address_from_char(static_cast<std::uint8_t>(t[0]));
    const auto c = t.size() >= 10 ? Code::parse(std::string_view(t).substr(2, 5)) : std::nullopt;
    if (!a || t[1] != kStx || !c || t[7] != kEquals) {
      out_ << host_at_ << " host  broken telegram (no SELECT of 6.2): " << printable(t) << "\n";
      return;
    }
    const std::string v = t.substr(8, t.size() - 10);
    std::uint8_t bcc = 0;
    for (std::size_t i = 2; i + 1 < t.size(); ++i) bcc ^= static_cast<std::uint8_t>(t[i]);
    const bool ok = bcc == static_cast<std::uint8_t>(t.back());
    addr_ = *a;
    code_ = *c;
    expect_ = AnswerDecoder::Expect::ack_or_nak;
    const Named n = name_code(*c, lookup_);
    out_ << host_at_ << " host  SELECT " << t[0] << " (address " << int{*a}
         << (*a == kAddressBroadcast ? ", broadcast" : "") << ") " << c->text() << "=" << printable(v)
         << (ok ? " BCC ok: "
                : " BCC WRONG (" + hex2(static_cast<std::uint8_t>(t.back())) + ", should be " + hex2(bcc) + "): ")
         << n.text << (n.param && !n.description ? " :=" : "") << explain_value(n, v) << "\n";
  }

  std::ostream& out_;
  const ParameterLookup& lookup_;
  std::string host_;
  std::string host_at_;
  Step step_ = Step::text;
  bool answering_ = false;
  std::string answer_at_;
  std::string raw_;
  Address addr_ = 0;
  Code code_{};
  AnswerDecoder::Expect expect_ = AnswerDecoder::Expect::text_or_nak;
  AnswerDecoder decoder_{};
};

struct LogLine {
  std::string at;
  bool tx = false;
  std::string port;
  std::vector<std::uint8_t> bytes;
};

}  // namespace

std::string engineering_text(DataType t, std::uint32_t bits) {
  const auto e = to_engineering(t, bits);
  if (!e.ok()) return "";
  if (t == DataType::fixpoint16) {
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", e.value);
    return b;
  }
  std::ostringstream s;
  s << e.value;
  return s.str();
}

ByteLogReading read_byte_log(std::span<const std::string> lines, const ParameterLookup& lookup) {
  ByteLogReading r;
  std::vector<LogLine> parsed;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    if (l.empty()) continue;
    const auto bad = [&](const std::string& what) {
      r.error = ByteLogError{i + 2, what};  // the header is line 1
      return r;
    };
    std::istringstream s(l);
    LogLine line;
    std::string dir;
    s >> line.at >> dir >> line.port;
    double seconds = 0;
    if (std::from_chars(line.at.data(), line.at.data() + line.at.size(), seconds).ec != std::errc{}) {
      return bad("'" + line.at + "' is no time in seconds");
    }
    if (dir != "tx" && dir != "rx") return bad("'" + dir + "' is neither tx nor rx");
    line.tx = dir == "tx";
    for (std::string h; s >> h;) {
      unsigned v = 0;
      const auto rh = std::from_chars(h.data(), h.data() + h.size(), v, 16);
      if (h.size() != 2 || rh.ec != std::errc{} || rh.ptr != h.data() + 2) {
        return bad("'" + h + "' is not a byte in two hex digits");
      }
      line.bytes.push_back(static_cast<std::uint8_t>(v));
    }
    if (line.bytes.empty()) return bad("a line without bytes");
    parsed.push_back(std::move(line));
  }
  // The host's side is the one that sends EOT first (3: every telegram begins with it).
  const auto first = std::find_if(parsed.begin(), parsed.end(), [](const LogLine& l) { return l.bytes[0] == kEot; });
  if (first == parsed.end()) {
    r.error = ByteLogError{0, "no EOT in the log: not a LUSTBUS byte log (3: every telegram begins with EOT)"};
    return r;
  }
  r.host_tx = first->tx;
  r.host_port = first->port;
  std::vector<LineBytes> chunks;
  chunks.reserve(parsed.size());
  for (LogLine& l : parsed) chunks.push_back({std::move(l.at), l.tx == r.host_tx, std::move(l.bytes)});
  r.text = explain_line(chunks, lookup);
  return r;
}

std::string explain_line(std::span<const LineBytes> chunks, const ParameterLookup& lookup) {
  std::ostringstream out;
  LogReader reader(out, lookup);
  for (const LineBytes& l : chunks) {
    for (const std::uint8_t b : l.bytes) {
      if (l.from_host) {
        reader.host_byte(b, l.at);
      } else {
        reader.device_byte(b, l.at);
      }
    }
  }
  reader.end();
  return out.str();
}

}  // namespace ibs::lustbus
