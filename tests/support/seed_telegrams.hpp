// The manuals' worked examples on the serial lines, byte for byte, as the captures' tests feed
// them: LUSTBUS (LUSTBUS manual: 6.1.1.1, 6.1.1.2, 6.2.2, 6.2.3, 11.6.4) corrected as docs/errata.md
// decides (LB-E1 the answer's ADR '@', LB-E3 CODE 00112 / 00105, LB-E4 ETX = 3 and VALUE
// 04FA4000, LB-E5 CODE 20428 for the servo), each BCC by the rule of 2.2; DFS-1 (DFS-1 manual, note
// 2: the set-speed frame with its doubled 10H and CSM 6DH, and its ACK).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "ibs/base/line_telegram.hpp"

namespace ibs::test {

struct SeedTelegram {
  base::LineSide from;
  std::vector<std::uint8_t> bytes;
};

namespace seed_detail {
inline std::vector<std::uint8_t> text(std::vector<std::uint8_t> head, std::string_view s,
                                      std::vector<std::uint8_t> tail) {
  head.insert(head.end(), s.begin(), s.end());
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}
}  // namespace seed_detail

// LUSTBUS manual's exchanges, one telegram after the other, each closed by the host's EOT (3).
inline std::vector<SeedTelegram> lustbus_seed_exchanges() {
  using seed_detail::text;
  constexpr auto H = base::LineSide::host;
  constexpr auto D = base::LineSide::device;
  return {
      // 6.1.1.1: 12-FOUT of a VF1000 via address 0; the answer 03E8 (50.00 Hz), BCC 72H.
      {H, text({0x04, 0x40}, "00112", {0x05})},
      {D, text({0x40, 0x02}, "00112=03E8", {0x03, 0x72})},
      {H, {0x04}},
      // 6.1.1.2: 77-SPEED of an MC6000; 04FA4000H = 1274.25 1/min, BCC 0BH.
      {H, text({0x04, 0x40}, "20077", {0x05})},
      {D, text({0x40, 0x02}, "20077=04FA4000", {0x03, 0x0B})},
      {H, {0x04}},
      // 6.2.2: 5-FSSIO := 50.00 Hz (03E8), BCC 74H; ACK.
      {H, text({0x04, 0x40, 0x02}, "00105=03E8", {0x03, 0x74})},
      {D, {0x40, 0x06}},
      {H, {0x04}},
      // 6.2.3 with CODE 20428 (428-RSIO, LB-E5): 333.254 1/min = 14D4106H, BCC 40H; ACK.
      {H, text({0x04, 0x40, 0x02}, "20428=14D4106", {0x03, 0x40})},
      {D, {0x40, 0x06}},
      {H, {0x04}},
      // 11.6.4: a manual command to the PosMOD1 (CODE 49999), status byte 38H, BCC 1CH.
      {H, text({0x04, 0x40, 0x02}, "49999=8GOA0V1000", {0x03, 0x1C})},
      {D, {0x40, 0x06}},
      {H, {0x04}},
  };
}

// DFS-1 manual, note 2: "[10][02] [01] [82] [00][00][10][10][00] [10] [03] [6D]": set speed (82H) of
// UID 1 to 00 00 10 00 (4096 rpm), the 10H datum doubled; the controller's ACK (CSM F9H, of 01 + 06).
inline std::vector<SeedTelegram> dfs1_seed_exchange() {
  constexpr auto H = base::LineSide::host;
  constexpr auto D = base::LineSide::device;
  return {
      {H, {0x10, 0x02, 0x01, 0x82, 0x00, 0x00, 0x10, 0x10, 0x00, 0x10, 0x03, 0x6D}},
      {D, {0x10, 0x02, 0x01, 0x06, 0x10, 0x03, 0xF9}},
  };
}

}  // namespace ibs::test
