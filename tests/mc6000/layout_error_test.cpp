// The non-throwing MC6000 layout (try_make_layout, docs/embedding.md "An embedded build"): for
// every 405-SUPI / 406-IBCNF pair around the valid ranges and both bus sides, the same layout as
// make_layout, or the refusal's code with the very message LayoutError carries.
#include <gtest/gtest.h>

#include <string>

#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/base/error.hpp"

namespace ibs::devices::mc6000 {
namespace {

// The rule of 3.2.2 / 3.2.3, written out on its own: which code a pair must get.
ErrorCode expected_code(int supi, int ibcnf) {
  if (supi < 0 || supi > 12) return ErrorCode::layout_setting_out_of_range;
  if (ibcnf < 0 || ibcnf > 4) return ErrorCode::layout_setting_out_of_range;
  if (ibcnf == 4) return ErrorCode::layout_setting_unsupported;
  if (supi == 0) return ErrorCode::none;
  const bool allowed =
      ibcnf == 0 || (ibcnf == 1 && supi >= 7) || ((ibcnf == 2 || ibcnf == 3) && supi >= 10);
  return allowed ? ErrorCode::none : ErrorCode::layout_settings_conflict;
}

TEST(Mc6000LayoutError, EveryPairGivesTheThrowingFormsLayoutOrItsMessage) {
  int refused = 0;
  int accepted = 0;
  for (int supi = -2; supi <= 14; ++supi) {
    for (int ibcnf = -1; ibcnf <= 5; ++ibcnf) {
      for (const auto bus : {interbus::BusKind::local, interbus::BusKind::remote}) {
        SCOPED_TRACE(std::to_string(supi) + "/" + std::to_string(ibcnf));
        const Expected<Layout> r = try_make_layout(supi, ibcnf, bus);
        const ErrorCode want = expected_code(supi, ibcnf);
        if (want == ErrorCode::none) {
          ++accepted;
          ASSERT_TRUE(r.ok()) << r.error().message;
          const Layout l = make_layout(supi, ibcnf, bus);
          EXPECT_EQ(r->supi, l.supi);
          EXPECT_EQ(r->ibcnf, l.ibcnf);
          EXPECT_EQ(r->bus, l.bus);
          EXPECT_EQ(r->pd_words, l.pd_words);
          EXPECT_EQ(r->pcp_words, l.pcp_words);
          EXPECT_EQ(r->exchanges_data, l.exchanges_data);
          EXPECT_EQ(r->id_code, l.id_code);
          EXPECT_EQ(r->reference_words, l.reference_words);
          EXPECT_EQ(r->actual_words, l.actual_words);
          continue;
        }
        ++refused;
        ASSERT_FALSE(r.ok());
        EXPECT_EQ(r.error().code, want);
        try {
          (void)make_layout(supi, ibcnf, bus);
          ADD_FAILURE() << "make_layout accepted what try_make_layout refuses";
        } catch (const LayoutError& e) {
          EXPECT_EQ(r.error().message, e.what());
        }
      }
    }
  }
  EXPECT_GT(accepted, 0);
  EXPECT_GT(refused, 0);
}

TEST(Mc6000LayoutError, TheMessagesNameTheValueAndTheRule) {
  EXPECT_EQ(try_make_layout(13, 2).error().message,
            "405-SUPI = 13 is out of range (0..12, INTERBUS manual 3.2.2)");
  EXPECT_EQ(try_make_layout(11, 5).error().message,
            "406-IBCNF = 5 is out of range (0..4, INTERBUS manual 3.2.3)");
  EXPECT_EQ(try_make_layout(9, 4).error().message,
            "406-IBCNF = 4 (modified LISIM software) is not supported");
  EXPECT_EQ(try_make_layout(7, 2).error().message,
            "406-IBCNF = 2 needs 405-SUPI 10..12, not 7 (INTERBUS manual 3.2.3)");
}

TEST(Mc6000LayoutError, Supi0IsAcceptedWithAnyIbcnfBelowLisim) {
  for (int ibcnf = 0; ibcnf <= 3; ++ibcnf) {
    const Expected<Layout> r = try_make_layout(0, ibcnf);
    ASSERT_TRUE(r.ok());
    EXPECT_FALSE(r->exchanges_data);
    EXPECT_EQ(r->id_code, 0x17B);
  }
}

}  // namespace
}  // namespace ibs::devices::mc6000
