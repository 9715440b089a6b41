// The cycle path allocates nothing: after construction, no access to a Store or a StoredServed
// allocates, whatever it is asked (this file replaces operator new for the whole test binary).
#include <gtest/gtest.h>

#include <random>

#include "../support/counting_new.hpp"
#include "ibs/od/stored_served.hpp"
#include "sample.hpp"

namespace ibs::od {
namespace {

using namespace std::chrono_literals;

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

TEST(OdAllocation, NoServedAccessAllocates) {
  for (const Dictionary* d : {&test::kVf, &test::kMc, &test::kCda}) {
    StoredServedConfig c;
    c.timing.download_check = 5ms;
    StoredServed served(*d, c);
    ServedParameters& p = served;
    std::mt19937 gen(7);
    char text[100];
    const ibs::test::AllocationCounter count;
    Time now{};
    for (int i = 0; i < 20000; ++i) {
      now += 1ms;
      const auto s = static_cast<Slot>(gen() % (d->size() + 1));
      const Raw r = gen() % 2 == 0 ? static_cast<Raw>(gen() % 8) : static_cast<Raw>(gen());
      switch (gen() % 8) {
        case 0:
          p.read(s, now);
          break;
        case 1:
          static_cast<void>(p.check(s, r, now));
          break;
        case 2:
          p.refuse(Refusal::transfer_error);
          break;
        case 3:
          p.clear_error_flags(0xFF);
          break;
        case 4:
          p.read_text(s, text, now);
          break;
        case 5:
          p.write_text(s, "PRESS", now);
          break;
        default:
          p.write(s, r, now);
          break;
      }
      p.advance(now);
    }
    served.power_on();
    EXPECT_EQ(count.count(), 0);
  }
}

}  // namespace
}  // namespace ibs::od
