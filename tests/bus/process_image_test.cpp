// Process image: per-device slices and the DDI byte view (public-facts.md: big-endian words,
// high byte at the lower address).
#include "ibs/interbus/process_image.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "ibs/interbus/bus_config.hpp"

namespace ibs::interbus {
namespace {

BusConfig default_bus() {
  const std::vector<DeviceSpec> ring{{"mc6000", IdCode{0x4DB}, {}}, {"vf1000", IdCode{0x33B}, {}}};
  return make_bus_config(ring);
}

TEST(ProcessImage, SizedForTheInterbusMaximum) {
  const ProcessImage p;
  EXPECT_EQ(p.words(Area::in).size(), 256U);
  EXPECT_EQ(p.words(Area::out).size(), 256U);
  EXPECT_EQ(p.words(Area::pcp_in).size(), 62U * 4U);
  EXPECT_EQ(p.words(Area::pcp_out).size(), 62U * 4U);
  EXPECT_EQ(p.size_bytes(Area::in), 512U);
}

TEST(ProcessImage, DeviceSlicesWriteThroughToTheirPlaceInTheImage) {
  const BusConfig c = default_bus();
  auto p = std::make_unique<ProcessImage>();
  const Device& mc = *c.find("mc6000");
  const Device& vf = *c.find("vf1000");

  const std::span<Word> mc_out = out_slice(*p, mc);
  ASSERT_EQ(mc_out.size(), 3U);
  mc_out[0] = 0x000F;
  const std::span<Word> vf_out = out_slice(*p, vf);
  ASSERT_EQ(vf_out.size(), 3U);
  vf_out[0] = 0x0006;
  vf_out[2] = 0x1234;
  EXPECT_EQ(p->out[0], 0x000F);
  EXPECT_EQ(p->out[3], 0x0006);
  EXPECT_EQ(p->out[5], 0x1234);
  EXPECT_EQ(mc_out.data() + 3, vf_out.data());

  p->in[4] = 0x0437;
  EXPECT_EQ(in_slice(std::as_const(*p), vf)[1], 0x0437);
  pcp_out_slice(*p, mc)[0] = 0xABCD;
  EXPECT_EQ(p->pcp_out[0], 0xABCD);
  EXPECT_EQ(pcp_in_slice(*p, mc).size(), 1U);
  EXPECT_TRUE(pcp_in_slice(*p, vf).empty());
}

TEST(ProcessImage, SliceOutsideTheAreaIsEmpty) {
  ProcessImage p;
  EXPECT_EQ(p.slice(Area::in, Slice{250, 6}).size(), 6U);
  EXPECT_TRUE(p.slice(Area::in, Slice{250, 7}).empty());
  EXPECT_TRUE(p.slice(Area::in, Slice{257, 0}).empty());
  EXPECT_TRUE(p.slice(Area::pcp_in, Slice{0, 249}).empty());
  EXPECT_TRUE(p.slice(Area::out, Slice{SIZE_MAX, 2}).empty());
}

TEST(ProcessImage, ByteViewPutsTheHighByteAtTheLowerAddress) {
  ProcessImage p;
  p.in[0] = 0x0437;
  p.in[1] = 0x09C4;
  p.in[2] = 0x4000;
  std::array<std::uint8_t, 6> b{};
  ASSERT_TRUE(p.read_bytes(Area::in, 0, b));
  EXPECT_EQ(b, (std::array<std::uint8_t, 6>{0x04, 0x37, 0x09, 0xC4, 0x40, 0x00}));
  EXPECT_EQ(p.byte(Area::in, 2), 0x09);
  EXPECT_EQ(p.byte(Area::in, 3), 0xC4);
  // An odd start address (DDI BYTE consistency) reads across word boundaries.
  std::array<std::uint8_t, 3> odd{};
  ASSERT_TRUE(p.read_bytes(Area::in, 1, odd));
  EXPECT_EQ(odd, (std::array<std::uint8_t, 3>{0x37, 0x09, 0xC4}));
}

TEST(ProcessImage, ByteWritesChangeOnlyTheirHalfOfAWord) {
  ProcessImage p;
  p.out[10] = 0x1122;
  p.out[11] = 0x3344;
  const std::array<std::uint8_t, 2> b{0xAA, 0xBB};
  ASSERT_TRUE(p.write_bytes(Area::out, 21, b));  // low byte of word 10, high byte of word 11
  EXPECT_EQ(p.out[10], 0x11AA);
  EXPECT_EQ(p.out[11], 0xBB44);
}

TEST(ProcessImage, ByteAccessLeavingTheAreaFailsWithoutSideEffects) {
  ProcessImage p;
  p.in[255] = 0x5566;
  std::array<std::uint8_t, 2> b{0xEE, 0xEE};
  EXPECT_FALSE(p.read_bytes(Area::in, 511, b));
  EXPECT_EQ(b, (std::array<std::uint8_t, 2>{0xEE, 0xEE}));
  EXPECT_TRUE(p.read_bytes(Area::in, 510, b));
  EXPECT_EQ(b, (std::array<std::uint8_t, 2>{0x55, 0x66}));
  EXPECT_FALSE(p.write_bytes(Area::in, 511, b));
  EXPECT_EQ(p.in[255], 0x5566);
  EXPECT_EQ(p.byte(Area::in, 512), 0);
  EXPECT_FALSE(p.read_bytes(Area::pcp_in, 62 * 8, std::span<std::uint8_t>(b).first(1)));
}

TEST(ProcessImage, ClearZeroesEveryArea) {
  ProcessImage p;
  p.in[1] = 1;
  p.out[2] = 2;
  p.pcp_in[3] = 3;
  p.pcp_out[4] = 4;
  p.clear();
  for (const Area a : {Area::in, Area::out, Area::pcp_in, Area::pcp_out}) {
    for (const Word w : p.words(a)) EXPECT_EQ(w, 0);
  }
}

}  // namespace
}  // namespace ibs::interbus
