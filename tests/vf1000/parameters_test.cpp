// The VF1000 parameter model: the table's content against the manuals, the index, the value store
// with its RAM/EEPROM rules, the write checks and the description record (INTERBUS manual 4.1.3.3).
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/drive/parameters.hpp"
#include "ibs/vf1000_channel/description.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace ibs::vf1000_channel;
using namespace ibs::drive;
using namespace ibs::devices::vf1000;

const ParameterInfo& get(const ParameterTable& t, std::uint16_t n) {
  const ParameterInfo* p = t.find(n);
  if (p == nullptr) throw std::runtime_error("no parameter " + std::to_string(n));
  return *p;
}

TEST(Vf1000Table, HoldsEveryParameterTheManualsName) {
  const ParameterTable t(parameters());
  const std::vector<std::pair<std::uint16_t, std::string>> named = {
      {1, "MODE"},    {2, "CSEL"},    {3, "CNTL"},    {4, "FSSEL"},   {5, "FSSIO"}, {11, "STAT"},
      {12, "FOUT"},
      {22, "FMAX1"},  {36, "RSTOP"},  {45, "VB2"},    {61, "SOUTA"},  {71, "PROG"}, {81, "SIOC"},
      {82, "SIOA"},   {83, "SIOW"},   {84, "SIOT"},   {85, "SIOF"},   {91, "TYPE"}, {901, "ICNTL"},
      {905, "FDRIV"}, {906, "IB-WD"}, {907, "IBCOD"}, {911, "IBSTA"}, {912, "FIST"}};
  for (const auto& [n, name] : named) {
    const ParameterInfo* p = t.find(n);
    ASSERT_NE(p, nullptr) << n << "-" << name;
    EXPECT_EQ(p->name, name) << n;
  }
  EXPECT_EQ(t.size(), named.size());
}

TEST(Vf1000Table, InterbusFactoryDefaultsOfSection311) {
  const ParameterTable t(parameters());
  EXPECT_EQ(get(t, pnr::kMode).default_value, 4);
  EXPECT_EQ(get(t, pnr::kCsel).default_value, 5);
  EXPECT_EQ(get(t, pnr::kFssel).default_value, 25);
}

TEST(Vf1000Table, InterbusParametersOfSection411) {
  const ParameterTable t(parameters());
  const ParameterInfo& icntl = get(t, pnr::kIcntl);
  EXPECT_EQ(icntl.category, Category::ram_control);
  EXPECT_EQ(icntl.type, DataType::usign16);
  EXPECT_EQ(icntl.min, 0x0000);
  EXPECT_EQ(icntl.max, 0xFFFF);
  const ParameterInfo& fdriv = get(t, pnr::kFdriv);
  EXPECT_EQ(fdriv.type, DataType::integer16);
  EXPECT_EQ(fdriv.category, Category::ram_control);
  EXPECT_EQ(fdriv.unit, "Hz");
  const ParameterInfo& ibwd = get(t, pnr::kIbWd);
  EXPECT_EQ(ibwd.category, Category::eeprom);
  EXPECT_EQ(ibwd.min, 8);
  EXPECT_EQ(ibwd.max, 65535);
  EXPECT_EQ(ibwd.default_value, 200);
  EXPECT_EQ(ibwd.unit, "ms");
  const ParameterInfo& ibcod = get(t, pnr::kIbcod);
  EXPECT_EQ(ibcod.category, Category::eeprom);
  EXPECT_EQ(ibcod.max, 3);
  EXPECT_EQ(ibcod.default_value, 0);
  EXPECT_EQ(get(t, pnr::kIbsta).category, Category::ram_actual);
  EXPECT_EQ(get(t, pnr::kFist).category, Category::ram_actual);
  EXPECT_EQ(get(t, pnr::kFist).type, DataType::integer16);
}

TEST(Vf1000Table, Vb2IsTheDescriptionExampleOfSection41331) {
  const ParameterTable t(parameters());
  const ParameterInfo& vb2 = get(t, pnr::kVb2);
  EXPECT_EQ(vb2.unit, "%");
  EXPECT_EQ(vb2.category, Category::eeprom);
  EXPECT_EQ(vb2.type, DataType::fixpoint16);
  EXPECT_EQ(vb2.min, 0);
  EXPECT_EQ(vb2.max, 20 * 25);
  EXPECT_EQ(vb2.default_value, 20 * 8);
}

TEST(Vf1000Table, Fmax1IsParameter22HoldingThe3E8HOfTheInquiryExample) {
  const ParameterTable t(parameters());
  EXPECT_EQ(t.find(21), nullptr);
  const ParameterInfo& f = get(t, 0x16);
  EXPECT_EQ(f.name, "FMAX1");
  EXPECT_EQ(f.default_value, 0x03E8);
  EXPECT_TRUE(in_range(f, 0x01F4));  // the transfer example's 25 Hz
  EXPECT_DOUBLE_EQ(*to_engineering(f, 0x03E8), 50.0);
}

TEST(Vf1000Table, EveryEntryPassesTheTableChecks) {
  EXPECT_NO_THROW(ParameterTable{parameters()});
  for (const ParameterInfo& p : parameters()) {
    EXPECT_TRUE(in_range(p, p.default_value)) << p.number;
    if (p.type == DataType::fixpoint16) {
      EXPECT_DOUBLE_EQ(p.scale, 0.05) << p.number;
    }
    if (is_single_byte(p.type)) {
      EXPECT_LE(p.max, 0xFF) << p.number;
    }
  }
}

TEST(ParameterTable, FindsByNumberAndRejectsNumbersAbove3FF) {
  const ParameterTable t(parameters());
  EXPECT_EQ(t.find(906)->name, "IB-WD");
  EXPECT_EQ(t.find(0), nullptr);
  EXPECT_EQ(t.find(0x400), nullptr);
  EXPECT_EQ(t.find(0xFFFF), nullptr);
  EXPECT_EQ(t.slot(0xFFFF), -1);
  EXPECT_EQ(&t.params()[static_cast<std::size_t>(t.slot(85))], t.find(85));
}

TEST(ParameterTable, RejectsMalformedTablesSayingWhich) {
  const auto fails_with = [](std::vector<ParameterInfo> v, const std::string& what) {
    try {
      const ParameterTable t(v);
      ADD_FAILURE() << "accepted a table that should fail with: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  const ParameterInfo ok{7, "ABC", "", Category::ram_control, DataType::usign8, 0, 10, 5, 1.0, ""};
  ParameterInfo p = ok;
  p.number = 0x400;
  fails_with({p}, "number above 3FFH");
  fails_with({ok, ok}, "number used twice");
  p = ok;
  p.name = "TOOLONG";
  fails_with({p}, "name must be 1 to 5");
  p = ok;
  p.unit = "x\x01";
  fails_with({p}, "unit must be");
  p = ok;
  p.max = 0x100;
  fails_with({p}, "outside the range of PT_USIGN8");
  p = ok;
  p.min = 11;
  fails_with({p}, "min above max");
  p = ok;
  p.default_value = 11;
  fails_with({p}, "default outside min/max");
  p = ok;
  p.scale = 0.0;
  fails_with({p}, "scale must be positive");
}

TEST(WriteCheck, OrderNumberThenPermissionThenValue) {
  const ParameterTable t(parameters());
  EXPECT_EQ(check_write(nullptr, 0, false), WriteCheck::no_parameter);
  EXPECT_EQ(check_write(t.find(pnr::kIbsta), 0x1234, false), WriteCheck::no_change);
  EXPECT_EQ(check_write(t.find(pnr::kFmax1), 0x01F4, true), WriteCheck::no_change);  // EEPROM
  EXPECT_EQ(check_write(t.find(pnr::kFmax1), 0xFFFF, true), WriteCheck::no_change);
  EXPECT_EQ(check_write(t.find(pnr::kFmax1), 0xFFFF, false), WriteCheck::invalid_value);
  EXPECT_EQ(check_write(t.find(pnr::kFmax1), 0x01F4, false), WriteCheck::ok);
  EXPECT_EQ(check_write(t.find(pnr::kFssio), 0x01F4, true), WriteCheck::ok);        // EEPROM/RAM
  EXPECT_EQ(check_write(t.find(pnr::kIbWd), 7, false), WriteCheck::invalid_value);  // min 8
  EXPECT_EQ(check_write(t.find(pnr::kIbWd), 8, false), WriteCheck::ok);
  EXPECT_EQ(check_write(t.find(pnr::kCntl), 0x0100, true), WriteCheck::invalid_value);  // 1 byte
  EXPECT_EQ(check_write(t.find(pnr::kFdriv), 0xFFEC, true), WriteCheck::ok);            // -20
  EXPECT_EQ(siof_bits_for(WriteCheck::no_parameter), 0x20);
  EXPECT_EQ(siof_bits_for(WriteCheck::no_change), 0x40);
  EXPECT_EQ(siof_bits_for(WriteCheck::invalid_value), 0x80);
  EXPECT_EQ(siof_bits_for(WriteCheck::ok), 0x00);
}

TEST(DescriptionRecord, Vb2GivesTheEighteenBytesOfTheExample) {
  const ParameterTable t(parameters());
  const DescriptionRecord r = make_description(get(t, pnr::kVb2));
  // 'V' 'B' '2' ' ' ' ' '%' ' ' ' ' ' ' ' ' '2' '2' 0 0 1 F4 0 A0 (4.1.3.3.1)
  const DescriptionRecord expected = {'V', 'B', '2', ' ',  ' ',  '%',  ' ',  ' ',  ' ',
                                      ' ', '2', '2', 0x00, 0x00, 0x01, 0xF4, 0x00, 0xA0};
  EXPECT_EQ(r, expected);
  const Description d = decode_description(r);
  EXPECT_EQ(d.name, "VB2");
  EXPECT_EQ(d.unit, "%");
  EXPECT_EQ(d.category, Category::eeprom);
  EXPECT_EQ(d.type, DataType::fixpoint16);
  EXPECT_EQ(d.min, 0);
  EXPECT_EQ(d.max, 0x01F4);
  EXPECT_EQ(d.default_value, 0x00A0);
}

TEST(DescriptionRecord, SignedLimitsGoOutAsTwosComplementAndNoUnitAsBlanks) {
  const ParameterTable t(parameters());
  const DescriptionRecord r = make_description(get(t, pnr::kFdriv));
  EXPECT_EQ(r[11], '7');
  EXPECT_EQ(r[12], 0x80);
  EXPECT_EQ(r[13], 0x00);
  EXPECT_EQ(r[14], 0x7F);
  EXPECT_EQ(r[15], 0xFF);
  const DescriptionRecord m = make_description(get(t, pnr::kMode));
  for (std::size_t i = 5; i < 10; ++i) EXPECT_EQ(m[i], ' ') << i;
  EXPECT_EQ(decode_description(m).unit, "");
  DescriptionRecord bad = m;
  bad[10] = 'x';
  bad[11] = '0';
  EXPECT_FALSE(decode_description(bad).category.has_value());
  EXPECT_FALSE(decode_description(bad).type.has_value());
}

TEST(ParameterStore, StartsAtDefaultsAndKeepsOnlyEepromAcrossPowerUp) {
  const ParameterTable t(parameters());
  ParameterStore s(parameters());
  const auto slot = [&t](std::uint16_t n) { return static_cast<std::size_t>(t.slot(n)); };
  EXPECT_EQ(s.value(slot(pnr::kFmax1)), 0x03E8);
  s.write(slot(pnr::kFmax1), 0x01F4, false);  // EEPROM
  s.write(slot(pnr::kIcntl), 0x000F, true);   // RAM control
  s.write(slot(pnr::kFssio), 0x0100, true);   // EEPROM/RAM, power stage on: RAM only
  EXPECT_EQ(s.value(slot(pnr::kFssio)), 0x0100);
  EXPECT_EQ(s.eeprom_value(slot(pnr::kFssio)), 0);
  s.power_on();
  EXPECT_EQ(s.value(slot(pnr::kFmax1)), 0x01F4);
  EXPECT_EQ(s.value(slot(pnr::kIcntl)), 0);
  EXPECT_EQ(s.value(slot(pnr::kFssio)), 0);
  s.write(slot(pnr::kFssio), 0x0200, false);  // power stage off: RAM and EEPROM
  s.power_on();
  EXPECT_EQ(s.value(slot(pnr::kFssio)), 0x0200);
  s.factory_defaults();
  EXPECT_EQ(s.value(slot(pnr::kFmax1)), 0x03E8);
  EXPECT_EQ(s.eeprom_value(slot(pnr::kFssio)), 0);
}

TEST(IbWd, MonitoringTimeCountsIn50MsStepsAndMaxSwitchesOff) {
  using std::chrono::milliseconds;
  EXPECT_EQ(ib_wd_monitoring_time(65), milliseconds(100));  // the example of 4.1.1
  EXPECT_EQ(ib_wd_monitoring_time(200), milliseconds(200));
  EXPECT_EQ(ib_wd_monitoring_time(8), milliseconds(50));
  EXPECT_EQ(ib_wd_monitoring_time(50), milliseconds(50));
  EXPECT_EQ(ib_wd_monitoring_time(51), milliseconds(100));
  EXPECT_EQ(ib_wd_monitoring_time(65534), milliseconds(65550));
  EXPECT_FALSE(ib_wd_monitoring_time(65535).has_value());
  EXPECT_EQ(static_cast<int>(IbCod::shutdown_e_ibs), 1);
  EXPECT_EQ(kErrorEIbs, 12);
}

}  // namespace
