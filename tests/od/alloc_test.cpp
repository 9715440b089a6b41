// The cycle path allocates nothing: after construction, no access to a Store allocates (this file
// replaces operator new for the whole test binary).
#include <gtest/gtest.h>

#include "../support/counting_new.hpp"
#include "ibs/od/store.hpp"
#include "sample.hpp"

namespace ibs::od {
namespace {

TEST(OdAllocation, NoStoreAccessAllocates) {
  Store s(test::kCda);
  const ibs::test::AllocationCounter count;
  for (Slot i = 0; i < s.size(); ++i) {
    s.set(i, s.ram(i) + 1);
    s.write(i, s.ram(i), false);
  }
  s.set_text(test::kCda.slot(90), "abc");
  s.write_text(test::kCda.slot(90), "abcd", false);
  s.save(Storage::flash);
  s.power_on();
  s.factory_defaults();
  s.snapshot();
  s.restore_data_set();
  s.keep_data_set();
  EXPECT_EQ(count.count(), 0);
}

}  // namespace
}  // namespace ibs::od
