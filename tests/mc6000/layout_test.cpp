// INTERBUS manual 3.2.2 and 3.2.3: which SUPI/IBCNF pairs the MC6000 accepts and how the words read.
#include <gtest/gtest.h>

#include "ibs/devices/mc6000/layout.hpp"

namespace ibs::devices::mc6000 {
namespace {

TEST(Mc6000Layout, EveryPairAgainstTheTableOf323) {
  // Possible SUPI settings per IBCNF: 0: 1..12, 1: 7..12, 2: 10..12, 3: 10..12, 4: refused.
  for (int supi = 1; supi <= 12; ++supi) {
    for (int ibcnf = 0; ibcnf <= 4; ++ibcnf) {
      const bool allowed = (ibcnf == 0) || (ibcnf == 1 && supi >= 7) || ((ibcnf == 2 || ibcnf == 3) && supi >= 10);
      if (allowed) {
        EXPECT_NO_THROW(make_layout(supi, ibcnf)) << supi << "/" << ibcnf;
      } else {
        EXPECT_THROW(make_layout(supi, ibcnf), LayoutError) << supi << "/" << ibcnf;
      }
    }
  }
}

TEST(Mc6000Layout, RefusalsSayWhat) {
  try {
    make_layout(7, 2);
    FAIL();
  } catch (const LayoutError& e) {
    EXPECT_STREQ(e.what(), "406-IBCNF = 2 needs 405-SUPI 10..12, not 7 (INTERBUS manual 3.2.3)");
  }
  try {
    make_layout(9, 4);
    FAIL();
  } catch (const LayoutError& e) {
    EXPECT_STREQ(e.what(), "406-IBCNF = 4 (modified LISIM software) is not supported");
  }
  EXPECT_THROW(make_layout(13, 0), LayoutError);
  EXPECT_THROW(make_layout(-1, 0), LayoutError);
  EXPECT_THROW(make_layout(11, 5), LayoutError);
}

TEST(Mc6000Layout, ErratumPd6Ibcnf4LisimIsRefusedEvenWithItsSupi9) {
  // INTERBUS manual 3.2.3: IBCNF 4 is "Modificated software LISIM" with SUPI 9; no section gives the
  // words' meaning, so ibs refuses it (erratum PD6) with every SUPI, its own 9 included.
  EXPECT_EQ(allowed_supi(Ibcnf::lisim).first, 9);
  EXPECT_EQ(allowed_supi(Ibcnf::lisim).last, 9);
  for (int supi = 0; supi <= kSupiMax; ++supi) {
    for (const auto bus : {interbus::BusKind::local, interbus::BusKind::remote}) {
      try {
        make_layout(supi, 4, bus);
        ADD_FAILURE() << "SUPI " << supi << " with IBCNF 4 accepted";
      } catch (const LayoutError& e) {
        if (supi == 9) {
          EXPECT_STREQ(e.what(), "406-IBCNF = 4 (modified LISIM software) is not supported");
        }
      }
    }
  }
}

TEST(Mc6000Layout, Supi0ExchangesNoDataAndReadsAsConfiguration4) {
  const Layout l = make_layout(0, 2, interbus::BusKind::local);
  EXPECT_FALSE(l.exchanges_data);
  EXPECT_EQ(l.id_code, 0x193);
  EXPECT_EQ(make_layout(0, 0, interbus::BusKind::remote).id_code, 0x17B);
}

TEST(Mc6000Layout, DefaultLayoutOf534) {
  const Layout l = make_layout(11, 2);
  EXPECT_EQ(l.pd_words, 3);
  EXPECT_EQ(l.pcp_words, 1);
  EXPECT_EQ(l.id_code, 0x4DB);
  EXPECT_EQ(make_layout(11, 2, interbus::BusKind::local).id_code, 0x4D3);
  std::array<Word, 2> w{};
  encode_reference(l, 2500.25, w);
  EXPECT_EQ(w[0], 0x09C4);
  EXPECT_EQ(w[1], 0x4000);
  EXPECT_DOUBLE_EQ(decode_reference(l, w), 2500.25);
  encode_reference(l, -1.0, w);
  EXPECT_EQ(w[0], 0xFFFF);
  EXPECT_EQ(w[1], 0x0000);
}

TEST(Mc6000Layout, SixteenBitAndSpeedTorqueLayouts) {
  const Layout l16 = make_layout(7, 1);
  EXPECT_EQ(l16.reference_words, 1);
  std::array<Word, 1> w1{};
  encode_reference(l16, -1500.4, w1);
  EXPECT_EQ(w1[0], static_cast<Word>(-1500));
  const Layout st = make_layout(12, 3);
  std::array<Word, 2> a{};
  encode_actual(st, {1234.0, -56.0}, a);
  EXPECT_EQ(a[0], 1234);
  EXPECT_EQ(a[1], static_cast<Word>(-56));
  const Actual back = decode_actual(st, a);
  EXPECT_DOUBLE_EQ(back.value, 1234.0);
  EXPECT_DOUBLE_EQ(back.torque, -56.0);
  // IBCNF 0: no reference transfer, all actual words 0.
  const Layout none = make_layout(12, 0);
  EXPECT_EQ(none.reference_words, 0);
  EXPECT_EQ(none.actual_words, 0);
}

TEST(Mc6000Layout, Q16Saturates) {
  EXPECT_EQ(to_q16(1e9), std::numeric_limits<std::int32_t>::max());
  EXPECT_EQ(to_q16(-1e9), std::numeric_limits<std::int32_t>::min());
  EXPECT_DOUBLE_EQ(from_q16(to_q16(0.5)), 0.5);
}

}  // namespace
}  // namespace ibs::devices::mc6000
