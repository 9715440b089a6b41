// The MC6000 parameter model: indices (INTERBUS manual 4.2), the named parameters, the store.
#include "ibs/devices/mc6000/parameters.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "ibs/pcp/parameter_store.hpp"

namespace ibs::pcp {
namespace {

using namespace ibs::devices::mc6000;

TEST(Mc6000Parameters, IndexIsNumberPlus5C00) {
  EXPECT_EQ(index_of(407), 0x5D97);  // INTERBUS manual 4.2.1: 407-IBSTU at 5D97H
  EXPECT_EQ(index_of(408), 0x5D98);
  EXPECT_EQ(ParameterRef::number(407), ParameterRef::object(0x5D97));
  EXPECT_EQ(number_of(0x5D97), 407);
  EXPECT_EQ(number_of(0x5C00), 0);
  EXPECT_EQ(number_of(0x5C00 + 999), 999);
  EXPECT_FALSE(number_of(0x5BFF).has_value());
  EXPECT_FALSE(number_of(0x5C00 + 1000).has_value());
}

TEST(Mc6000Parameters, EveryParameterTheSeedsNameIsThere) {
  const std::vector<std::uint16_t> named{4,   15,  77,  80,  81,  82,  83,  84,  85,  91,  107,
                                         108, 300, 402, 405, 406, 407, 408, 409, 416, 417, 418,
                                         419, 420, 428, 439, 440, 443, 444, 445, 446};
  for (const std::uint16_t n : named) EXPECT_NE(find_parameter(kParameters, n), nullptr) << n;
  // LUSTBUS manual 8 makes each error's reaction programmable without naming the parameters: the
  // table's own three (docs/errata.md MC-D7), and no others beside the named ones.
  const std::vector<std::uint16_t> chosen{kReop1, kResio, kRedev};
  for (const std::uint16_t n : chosen) EXPECT_NE(find_parameter(kParameters, n), nullptr) << n;
  EXPECT_EQ(kParameters.size(), named.size() + chosen.size());
  EXPECT_NO_THROW(ParameterStore store(kParameters)) << "the table passes the store's checks";
}

TEST(Mc6000Parameters, DefaultsFromTheSeeds) {
  auto def = [](std::uint16_t n) { return find_parameter(kParameters, n)->default_value; };
  EXPECT_EQ(def(402), kClselOpt1);  // INTERBUS manual 3.2.1
  EXPECT_EQ(def(417), kRsslRcon);
  EXPECT_EQ(def(418), kRsslRcon);
  EXPECT_EQ(def(419), kRsslOpt1);
  EXPECT_EQ(def(420), kRsslRcon);
  EXPECT_EQ(def(443), kFunctionOff);
  EXPECT_EQ(def(444), kFunctionOff);
  EXPECT_EQ(def(406), 2);    // INTERBUS manual 5.3.3: Q16 reference by default
  EXPECT_EQ(def(81), 9600);  // LUSTBUS manual 4
  EXPECT_EQ(def(84), 0);     // LUSTBUS manual 1: no watchdog by factory
  EXPECT_EQ(def(300), kCfconScon);
}

TEST(Mc6000Parameters, Errata407IsTheWritableControlWord408TheStatusWord) {
  // INTERBUS manual 4.2.1 titles both "DRIVECOM status word"; 407's category is "RAM control value".
  const ParameterInfo* ibstu = find_parameter(kParameters, kIbstu);
  const ParameterInfo* ibsta = find_parameter(kParameters, kIbsta);
  EXPECT_TRUE(ibstu->writable());
  EXPECT_EQ(ibstu->category, Category::ram_control);
  EXPECT_FALSE(ibsta->writable());
  EXPECT_EQ(ibsta->category, Category::ram_actual);
}

TEST(Mc6000Parameters, ErrataFunctionSelectorNamesAndRopt1) {
  // INTERBUS manual 3.2.1 writes "FSI00 ... OPT1", 5.3.2 "439-FIS00 = ROPT1": one name, one value.
  EXPECT_EQ(find_parameter(kParameters, 439)->name, "FIS00");
  EXPECT_EQ(find_parameter(kParameters, 440)->name, "FIS01");
  for (const std::uint16_t n :
       {std::uint16_t{439}, std::uint16_t{440}, std::uint16_t{445}, std::uint16_t{446}}) {
    EXPECT_EQ(find_parameter(kParameters, n)->default_value, kFunctionRopt1) << n;
  }
}

TEST(Mc6000Parameters, ErrataMode1IsNotAnMc6000Parameter) {
  // LUSTBUS manual 2.4.2 builds the MC6000 CODE of "1-MODE"; MODE is the VF1000's parameter 1 (7.1) and
  // no seed gives the MC6000 one: not modelled, so a Read of 1 is "object does not exist".
  EXPECT_EQ(find_parameter(kParameters, 1), nullptr);
}

TEST(ParameterStore, RejectsBrokenTables) {
  const std::array<ParameterInfo, 2> dup{
      {{1, "A", DataType::usign8, Category::ram_control, 0, 9, 0, 0},
       {1, "B", DataType::usign8, Category::ram_control, 0, 9, 0, 0}}};
  EXPECT_THROW(ParameterStore{dup}, std::invalid_argument);
  const std::array<ParameterInfo, 1> out{
      {{2, "C", DataType::usign8, Category::ram_control, 0, 9, 10, 0}}};
  EXPECT_THROW(ParameterStore{out}, std::invalid_argument);
  const std::array<ParameterInfo, 1> name{
      {{3, "TOOLONG", DataType::usign8, Category::ram_control, 0, 9, 0, 0}}};
  EXPECT_THROW(ParameterStore{name}, std::invalid_argument);
  const std::array<ParameterInfo, 1> fit{
      {{4, "D", DataType::usign8, Category::ram_control, 0, 300, 0, 0}}};
  EXPECT_THROW(ParameterStore{fit}, std::invalid_argument);
  const std::array<ParameterInfo, 1> order{
      {{5, "E", DataType::integer16, Category::ram_control, 5, -5, 0, 0}}};
  EXPECT_THROW(ParameterStore{order}, std::invalid_argument);
  std::vector<ParameterInfo> many(kMaxParameters + 1);
  for (std::size_t i = 0; i < many.size(); ++i) {
    many[i] = {
        static_cast<std::uint16_t>(i), "X", DataType::usign8, Category::ram_control, 0, 1, 0, 0};
  }
  EXPECT_THROW(ParameterStore{many}, std::invalid_argument);
  try {
    ParameterStore s{out};
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "parameter table: 2-C: default outside min..max");
  }
}

TEST(ParameterStore, PowerOnKeepsEepromAndResetsRam) {
  ParameterStore s(kParameters);
  ASSERT_TRUE(s.set(83, 1234));  // RAM control
  ASSERT_TRUE(s.set(84, 500));   // EEPROM parameter: RAM copy only
  ASSERT_TRUE(s.commit_eeprom(409, 250));
  ASSERT_TRUE(s.set(409, 250));
  s.power_on();
  EXPECT_EQ(s.get(83)->raw, 0U);
  EXPECT_EQ(s.get(84)->raw, 0U) << "never saved";
  EXPECT_EQ(s.get(409)->raw, 250U);
  EXPECT_EQ(s.get(91)->raw, static_cast<std::uint32_t>(kMc6000TypeCode));
  s.factory_defaults();
  EXPECT_EQ(s.get(409)->raw, 0U);
  EXPECT_EQ(s.eeprom(409)->raw, 0U);
  EXPECT_FALSE(s.eeprom(83).has_value());
  EXPECT_FALSE(s.get(999).has_value());
  EXPECT_TRUE(s.set(82, 0x1FF));
  EXPECT_EQ(s.get(82)->raw, 0xFFU) << "a USIGN8 keeps 8 bits";
}

// LUSTBUS manual 11.2.1, the attribute NoInit (0080H): "RAM-control parameters that have this
// attribute will not be pre-initialized, during start up, with the factory setting from the
// parameter list." The store keeps such a RAM control value over a power-on; a RAM actual value
// and an EEPROM value are not RAM control parameters and go as before; 4-PROG = 1 (10 exception
// 1: "overwrites all parameter settings") resets it too. The MC6000's own table marks none (the
// seeds name none; docs/errata.md MC-D11).
TEST(ParameterStore, NoInitKeepsARamControlValueOverAPowerOn) {
  EXPECT_EQ(kAttrNoInit, 0x0080);
  static constexpr std::array<ParameterInfo, 3> table{{
      {10, "KEEP", DataType::usign16, Category::ram_control, 0, 65535, 7, kAttrNoInit},
      {11, "GO", DataType::usign16, Category::ram_control, 0, 65535, 7, 0},
      {12, "ACT", DataType::usign16, Category::ram_actual, 0, 65535, 7, kAttrNoInit},
  }};
  ParameterStore s(table);
  EXPECT_EQ(s.get(10)->raw, 7U) << "a new device starts from the list";
  for (const std::uint16_t n : std::array<std::uint16_t, 3>{10, 11, 12}) ASSERT_TRUE(s.set(n, 99));
  s.power_on();
  EXPECT_EQ(s.get(10)->raw, 99U) << "NoInit: not pre-initialized at the start";
  EXPECT_EQ(s.get(11)->raw, 7U);
  EXPECT_EQ(s.get(12)->raw, 7U) << "NoInit names RAM-control parameters only";
  s.factory_defaults();
  EXPECT_EQ(s.get(10)->raw, 7U);
  for (const ParameterInfo& p : kParameters) EXPECT_EQ(p.attributes & kAttrNoInit, 0) << p.number;
}

}  // namespace
}  // namespace ibs::pcp
