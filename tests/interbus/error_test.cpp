// The error boundary itself (ibs/base/error.hpp): Error and Expected as the non-throwing
// configuration API returns them, the codes' names, and detail::require, which the constructors of
// the default build throw through.
#include "ibs/base/error.hpp"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ibs {
namespace {

static_assert(IBS_EXCEPTIONS == 1, "the test suite is the default build: the throwing API exists");
static_assert(IBS_EMBEDDED == 0);

TEST(Error, NoErrorIsFalseAnErrorIsTrue) {
  const Error none;
  EXPECT_TRUE(none.ok());
  EXPECT_FALSE(static_cast<bool>(none));
  const Error refused{ErrorCode::master_driver_count, "master loop: 1 drivers for 2 devices"};
  EXPECT_FALSE(refused.ok());
  EXPECT_TRUE(static_cast<bool>(refused));
  EXPECT_EQ(refused,
            (Error{ErrorCode::master_driver_count, "master loop: 1 drivers for 2 devices"}));
  EXPECT_NE(refused, none);
}

TEST(Error, EveryCodeHasItsOwnName) {
  std::set<std::string_view> names;
  const auto last = static_cast<int>(ErrorCode::board_no_answer);
  for (int c = 0; c <= last; ++c) {
    const std::string_view name = to_string(static_cast<ErrorCode>(c));
    EXPECT_NE(name, "?") << c;
    EXPECT_TRUE(names.insert(name).second) << name;
  }
  EXPECT_EQ(to_string(ErrorCode::none), "none");
  EXPECT_EQ(to_string(ErrorCode::layout_setting_out_of_range), "layout_setting_out_of_range");
  EXPECT_EQ(to_string(ErrorCode::bus_too_many_pcp_devices), "bus_too_many_pcp_devices");
  EXPECT_EQ(to_string(static_cast<ErrorCode>(last + 1)), "?");
}

TEST(Expected, HoldsTheValueOrTheError) {
  Expected<std::string> good = std::string("layout");
  ASSERT_TRUE(good.ok());
  EXPECT_TRUE(static_cast<bool>(good));
  EXPECT_EQ(good.value(), "layout");
  EXPECT_EQ(good->size(), 6U);
  EXPECT_EQ(good.error().code, ErrorCode::none);
  good.value() += "s";
  EXPECT_EQ(std::move(good).value(), "layouts");

  const Expected<int> bad = Error{ErrorCode::layout_setting_unsupported, "not supported"};
  EXPECT_FALSE(bad.ok());
  EXPECT_FALSE(static_cast<bool>(bad));
  EXPECT_EQ(bad.error().code, ErrorCode::layout_setting_unsupported);
  EXPECT_EQ(bad.error().message, "not supported");
}

struct Refusal : Error {
  std::string_view setting;
};

TEST(Expected, CarriesAnErrorOfItsOwnType) {
  const Expected<int, Refusal> bad =
      Refusal{{ErrorCode::setting_out_of_range, "too high"}, "watchdog_ms"};
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().setting, "watchdog_ms");
  EXPECT_EQ(bad.error().message, "too high");
}

TEST(ExpectedDeathTest, AskingAnErrorForItsValueAborts) {
  const Expected<int> bad = Error{ErrorCode::layout_setting_out_of_range, "405-SUPI = 13"};
  EXPECT_DEATH((void)bad.value(), "Expected::value\\(\\) asked of an error");
}

TEST(ErrorDeathTest, AbortWithNamesTheCodeAndTheMessage) {
  EXPECT_DEATH(detail::abort_with({ErrorCode::channel_width_invalid, "PCP channel of 3 words"}),
               "ibs: channel_width_invalid: PCP channel of 3 words");
}

struct WithSetting : std::invalid_argument {
  explicit WithSetting(const Refusal& r) : std::invalid_argument(r.message), setting(r.setting) {}
  std::string_view setting;
};

TEST(Require, NothingForNoErrorAndTheExceptionWithTheMessageOtherwise) {
  EXPECT_NO_THROW(detail::require<std::invalid_argument>(Error{}));
  try {
    detail::require<std::invalid_argument>(Error{ErrorCode::channel_capacity_zero, "at least 1"});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "at least 1");
  }
  // An exception that can be made from the error itself is: it keeps what the error carries.
  try {
    detail::require<WithSetting>(
        Refusal{{ErrorCode::setting_out_of_range, "too high"}, "reset_time"});
    FAIL() << "no exception";
  } catch (const WithSetting& e) {
    EXPECT_STREQ(e.what(), "too high");
    EXPECT_EQ(e.setting, "reset_time");
  }
}

}  // namespace
}  // namespace ibs
