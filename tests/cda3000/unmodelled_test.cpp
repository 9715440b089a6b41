// Where CANLust manual names a function of the CDA3000 but not its parts, ibs decides not to model it
// (docs/errata.md CAN-E19, CAN-E20); these tests pin what the drive does instead.
//   6.1 (p. 67): "If the parameter setting for response to an error is a warning message WRN the
//       device indicates the warning by way of an appropriately parameterized digital outp[ut]"
//       -- no output, no selector, no function code survives in the seed: the warning shows on
//       the CAN only (the error telegram's reaction 0, status bit 7).
//   5.4.1 (pp. 54-58): EasyDrive control bits FFTB1/2 "select table reference", CUSEL "can be used
//       to switch between characteristic data sets 1 and 2" ("only active with setting 651-CDSSL =
//       6 OPTN2"), UM0 "select user mode" -- the seed says what none of the tables, data sets or
//       user modes holds: the bits are taken and change nothing.
#include <gtest/gtest.h>

#include <string_view>
#include <vector>

#include "bus.hpp"
#include "ibs/canlust/errors.hpp"
#include "ibs/devices/cda3000/descriptor.hpp"
#include "ibs/devices/cda3000/driver.hpp"

namespace ibs::devices::cda3000 {
namespace {

using namespace ibs::canlust;
using test::Bus;
using test::commissioned;

// CAN-E19: the WRN response shows on the bus -- the error telegram carries reaction 0 and status
// bit 7 is set while the drive runs on -- and nowhere else: the drive has no digital output and
// no parameter that would give one a function (the terminals it has are the inputs ENPO and ISD00
// of 2.3).
TEST(Cda3000Unmodelled, WrnShowsOnTheCanOnlyNoDigitalOutputIsModelled) {
  DeviceConfig dc = commissioned(1);
  dc.saved.emplace_back(kRpls, 0);  // E-PLS: WRN (6.1)
  Cda3000 d(dc);
  d.power_on(Time{0});
  while (d.take_frame()) {
  }
  ASSERT_TRUE(d.inject_fault(kErrorPls, Time{0} + 1ms));
  EXPECT_TRUE(d.warning());
  EXPECT_NE(d.status_word() & 0x0080U, 0U);  // status bit 7 (DRIVECOM and EasyDrive: 5.4)
  EXPECT_FALSE(d.fault().has_value());       // the drive runs on
  bool telegram = false;
  while (const auto f = d.take_frame()) {
    if (f->id != kBaseError + 2) continue;  // CDA 1's error identifier (D1: step 2)
    telegram = true;
    EXPECT_EQ(f->data[0], kErrorPls);
    EXPECT_EQ(f->data[2], 0);  // reaction 0: WRN (D6, D7)
  }
  EXPECT_TRUE(telegram);
  for (const ParameterInfo& p : kParameters) {
    EXPECT_EQ(p.text.find("output"), std::string_view::npos) << p.number << " " << p.name;
  }
  EXPECT_FALSE(find_input("OSD00").has_value());
  EXPECT_TRUE(find_input("ISD00").has_value());
}

// CAN-E20: with 651-CDSSL = OPTN2 (the one setting under which 5.4.1 says CUSEL acts) a drive
// driven with STR and CUSEL, FFTB1, FFTB2 and UM0 set runs, reports and holds its parameters
// as one driven with STR alone.
TEST(Cda3000Unmodelled, CuselFftbAndUm0ChangeNothing) {
  const auto run = [](ibs::Word extra) {
    DriverConfig c;
    c.drives.push_back({1, 4, 400.0});
    Driver d(c);
    Bus<Driver> b(d);
    DeviceConfig dc = commissioned(1, 4);
    dc.saved.emplace_back(kCdssl, kOptn2Code);
    b.add(dc);
    b.run_until(Time{150ms});
    d.system_start(b.now());
    EXPECT_EQ(d.set_reference_hz(1, 20.5), ReferenceError::none);
    EXPECT_TRUE(d.set_easydrive(1, static_cast<ibs::Word>((1U << easydrive::kStr) | extra)));
    std::vector<double> trace;
    std::vector<ibs::Word> words;
    for (int i = 0; i < 30; ++i) {
      b.run_for(100ms);
      trace.push_back(d.drive(1).actual_hz);
      words.push_back(d.drive(1).status_word);
    }
    std::vector<std::uint32_t> values;
    for (const ParameterInfo& p : kParameters) {
      if (!p.is_string()) values.push_back(b.drive(0).value(p.number).value_or(0));
    }
    return std::tuple{trace, words, values};
  };
  const auto plain = run(0);
  const auto with_bits = run(static_cast<ibs::Word>((1U << easydrive::kCusel) | (1U << easydrive::kFftb1) |
                                                    (1U << easydrive::kFftb2) | (1U << easydrive::kUm0)));
  // The control telegram with more bits set is a few bit times longer on the bus (bit stuffing):
  // the same motor, a few microseconds later.
  ASSERT_EQ(std::get<0>(plain).size(), std::get<0>(with_bits).size());
  for (std::size_t i = 0; i < std::get<0>(plain).size(); ++i) {
    EXPECT_NEAR(std::get<0>(plain)[i], std::get<0>(with_bits)[i], 1e-3) << i;
  }
  EXPECT_EQ(std::get<1>(plain), std::get<1>(with_bits));
  EXPECT_EQ(std::get<2>(plain), std::get<2>(with_bits));
  EXPECT_NEAR(std::get<0>(with_bits).back(), 20.5, 0.05);
}

}  // namespace
}  // namespace ibs::devices::cda3000
