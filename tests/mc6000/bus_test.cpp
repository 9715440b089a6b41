// The MC6000's layouts on the bus: every 405-SUPI row's ID code decodes to its words, PCP width
// and bus (INTERBUS manual 3.2.2, the ID-code rules of interbus/id_code.hpp), and a Q16 reference sits in
// the process image as big-endian bytes (5.3.4).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/interbus/bus_config.hpp"
#include "ibs/interbus/id_code.hpp"
#include "ibs/interbus/process_image.hpp"

namespace ibs::devices::mc6000 {
namespace {

using namespace interbus;

TEST(IdCode, EverySupiRowDecodesToItsWordsPcpWidthAndBus) {
  for (const SupiRow& row : kSupiTable) {
    for (const auto& [raw, bus] :
         {std::pair{row.id_local, BusKind::local}, std::pair{row.id_remote, BusKind::remote}}) {
      const IdCode id{raw};
      SCOPED_TRACE("SUPI " + std::to_string(row.supi) + " " + to_hex(id));
      ASSERT_TRUE(id.decodable());
      EXPECT_EQ(id.ring_words(), row.pd_words + row.pcp_words);
      EXPECT_EQ(id.pcp_words(), row.pcp_words);
      EXPECT_EQ(id.pd_words(), row.pd_words);
      EXPECT_EQ(id.has_pcp(), row.pcp_words > 0);
      EXPECT_EQ(id.bus(), bus);
      EXPECT_EQ(id.direction(), Direction::in_out);
    }
  }
}

TEST(IdCode, EverySupiRowIsRebuiltFromItsWordCounts) {
  for (const SupiRow& row : kSupiTable) {
    SCOPED_TRACE("SUPI " + std::to_string(row.supi));
    if (row.pcp_words > 0) {
      // Class DH, type 0 on the local bus, type 2 on the remote bus.
      EXPECT_EQ(make_pcp_id_code(0xD, 0, row.pd_words, row.pcp_words), IdCode{row.id_local});
      EXPECT_EQ(make_pcp_id_code(0xD, 2, row.pd_words, row.pcp_words), IdCode{row.id_remote});
    } else {
      EXPECT_EQ(make_id_code(0x93, row.pd_words), IdCode{row.id_local});
      EXPECT_EQ(make_id_code(0x7B, row.pd_words), IdCode{row.id_remote});
    }
  }
}

TEST(IdCode, SupiLayoutsCarryCodesThatDecodeToTheLayout) {
  for (int supi = 1; supi <= kSupiMax; ++supi) {
    for (const auto bus : {interbus::BusKind::local, interbus::BusKind::remote}) {
      const Layout l = make_layout(supi, 0, bus);
      const IdCode id{l.id_code};
      EXPECT_EQ(id.pd_words(), l.pd_words) << supi;
      EXPECT_EQ(id.pcp_words(), l.pcp_words) << supi;
      EXPECT_EQ(id.bus() == BusKind::local, bus == interbus::BusKind::local) << supi;
    }
  }
}

TEST(ProcessImage, Mc6000ReferenceOfExample534ReadsAsBigEndianBytes) {
  // INTERBUS manual 5.3.4: control word 000FH, reference 2500.25 rpm = 09C44000H, Q16 high word first.
  const std::vector<DeviceSpec> ring{{"mc6000", IdCode{0x4DB}, {}}, {"vf1000", IdCode{0x33B}, {}}};
  const BusConfig c = make_bus_config(ring);
  ProcessImage p;
  const Device& mc = *c.find("mc6000");
  const Layout l = make_layout(11, 2);
  const std::span<Word> out = out_slice(p, mc);
  out[0] = 0x000F;
  encode_reference(l, 2500.25, out.subspan(1, 2));
  std::array<std::uint8_t, 6> b{};
  ASSERT_TRUE(p.read_bytes(Area::out, mc.out.byte_offset(), b));
  EXPECT_EQ(b, (std::array<std::uint8_t, 6>{0x00, 0x0F, 0x09, 0xC4, 0x40, 0x00}));
}

}  // namespace
}  // namespace ibs::devices::mc6000
