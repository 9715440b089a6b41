#include "ibs/lustbus/capture_framer.hpp"

#include <algorithm>

#include "ibs/lustbus/chars.hpp"
#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/telegram.hpp"

namespace ibs::lustbus {

namespace {

using base::LineSide;
using base::LineTelegram;

// Noise is cut into packets of at most this many bytes; a telegram that runs past the longest one
// of 6.2 (kMaxTelegramLength) without its end is cut there and what follows is noise.
constexpr std::size_t kMaxNoise = 256;

bool is_adr(std::uint8_t b) { return address_from_char(b).has_value(); }

}  // namespace

void CaptureFramer::begin(Pending& p, LineSide side, Step step, std::uint8_t b, Time at) {
  p.t = LineTelegram{};
  p.t.from = side;
  p.t.first = at;
  p.t.last = at;
  p.t.bytes.push_back(b);
  if (step == Step::noise) p.t.flags = base::kTelegramNoise;
  p.step = step;
  p.raw = 0;
}

void CaptureFramer::add(Pending& p, std::uint8_t b, Time at) {
  p.t.bytes.push_back(b);
  p.t.last = at;
}

void CaptureFramer::emit(Pending& p, bool complete, std::vector<LineTelegram>& out) {
  if (p.step == Step::none) return;
  // A lone EOT is a whole telegram (3: the host's closing one); noise is noise, not a cut telegram.
  if (!complete && p.step != Step::eot && p.step != Step::noise) p.t.flags |= base::kTelegramCut;
  out.push_back(std::move(p.t));
  p.t = LineTelegram{};
  p.step = Step::none;
}

// The byte after ETX is the BCC, whatever it is (2.2): XOR of the bytes after STX through ETX.
void CaptureFramer::bcc_done(Pending& p, std::vector<LineTelegram>& out) {
  const auto& b = p.t.bytes;
  const auto stx = std::find(b.begin(), b.end(), kStx);
  if (stx != b.end() && bcc(std::span<const std::uint8_t>(&*(stx + 1), static_cast<std::size_t>(b.end() - 1 - (stx + 1)))) != b.back()) {
    p.t.flags |= base::kTelegramCheckBad;
  }
  emit(p, true, out);
}

void CaptureFramer::host_byte(std::uint8_t b, Time at, std::vector<LineTelegram>& out) {
  Pending& p = host_;
  if (b == kEot && p.step != Step::bcc) {
    // EOT begins every telegram (3): what was pending ends here (a lone EOT complete).
    emit(p, false, out);
    begin(p, LineSide::host, Step::eot, b, at);
    return;
  }
  switch (p.step) {
    case Step::none:
      begin(p, LineSide::host, Step::noise, b, at);
      return;
    case Step::noise:
      add(p, b, at);
      if (p.t.bytes.size() >= kMaxNoise) emit(p, false, out);
      return;
    case Step::eot:
      add(p, b, at);
      if (is_adr(b)) {
        p.t.address = static_cast<std::uint8_t>(b - kAddressBase);
        p.step = Step::address;
      } else {
        p.t.flags |= base::kTelegramNoise;  // EOT then no ADR: no telegram of 6.1 or 6.2
        p.step = Step::noise;
      }
      return;
    case Step::address:
      add(p, b, at);
      if (b == kStx) {
        p.step = Step::text;  // SELECT (6.2)
      } else if (b == kEnq) {
        // ENQUIRY (6.1): EOT ADR CODE ENQ; its CODE says how the answer's VALUE reads.
        const auto code = p.t.bytes.size() == 3 + kCodeLength
                              ? Code::parse(std::string_view(reinterpret_cast<const char*>(p.t.bytes.data()) + 2,
                                                             kCodeLength))
                              : std::nullopt;
        enquiry_ = code.has_value();
        if (code) code_ = *code;
        emit(p, true, out);
      } else if (p.t.bytes.size() > 2 + kCodeLength + 1) {
        p.t.flags |= base::kTelegramNoise;  // no ENQ after the CODE
        p.step = Step::noise;
      }
      return;
    case Step::text:
      add(p, b, at);
      if (b == kEtx) {
        p.step = Step::bcc;
      } else if (p.t.bytes.size() >= kMaxTelegramLength) {
        emit(p, false, out);
      }
      return;
    case Step::bcc:
      add(p, b, at);
      enquiry_ = false;  // a SELECT is answered ACK or NAK
      bcc_done(p, out);
      return;
  }
}

void CaptureFramer::device_byte(std::uint8_t b, Time at, std::vector<LineTelegram>& out) {
  Pending& p = device_;
  switch (p.step) {
    case Step::none:
    case Step::eot:
      if (is_adr(b)) {
        begin(p, LineSide::device, Step::address, b, at);
        p.t.address = static_cast<std::uint8_t>(b - kAddressBase);
      } else {
        begin(p, LineSide::device, Step::noise, b, at);
      }
      return;
    case Step::noise:
      add(p, b, at);
      if (p.t.bytes.size() >= kMaxNoise) emit(p, false, out);
      return;
    case Step::address:
      add(p, b, at);
      if (b == kAck || b == kNak) {
        emit(p, true, out);
      } else if (b == kStx) {
        p.step = Step::text;
        // LB-D10: CODE, '=' and the binary elements of an MC6000 description travel whatever they are.
        const std::size_t binary = enquiry_ ? answer_binary_prefix(code_) : 0;
        p.raw = binary == 0 ? 0 : kCodeLength + 1 + binary;
      } else {
        p.t.flags |= base::kTelegramNoise;  // ADR then neither STX, ACK nor NAK
        p.step = Step::noise;
      }
      return;
    case Step::text:
      add(p, b, at);
      if (p.raw > 0) {
        --p.raw;
      } else if (b == kEtx) {
        p.step = Step::bcc;
      } else if (p.t.bytes.size() >= kMaxTelegramLength) {
        emit(p, false, out);
      }
      return;
    case Step::bcc:
      add(p, b, at);
      bcc_done(p, out);
      return;
  }
}

void CaptureFramer::feed(LineSide side, std::span<const std::uint8_t> bytes, Time at, std::vector<LineTelegram>& out) {
  if (bytes.empty()) return;
  // Half duplex: when one side speaks, what the other left pending has ended.
  emit(side == LineSide::host ? device_ : host_, false, out);
  for (const std::uint8_t b : bytes) {
    if (side == LineSide::host) {
      host_byte(b, at, out);
    } else {
      device_byte(b, at, out);
    }
  }
}

void CaptureFramer::finish(std::vector<LineTelegram>& out) {
  // In the order they began.
  Pending* first = &host_;
  Pending* second = &device_;
  if (device_.step != Step::none && (host_.step == Step::none || device_.t.first < host_.t.first)) {
    std::swap(first, second);
  }
  emit(*first, false, out);
  emit(*second, false, out);
}

}  // namespace ibs::lustbus
