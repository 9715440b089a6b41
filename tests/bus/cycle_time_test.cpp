// Cycle time, reaction time and recovery against values computed by hand from
// T_cycle = SW + (13 * (6 + N) + 1.5 * M) * T_bit (public-facts.md, "Cycle time").
#include "ibs/interbus/cycle_time.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ibs/interbus/bus_config.hpp"

namespace ibs::interbus {
namespace {

BusConfig ring_of(const std::vector<Word>& codes) {
  std::vector<DeviceSpec> ring;
  for (const Word c : codes) {
    std::string name = "d";
    name += std::to_string(ring.size());
    ring.push_back({name, IdCode{c}, {}});
  }
  return make_bus_config(ring);
}

TEST(CycleTime, DefaultBusMc6000Supi11AndVf1000At500kbit) {
  // N = (4 + 3) words * 2 = 14 bytes, M = 2 remote devices:
  // 13 * (6 + 14) + 1.5 * 2 = 263 bits * 2 us = 526 us; + SW 200 us = 726 us.
  const BusConfig c = ring_of({0x4DB, 0x33B});
  EXPECT_EQ(ring_load(c).data_bytes, 14U);
  EXPECT_EQ(ring_load(c).remote_devices, 2U);
  EXPECT_EQ(cycle_time(c), 726us);
}

TEST(CycleTime, DefaultBusAt2Mbit) {
  // 263 bits * 0.5 us = 131.5 us; + 200 us = 331.5 us.
  EXPECT_EQ(cycle_time(ring_of({0x4DB, 0x33B}), params_for(BaudRate::mbit2)), 331500ns);
}

TEST(CycleTime, EmptyRingIsTheProtocolOverheadOnly) {
  // 13 * 6 = 78 bits * 2 us = 156 us; + 200 us.
  EXPECT_EQ(cycle_time(RingLoad{}), 356us);
}

TEST(CycleTime, FullInputAndOutputImage) {
  // 16 devices of 16 words in/out: N = 512 bytes, M = 16:
  // 13 * 518 + 1.5 * 16 = 6734 + 24 = 6758 bits * 2 us = 13516 us; + 200 us = 13.716 ms.
  const BusConfig c = ring_of(std::vector<Word>(16, 0x1203));
  EXPECT_EQ(c.in_words, 256U);
  EXPECT_EQ(cycle_time(c), 13716us);
}

TEST(CycleTime, PcpWordsCountLikeProcessData) {
  // SUPI 11 (3 PD + 1 PCP) and SUPI 12 (4 PD) occupy the same ring; SUPI 10 (3 PD) is 2 bytes
  // = 26 bits = 52 us shorter.
  const Duration supi11 = cycle_time(ring_of({0x4DB}));
  EXPECT_EQ(cycle_time(ring_of({0x47B})), supi11);
  EXPECT_EQ(supi11 - cycle_time(ring_of({0x37B})), 52us);
}

TEST(CycleTime, LocalBusDevicesAddDataButNoCouplerTerm) {
  // Remote VF1000 and the same 3 words as a local MC6000 (393H): N = 12, M = 1:
  // 13 * 18 + 1.5 = 235.5 bits * 2 us = 471 us; + 200 us = 671 us.
  EXPECT_EQ(cycle_time(ring_of({0x33B, 0x393})), 671us);
}

TEST(CycleTime, EveryTermIsAParameter) {
  CycleTimeParams p;
  p.software_time = 1ms;
  EXPECT_EQ(cycle_time(RingLoad{14, 2}, p), 1526us);
  p = {};
  p.cable_km = 2.0;  // Lenze: about 0.24 ms per km
  EXPECT_EQ(cycle_time(RingLoad{14, 2}, p), 1206us);
  p = {};
  p.line_bits_per_byte = 10.0;
  p.overhead_bytes = 0.0;
  p.bits_per_remote_device = 0.0;
  EXPECT_EQ(cycle_time(RingLoad{14, 2}, p), 200us + 280us);
  p = {};
  p.bit_time = 1us;
  EXPECT_EQ(cycle_time(RingLoad{14, 2}, p), 463us);
  EXPECT_EQ(cycle_time(RingLoad{14, 3}), 729us);  // 1.5 bits more: 3 us
}

TEST(CycleTime, ReactionIsTwoCyclesAndRecoveryAboutFive) {
  const Duration t = cycle_time(ring_of({0x4DB, 0x33B}));
  EXPECT_EQ(worst_case_reaction_time(t), 1452us);
  EXPECT_EQ(recovery_time(t), 3630us);
  EXPECT_EQ(recovery_time(t, 3), 2178us);
  static_assert(kReactionCycles == 2 && kRecoveryCycles == 5);
}

TEST(CycleTime, BitTimes) {
  static_assert(bit_time(BaudRate::kbit500) == 2us);
  static_assert(bit_time(BaudRate::mbit2) == 500ns);
  EXPECT_EQ(params_for(BaudRate::mbit2).software_time, 200us);
}

}  // namespace
}  // namespace ibs::interbus
