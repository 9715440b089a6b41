// The LUSTBUS line cut into telegrams for a capture (docs/pcap.md, "Serial lines"; LUSTBUS manual 2.2,
// 3, 6.1, 6.2, 11.6):
//
//   host:   EOT ADR CODE ENQ  |  EOT ADR STX CODE = VALUE ETX BCC  |  EOT (alone: the closing one)
//   device: ADR STX CODE = VALUE ETX BCC  |  ADR ACK  |  ADR NAK
//
// A host telegram begins with EOT and ends with ENQ, with the byte after ETX (the BCC, whatever
// it is, 2.2), or with the next EOT (a lone EOT is complete; a longer telegram cut there is cut).
// A device telegram begins with ADR and ends with ACK, NAK or the byte after ETX; the first 42
// VALUE characters of the answer to an ENQUIRY of an MC6000 description are taken by length
// (LB-D10: they may be frame characters). The BCC is checked (XOR after STX through ETX), a
// telegram the other side interrupts is cut, and bytes that begin no telegram (host bytes before
// EOT, device bytes that are no ADR) are kept as noise up to the next telegram's start.
// Sans-I/O: bytes and time in, telegrams out.
#pragma once

#include <cstddef>

#include "ibs/base/line_telegram.hpp"
#include "ibs/lustbus/code.hpp"

namespace ibs::lustbus {

class CaptureFramer final : public base::TelegramFramer {
 public:
  void feed(base::LineSide side, std::span<const std::uint8_t> bytes, Time at,
            std::vector<base::LineTelegram>& out) override;
  void finish(std::vector<base::LineTelegram>& out) override;

 private:
  // Where a side's pending telegram stands.
  enum class Step : std::uint8_t {
    none,     // nothing pending
    noise,    // bytes that begin no telegram
    eot,      // host: EOT alone so far
    address,  // after ADR (host: after EOT ADR): CODE ENQ, STX, ACK or NAK next
    text,     // after STX: CODE = VALUE until ETX
    bcc,      // after ETX: the BCC
  };
  struct Pending {
    base::LineTelegram t;
    Step step = Step::none;
    std::size_t raw = 0;  // device: text bytes after STX still taken whatever they are (LB-D10)
  };

  void host_byte(std::uint8_t b, Time at, std::vector<base::LineTelegram>& out);
  void device_byte(std::uint8_t b, Time at, std::vector<base::LineTelegram>& out);
  void begin(Pending& p, base::LineSide side, Step step, std::uint8_t b, Time at);
  static void add(Pending& p, std::uint8_t b, Time at);
  // Ends `p`: complete, or cut (a telegram that did not reach its end; noise stays noise).
  static void emit(Pending& p, bool complete, std::vector<base::LineTelegram>& out);
  void bcc_done(Pending& p, std::vector<base::LineTelegram>& out);

  Pending host_;
  Pending device_;
  // The CODE of the host's last ENQUIRY (for the binary part of its answer); none after a SELECT.
  bool enquiry_ = false;
  Code code_{};
};

}  // namespace ibs::lustbus
