// CODE strings (2.4, 5.2, 11.3, 11.6), VALUE strings and every data type of 2.3 both ways, the
// descriptions of 11.1 / 11.2, substitution texts (11.3) and the 85-SIOF/SERR rules (9.2).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/siof.hpp"
#include "ibs/lustbus/timing.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::lustbus {
namespace {

// ---- CODE ---------------------------------------------------------------------------------------

TEST(Code, IsFiveDecimalDigits) {
  EXPECT_EQ(Code::parse("00112")->number(), 112U);
  EXPECT_FALSE(Code::parse("0112").has_value());
  EXPECT_FALSE(Code::parse("001120").has_value());
  EXPECT_FALSE(Code::parse("00A12").has_value());
  EXPECT_EQ(Code::from_number(1)->text(), "00001");
  EXPECT_EQ(Code::from_number(99999)->text(), "99999");
  EXPECT_FALSE(Code::from_number(100000).has_value());
}

TEST(VfCode, Coding241) {
  // sprintf("000%02u", 1) of 2.4.1 builds 00001: device digit 0, a basis parameter (11.1).
  EXPECT_EQ(as_vf_code(make_code(1)), (VfCode{VfSpecifier::value, 0, 1}));
  EXPECT_EQ(as_vf_code(make_code(112)), (VfCode{VfSpecifier::value, 1, 12}));
  EXPECT_EQ(as_vf_code(make_code(10105)), (VfCode{VfSpecifier::description, 1, 5}));
  EXPECT_FALSE(as_vf_code(make_code(20077)));  // specifier 2: the enhanced protocol
  EXPECT_FALSE(as_vf_code(make_code(1112)));   // data set 1
  EXPECT_FALSE(as_vf_code(make_code(212)));    // device 2
  EXPECT_EQ(vf_code(12)->text(), "00112");
  EXPECT_EQ(vf_code(12, VfSpecifier::description)->text(), "10112");
  EXPECT_EQ(vf_code(1, VfSpecifier::value, 0)->text(), "00001");
  EXPECT_FALSE(vf_code(100));
}

TEST(McCode, Coding242WithSharedSubstitutionAndPosmod) {
  EXPECT_EQ(as_mc_code(make_code(20077)), (McCode{McCodeKind::value, 77}));
  EXPECT_EQ(as_mc_code(make_code(30077)), (McCode{McCodeKind::description, 77}));
  EXPECT_EQ(as_mc_code(make_code(60004)), (McCode{McCodeKind::special, 4}));
  EXPECT_EQ(as_mc_code(make_code(61300)), (McCode{McCodeKind::substitution_text, 300}));
  EXPECT_EQ(as_mc_code(make_code(49999)), (McCode{McCodeKind::posmod, 0}));
  for (const unsigned p : {81U, 82U, 83U, 84U, 85U, 91U}) {
    EXPECT_EQ(as_mc_code(shared_code(p)), (McCode{McCodeKind::shared, static_cast<std::uint16_t>(p)}));
    EXPECT_EQ(shared_code(p).number(), p);
    EXPECT_TRUE(as_vf_code(shared_code(p)).has_value());  // both families answer them (5.2)
  }
  EXPECT_FALSE(as_mc_code(make_code(86)));
  EXPECT_FALSE(as_mc_code(make_code(5)));      // 6.2.3's printed CODE (LB-E5)
  EXPECT_FALSE(as_mc_code(make_code(21077)));  // data set 1
  EXPECT_FALSE(as_mc_code(make_code(10077)));
  EXPECT_FALSE(as_mc_code(make_code(40077)));
  EXPECT_EQ(mc_code(McCodeKind::value, 1)->text(), "20001");  // sprintf("20%03u", 1)
  EXPECT_EQ(mc_code(McCodeKind::substitution_text, 107)->text(), "61107");
  EXPECT_FALSE(mc_code(McCodeKind::value, 1000));
  EXPECT_FALSE(mc_code(McCodeKind::shared, 86));
  EXPECT_TRUE(reads_siof(kSiofCode));
  EXPECT_TRUE(reads_siof(make_code(20085)));
  EXPECT_FALSE(reads_siof(make_code(20086)));
}

// ---- VALUE formats (2.3) -------------------------------------------------------------------------

TEST(ValueFormat, Vf1000IsExactlyFourCapitalHexDigits) {
  EXPECT_EQ(format_raw(Family::standard, 0).value.view(), "0000");
  EXPECT_EQ(format_raw(Family::standard, 0x3E8).value.view(), "03E8");
  EXPECT_EQ(format_raw(Family::standard, 0xFFFF).value.view(), "FFFF");
  EXPECT_EQ(format_raw(Family::standard, 0x10000).error, ValueError::out_of_range);
  EXPECT_EQ(parse_raw(Family::standard, "03E8").value, 0x3E8U);
  EXPECT_EQ(parse_raw(Family::standard, "3E8").error, ValueError::wrong_length);
  EXPECT_EQ(parse_raw(Family::standard, "003E8").error, ValueError::wrong_length);
  EXPECT_EQ(parse_raw(Family::standard, "03e8").error, ValueError::lower_case);
  EXPECT_EQ(parse_raw(Family::standard, "03G8").error, ValueError::not_hex);
  EXPECT_EQ(parse_raw(Family::standard, "").error, ValueError::empty);
}

TEST(ValueFormat, Mc6000IsOneToHundredCharactersLeadingZerosOptional) {
  EXPECT_EQ(format_raw(Family::enhanced, 0).value.view(), "0");
  EXPECT_EQ(format_raw(Family::enhanced, 0x842666).value.view(), "842666");
  EXPECT_EQ(format_raw(Family::enhanced, 0xFFFFFFFF).value.view(), "FFFFFFFF");
  EXPECT_EQ(format_raw_width(0x4FA4000, 8).value.view(), "04FA4000");
  EXPECT_EQ(parse_raw(Family::enhanced, "2").value, 2U);
  EXPECT_EQ(parse_raw(Family::enhanced, "0002").value, 2U);
  EXPECT_EQ(parse_raw(Family::enhanced, std::string(92, '0') + "FFFFFFFF").value, 0xFFFFFFFFU);
  EXPECT_EQ(parse_raw(Family::enhanced, std::string(101, '0')).error, ValueError::too_long);
  EXPECT_EQ(parse_raw(Family::enhanced, "100000000").error, ValueError::too_long);
  EXPECT_EQ(parse_raw(Family::enhanced, "").error, ValueError::empty);
  EXPECT_EQ(parse_raw(Family::enhanced, "-1").error, ValueError::not_hex);
  EXPECT_EQ(parse_raw(Family::enhanced, " 1").error, ValueError::not_hex);
}

// ---- data types (2.3.1, 2.3.2) -------------------------------------------------------------------

TEST(DataTypes, FamiliesListTheirTables) {
  EXPECT_TRUE(family_has(Family::standard, DataType::binary8));
  EXPECT_TRUE(family_has(Family::standard, DataType::vf_error));
  EXPECT_FALSE(family_has(Family::standard, DataType::int32q16));
  EXPECT_TRUE(family_has(Family::enhanced, DataType::float_ieee));
  EXPECT_FALSE(family_has(Family::enhanced, DataType::binary8));
  for (const auto t : {DataType::usign8, DataType::usign16, DataType::fixpoint16, DataType::password}) {
    EXPECT_TRUE(family_has(Family::standard, t) && family_has(Family::enhanced, t)) << to_string(t);
  }
}

TEST(DataTypes, EightBitTypes) {
  for (const auto t : {DataType::usign8, DataType::binary8}) {
    EXPECT_EQ(encode(Family::standard, t, 255).value.view(), "00FF");
    EXPECT_EQ(encode(Family::standard, t, 256).error, ValueError::out_of_range);
    EXPECT_EQ(encode(Family::standard, t, -1).error, ValueError::out_of_range);
    EXPECT_EQ(decode(Family::standard, t, "00FF").value, 255.0);
    EXPECT_EQ(decode(Family::standard, t, "0100").error, ValueError::out_of_range);
  }
  EXPECT_EQ(encode(Family::enhanced, DataType::usign8, 3).value.view(), "3");
}

TEST(DataTypes, SixteenBitUnsignedAndPassword) {
  for (const auto t : {DataType::usign16, DataType::password}) {
    EXPECT_EQ(encode(Family::standard, t, 65535).value.view(), "FFFF");
    EXPECT_EQ(encode(Family::enhanced, t, 65535).value.view(), "FFFF");
    EXPECT_EQ(encode(Family::enhanced, t, 65536).error, ValueError::out_of_range);
    EXPECT_EQ(decode(Family::enhanced, t, "10000").error, ValueError::out_of_range);
    EXPECT_EQ(decode(Family::standard, t, "0000").value, 0.0);
  }
}

TEST(DataTypes, Fixpoint16RoundsToTheNearestStepUpTo3276p75) {
  EXPECT_EQ(encode(Family::standard, DataType::fixpoint16, 23.15).value.view(), "01CF");  // LB-D8
  EXPECT_EQ(encode(Family::standard, DataType::fixpoint16, 50.0).value.view(), "03E8");
  EXPECT_EQ(encode(Family::standard, DataType::fixpoint16, 3276.75).value.view(), "FFFF");
  EXPECT_EQ(encode(Family::standard, DataType::fixpoint16, 3276.80).error, ValueError::out_of_range);  // LB-E6
  EXPECT_EQ(encode(Family::standard, DataType::fixpoint16, -0.05).error, ValueError::out_of_range);
  EXPECT_DOUBLE_EQ(decode(Family::enhanced, DataType::fixpoint16, "FFFF").value, 3276.75);
  EXPECT_DOUBLE_EQ(decode(Family::standard, DataType::fixpoint16, "0001").value, 0.05);
}

TEST(DataTypes, Integer16IsSixteenBitTwosComplement) {
  EXPECT_EQ(encode(Family::enhanced, DataType::integer16, -1).value.view(), "FFFF");
  EXPECT_EQ(encode(Family::enhanced, DataType::integer16, -2).value.view(), "FFFE");
  EXPECT_EQ(encode(Family::enhanced, DataType::integer16, -32768).value.view(), "8000");
  EXPECT_EQ(encode(Family::enhanced, DataType::integer16, 32767).value.view(), "7FFF");
  EXPECT_EQ(encode(Family::enhanced, DataType::integer16, 32768).error, ValueError::out_of_range);
  EXPECT_EQ(encode(Family::enhanced, DataType::integer16, -32769).error, ValueError::out_of_range);
  EXPECT_EQ(decode(Family::enhanced, DataType::integer16, "FFFF").value, -1.0);
  EXPECT_EQ(decode(Family::enhanced, DataType::integer16, "5").value, 5.0);
  EXPECT_EQ(decode(Family::enhanced, DataType::integer16, "FFFFFFFF").error, ValueError::out_of_range);  // LB-D9
}

TEST(DataTypes, Int32Q16SpansTheFullSigned32BitRange) {
  EXPECT_EQ(encode(Family::enhanced, DataType::int32q16, 333.254).value.view(), "14D4106");  // 6.2.3
  EXPECT_EQ(encode(Family::enhanced, DataType::int32q16, 132.15).value.view(), "842666");    // 7.2.1
  EXPECT_DOUBLE_EQ(decode(Family::enhanced, DataType::int32q16, "4FA4000").value, 1274.25);  // 6.1.1.2
  EXPECT_EQ(encode(Family::enhanced, DataType::int32q16, -1.0).value.view(), "FFFF0000");
  EXPECT_EQ(encode(Family::enhanced, DataType::int32q16, -32768.0).value.view(), "80000000");
  EXPECT_EQ(encode(Family::enhanced, DataType::int32q16, 32768.0).error, ValueError::out_of_range);
  EXPECT_DOUBLE_EQ(decode(Family::enhanced, DataType::int32q16, "7FFFFFFF").value, 2147483647.0 / 65536.0);
  EXPECT_EQ(encode(Family::standard, DataType::int32q16, 1.0).error, ValueError::wrong_type);
}

TEST(DataTypes, FloatIeeeIsThePattern) {
  EXPECT_EQ(encode(Family::enhanced, DataType::float_ieee, 1.0).value.view(), "3F800000");
  EXPECT_EQ(encode(Family::enhanced, DataType::float_ieee, -2.5).value.view(), "C0200000");
  EXPECT_EQ(encode(Family::enhanced, DataType::float_ieee, 0.0).value.view(), "0");
  EXPECT_DOUBLE_EQ(decode(Family::enhanced, DataType::float_ieee, "3F800000").value, 1.0);
  EXPECT_EQ(decode(Family::enhanced, DataType::float_ieee, "7FC00000").error, ValueError::not_finite);
  EXPECT_EQ(encode(Family::enhanced, DataType::float_ieee, 1e39).error, ValueError::out_of_range);
  EXPECT_EQ(encode(Family::enhanced, DataType::float_ieee, std::nan("")).error, ValueError::not_finite);
}

TEST(DataTypes, ErrorStructures) {
  // PT_VF_ERROR: high byte error number, low byte time (2.3.1); FFFF (erased EEPROM) = none.
  const VfError e = vf_error_of(0x0203);
  EXPECT_EQ(e.code, 2);
  EXPECT_EQ(e.time_tenths, 3);
  EXPECT_FALSE(vf_error_of(0xFFFF).code.has_value());
  EXPECT_EQ(vf_error_bits(e), 0x0203U);
  EXPECT_EQ(format_typed(Family::standard, DataType::vf_error, 0x0203).value.view(), "0203");
  EXPECT_EQ(to_engineering(DataType::vf_error, 0x0203).error, ValueError::wrong_type);
  // PT_MC_ERROR: number bits 0-7, location 8-15, time 16-31 (PCP-E6).
  const McError m{0x12, 0x34, 0x5678};
  EXPECT_EQ(encode_mc_error(m), 0x56783412U);
  EXPECT_EQ(decode_mc_error(0x56783412U), m);
  EXPECT_EQ(format_typed(Family::enhanced, DataType::mc_error, encode_mc_error(m)).value.view(), "56783412");
  EXPECT_EQ(parse_typed(Family::enhanced, DataType::mc_error, "56783412").value, 0x56783412U);
  EXPECT_EQ(from_engineering(DataType::mc_error, 1.0).error, ValueError::wrong_type);
}

TEST(DataTypes, EveryTypeRoundTripsItsPatterns) {
  const DataType all[] = {DataType::binary8,   DataType::usign8,   DataType::usign16,
                          DataType::fixpoint16, DataType::integer16, DataType::int32q16,
                          DataType::float_ieee, DataType::vf_error,  DataType::mc_error,
                          DataType::password};
  const std::uint32_t patterns[] = {0, 1, 0x7F, 0xFF, 0x100, 0x7FFF, 0x8000, 0xFFFF, 0x10000,
                                    0x3F800000, 0x7FFFFFFF, 0x80000000, 0xFFFFFFFF};
  for (const auto f : {Family::standard, Family::enhanced}) {
    for (const auto t : all) {
      for (const auto p : patterns) {
        const auto v = format_typed(f, t, p);
        if (!v.ok()) continue;
        const auto back = parse_typed(f, t, v.value.view());
        ASSERT_TRUE(back.ok()) << to_string(f) << " " << to_string(t) << " " << p;
        EXPECT_EQ(back.value, p);
        const auto eng = to_engineering(t, p);
        if (eng.ok()) {
          const auto bits = from_engineering(t, eng.value);
          ASSERT_TRUE(bits.ok()) << to_string(t) << " " << p;
          EXPECT_EQ(bits.value, p) << to_string(t);
        }
      }
    }
  }
}

// ---- descriptions (11.1, 11.2) and substitution texts (11.3) -------------------------------------

TEST(VfDescription, TwentySixCharactersRightJustified) {
  const auto v = format_vf_description("FMAX1", "Hz", '2', '2', 0, 19999, 1000);
  ASSERT_TRUE(v);
  EXPECT_EQ(v->view(), " FMAX1    Hz2200004E1F03E8");
  EXPECT_EQ(v->size(), kVfDescriptionLength);
  const auto d = parse_vf_description(v->view());
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d.value.name_view(), "FMAX1");
  EXPECT_EQ(d.value.unit_view(), "Hz");
  EXPECT_EQ(d.value.kind, '2');
  EXPECT_EQ(vf_type_from_char(d.value.type), DataType::fixpoint16);
  EXPECT_EQ(d.value.max, 19999);
  EXPECT_EQ(d.value.basis, 1000);
  EXPECT_EQ(parse_vf_description("FMAX1     Hz2200004E1F03E8").error, DescriptionError::bad_name);
  EXPECT_EQ(parse_vf_description(" FMAX1    Hz9200004E1F03E8").error, DescriptionError::bad_kind);
  EXPECT_EQ(parse_vf_description(" FMAX1    Hz2700004E1F03E8").error, DescriptionError::bad_type);
  EXPECT_EQ(parse_vf_description(" FMAX1    Hz2200004e1F03E8").error, DescriptionError::bad_value);
  EXPECT_EQ(parse_vf_description(" FMAX1    Hz2200004E1F03E").error, DescriptionError::wrong_length);
  EXPECT_FALSE(format_vf_description("fmax", "", '2', '2', 0, 0, 0));
  EXPECT_FALSE(format_vf_description("TOOLONG", "", '2', '2', 0, 0, 0));
}

TEST(McDescription, ElementsAtTheTablesOffsetsFortyTwoOrFortyThree) {
  McDescription m;
  m.name = {'S', 'P', 'E', 'E', 'D', '\0'};
  m.unit = 1;
  m.kind = '0';
  m.type = '5';
  m.min = 0x80000000;
  m.max = 0x7FFFFFFF;
  m.reference = 0;
  m.level = 0x21;
  m.attribute = kAttrShowText;
  m.hardware_filter = 0x0100;
  m.structure_filter = 0x0010;  // EMaster
  m.subject_area = 9;           // SIO
  m.activity_area = 8;          // SC_PMOD
  const auto v = format_mc_description(m);
  ASSERT_TRUE(v);
  EXPECT_EQ(v->size(), kMcDescriptionLength);  // LB-E9
  const auto d = parse_mc_description(v->view());
  ASSERT_TRUE(d.ok()) << to_string(d.error);
  EXPECT_EQ(d.value.name_view(), "SPEED");
  EXPECT_EQ(d.value.min, 0x80000000U);
  EXPECT_EQ(d.value.max, 0x7FFFFFFFU);
  EXPECT_EQ(d.value.read_level(), 1);
  EXPECT_EQ(d.value.write_level(), 2);
  EXPECT_EQ(d.value.attribute, kAttrShowText);
  EXPECT_EQ(d.value.hardware_filter, 0x0100);
  EXPECT_EQ(d.value.structure_filter, 0x0010);
  EXPECT_EQ(d.value.subject_area, 9);
  EXPECT_EQ(d.value.activity_area, 8);
  EXPECT_TRUE(parse_mc_description(v->view().substr(0, 42)).ok());
  EXPECT_EQ(parse_mc_description(v->view().substr(0, 41)).error, DescriptionError::wrong_length);
  // LB-D10: binary elements travel as bytes, frame characters included (ETX as a level of 03H,
  // ACK as subject area 6 SCON, EOT as activity area 4 SC_SYS); a byte >= 80H cannot travel.
  m.level = 0x03;
  m.subject_area = 6;
  m.activity_area = 4;
  const auto framed = format_mc_description(m);
  ASSERT_TRUE(framed);
  const auto back = parse_mc_description(framed->view());
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back.value.level, 0x03);
  EXPECT_EQ(back.value.subject_area, 6);
  EXPECT_EQ(back.value.activity_area, 4);
  m.hardware_filter = kHwBrake;
  EXPECT_FALSE(format_mc_description(m));
  EXPECT_FALSE(Value::from("A\x03"));  // an ordinary VALUE still refuses ETX (LB-D12)
  EXPECT_EQ(kHwMptc, 0x4000);  // LB-E8
}

// 11.2.1's tables as printed, row by row (name, "Bit-position", "Bit-mask" / "Sequential Number",
// "Value"): every row is the library's, every mask is 1 << its bit -- but MPTC, printed "14
// 8000H" beside Brake's "15 8000H" (LB-E8): the printed mask is corrected to the bit position's
// 4000H, and 8000H stays Brake's alone.
TEST(McDescription1121, EveryRowOfTheTablesAsPrinted) {
  struct Printed {
    std::string_view name;
    unsigned bit;
    unsigned mask;
  };
  const Printed attributes[] = {{"ShowParaText", 2, 0x0004}, {"ShowNoFract", 3, 0x0008}, {"ShowFract1", 4, 0x0010},
                                {"ShowText", 5, 0x0020},     {"InitControl", 6, 0x0040}, {"NoInit", 7, 0x0080},
                                {"ShowHex", 8, 0x0100},      {"Password", 9, 0x0200}};
  const Printed hardware[] = {{"Resolver", 0, 0x0001},      {"EncoderSin", 1, 0x0002},   {"EncoderRec", 2, 0x0004},
                              {"EncdSsiSingle", 3, 0x0008}, {"EncdSsiMulti", 4, 0x0010}, {"Option1", 5, 0x0020},
                              {"Option2", 6, 0x0040},       {"ASM", 7, 0x0080},          {"SM", 8, 0x0100},
                              {"Special-drive", 9, 0x0200}, {"EA1", 10, 0x0400},         {"EA2", 11, 0x0800},
                              {"CAN", 12, 0x1000},          {"Extended Memory", 13, 0x2000},
                              {"MPTC", 14, 0x8000},         {"Brake", 15, 0x8000}};
  const Printed structure[] = {{"TorqueCtrl", 0, 0x0001}, {"SpeedCtrl", 1, 0x0002}, {"PosCtrl", 2, 0x0004},
                               {"VF_Conv", 3, 0x0008},    {"EMaster", 4, 0x0010},   {"ESlave", 5, 0x0020}};
  const auto check = [](std::span<const Printed> printed, std::span<const FlagRow> ours) {
    ASSERT_EQ(printed.size(), ours.size());
    for (std::size_t i = 0; i < printed.size(); ++i) {
      SCOPED_TRACE(printed[i].name);
      EXPECT_EQ(ours[i].name, printed[i].name);
      EXPECT_EQ(ours[i].bit, printed[i].bit);
      EXPECT_EQ(ours[i].mask, 1U << ours[i].bit);
      if (printed[i].name == "MPTC") {
        EXPECT_NE(ours[i].mask, printed[i].mask);  // LB-E8: 8000H corrected
        EXPECT_EQ(ours[i].mask, 0x4000);
      } else {
        EXPECT_EQ(ours[i].mask, printed[i].mask);
      }
    }
  };
  check(attributes, kAttributeFlags);
  check(hardware, kHardwareFlags);
  check(structure, kStructureFlags);
  // "The Subject Areas are sequentially numbered and thus are not combinable": CONF 0 .. VAL 21.
  const std::string_view subjects[] = {"CONF", "ENCD", "OPT1", "OPT2", "MOT",  "TCON", "SCON", "PCON",
                                       "VFCN", "SIO",  "KPAD", "PWM",  "SCTY", "USER", "SYS",  "REF",
                                       "IO1",  "IO2",  "CAN",  "PMOD", "MENU", "VAL"};
  ASSERT_EQ(std::size(subjects), kSubjectAreas.size());
  for (std::size_t i = 0; i < kSubjectAreas.size(); ++i) {
    EXPECT_EQ(kSubjectAreas[i].name, subjects[i]);
    EXPECT_EQ(kSubjectAreas[i].code, i);
  }
  const std::string_view activities[] = {"SC_Nothing", "SC_OPT1", "SC_OPT2", "SC_APP", "SC_SYS",
                                         "SC_DRIVE",   "SC_REF",  "SC_CAN",  "SC_PMOD"};
  ASSERT_EQ(std::size(activities), kActivityAreas.size());
  for (std::size_t i = 0; i < kActivityAreas.size(); ++i) {
    EXPECT_EQ(kActivityAreas[i].name, activities[i]);
    EXPECT_EQ(kActivityAreas[i].code, i);
  }
  // Every row travels in a description (LB-D10, LB-E15) but those with a byte of 80H, which a
  // 7-bit line cannot carry: Brake (8000H), ASM (0080H), NoInit (0080H); the MPTC of the printed
  // table would be Brake's too.
  McDescription m;
  m.name = {'X', '\0', '\0', '\0', '\0', '\0'};
  for (const FlagRow& r : kHardwareFlags) {
    m.hardware_filter = r.mask;
    EXPECT_EQ(format_mc_description(m).has_value(), r.mask != kHwBrake && r.mask != 0x0080) << r.name;
  }
  m.hardware_filter = 0;
  for (const FlagRow& r : kAttributeFlags) {
    m.attribute = r.mask;
    EXPECT_EQ(format_mc_description(m).has_value(), r.mask != kAttrNoInit) << r.name;
  }
  m.attribute = 0;
  for (const AreaRow& r : kSubjectAreas) {
    m.hardware_filter = 0;
    m.subject_area = r.code;
    const auto v = format_mc_description(m);
    ASSERT_TRUE(v) << r.name;
    EXPECT_EQ(parse_mc_description(v->view()).value.subject_area, r.code) << r.name;
  }
}

TEST(SubstitutionText, TrailingBlanksAndNulsGo) {
  EXPECT_EQ(substitution_text("SCON  "), "SCON");
  EXPECT_EQ(substitution_text(std::string_view("1/min\0", 6)), "1/min");
  EXPECT_EQ(substitution_text(""), "");
}

// ---- 85-SIOF / SERR (9.2) ------------------------------------------------------------------------

TEST(Siof, BitsOf92SharedWithTheInterbusChannel) {
  EXPECT_EQ(siof_mask(SiofBit::power_on), 0x01);
  EXPECT_EQ(siof_mask(SiofBit::watchdog), 0x02);
  EXPECT_EQ(siof_mask(SiofBit::eeprom_busy), 0x04);
  EXPECT_EQ(siof_mask(SiofBit::checksum), 0x08);
  EXPECT_EQ(siof_mask(SiofBit::no_parameter), 0x20);
  EXPECT_EQ(siof_mask(SiofBit::no_change), 0x40);
  EXPECT_EQ(siof_mask(SiofBit::invalid_value), 0x80);
  EXPECT_EQ(remedy(SiofBit::eeprom_busy), SiofRemedy::wait_and_repeat);
  EXPECT_EQ(remedy(SiofBit::checksum), SiofRemedy::repeat);
  EXPECT_EQ(remedy(SiofBit::invalid_value), SiofRemedy::other_value);
  EXPECT_EQ(describe_siof(0x80), "80H: invalid value");
}

TEST(Siof, WhichRefusalsMayBeRepeated) {
  EXPECT_TRUE(select_may_be_repeated(0x01));   // latch: power on
  EXPECT_TRUE(select_may_be_repeated(0x04));   // EEPROM busy
  EXPECT_TRUE(select_needs_eeprom_wait(0x04));
  EXPECT_TRUE(select_may_be_repeated(0x08));   // checksum
  EXPECT_TRUE(select_may_be_repeated(0x09));
  EXPECT_FALSE(select_may_be_repeated(0x00));
  EXPECT_FALSE(select_may_be_repeated(0x20));
  EXPECT_FALSE(select_may_be_repeated(0x41));
  EXPECT_FALSE(select_may_be_repeated(0x88));
}

// ---- durations (10.1) ------------------------------------------------------------------------------

TEST(Timing, CharacterIsTenBits) {
  EXPECT_EQ(character_time(9600), Duration{1041667});
  EXPECT_EQ(transfer_time(8, 9600), Duration{8333333});
  EXPECT_EQ(text_answer_length(4), 14U);
  EXPECT_EQ(text_answer_length(8), 18U);
  EXPECT_EQ(select_length(4), 15U);
  EXPECT_EQ(select_length(8), 19U);
  // 10.2.2's example with 10-bit characters: 60 ms memory time - 25.9 ms sequence.
  const auto seq = select_time(8, 9600, 1ms, 2ms).total();
  EXPECT_NEAR(to_ms(eeprom_wait(4, 5ms, seq)), 60.0 - to_ms(seq), 1e-9);
  EXPECT_EQ(eeprom_wait(1, 5ms, 100ms), Duration{0});
  // 10.2.2's numbers as printed: 4 bytes x 3 x 5 ms = 60 ms of memory time; with its minimum
  // telegram duration of 22 ms the wait is 38 ms.
  EXPECT_EQ(eeprom_wait(4, 5ms, 0ms), 60ms);
  EXPECT_EQ(eeprom_wait(4, 5ms, 22ms), 38ms);
}

}  // namespace
}  // namespace ibs::lustbus
