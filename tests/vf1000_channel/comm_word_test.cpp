// The communication word's bit layout (INTERBUS manual 4.1.2.1 and 4.1.2.2), pinned with the words of
// the manual's cycle tables (4.1.3).
#include "ibs/vf1000_channel/comm_word.hpp"

#include <gtest/gtest.h>

namespace {

using namespace ibs::vf1000_channel;

TEST(MasterWord, StartWordsOfTheCycleTables) {
  EXPECT_EQ(master_start_word(true, Code::value_inquiry, 0x16), 0x2416);   // 4.1.3.1.1 row 1
  EXPECT_EQ(master_start_word(true, Code::value_inquiry, 40), 0x2428);     // 4.1.3.1.1 NAK row 1
  EXPECT_EQ(master_start_word(true, Code::value_transfer, 0x16), 0x2816);  // 4.1.3.2.1 row 1
  EXPECT_EQ(master_start_word(true, Code::description_scan, 45), 0x2C2D);  // 4.1.3.3.1 row 1
}

TEST(MasterWord, DataWordsOfTheCycleTables) {
  EXPECT_EQ(master_word(false, Code::value_inquiry, 0, 0x00), 0x0400);   // 4.1.3.1.1 row 3
  EXPECT_EQ(master_word(false, Code::value_transfer, 0, 0x01), 0x0801);  // 4.1.3.2.1 row 3
  EXPECT_EQ(master_word(true, Code::value_transfer, 0, 0xF4), 0x28F4);   // 4.1.3.2.1 row 5
  EXPECT_EQ(master_word(false, Code::description_scan, 0, 0), 0x0C00);   // 4.1.3.3.1 row 3
  EXPECT_EQ(master_word(true, Code::description_scan, 0, 0), 0x2C00);    // 4.1.3.3.1 row 5
  EXPECT_EQ(master_word(false, Code::reset, 0, 0), kMasterIdleWord);
}

TEST(MasterWord, ParameterNumberBits8And9GoInControlBits0And1) {
  EXPECT_EQ(master_start_word(true, Code::value_inquiry, 0x3FF), 0x27FF);
  EXPECT_EQ(master_start_word(true, Code::value_inquiry, 906), 0x278A);
  EXPECT_EQ(master_start_word(false, Code::value_transfer, 0x100), 0x0900);
  for (std::uint16_t n = 0; n <= kMaxParameterNumber; ++n) {
    const ibs::Word w = master_start_word(true, Code::description_scan, n);
    ASSERT_EQ(master_number(w), n);
    ASSERT_EQ(master_code(w), 3);
    ASSERT_TRUE(master_toggle(w));
    ASSERT_FALSE(master_unused_bits(w));
  }
}

TEST(MasterWord, DecodesEveryField) {
  const ibs::Word w = 0xFFFF;
  EXPECT_TRUE(master_toggle(w));
  EXPECT_EQ(master_code(w), 7);
  EXPECT_EQ(master_number_high(w), 3);
  EXPECT_TRUE(master_unused_bits(w));
  EXPECT_FALSE(is_telegram_code(0));
  EXPECT_TRUE(is_telegram_code(1));
  EXPECT_TRUE(is_telegram_code(3));
  EXPECT_FALSE(is_telegram_code(4));
  EXPECT_TRUE(master_unused_bits(0x4000));
  EXPECT_TRUE(master_unused_bits(0x8000));
}

TEST(InverterWord, WordsOfTheCycleTables) {
  EXPECT_EQ(inverter_word(false, Flag::none, 0), 0x8000);     // wait mode
  EXPECT_EQ(inverter_word(true, Flag::none, 0x03), 0xA003);   // 4.1.3.1.1 row 2
  EXPECT_EQ(inverter_word(false, Flag::ack, 0xE8), 0x88E8);   // 4.1.3.1.1 row 4
  EXPECT_EQ(inverter_word(true, Flag::nak, 0), 0xB000);       // 4.1.3.1.1 NAK row 2
  EXPECT_EQ(inverter_word(true, Flag::ack, 0), 0xA800);       // 4.1.3.2.1 row 6
  EXPECT_EQ(inverter_word(false, Flag::none, 0x42), 0x8042);  // 4.1.3.3.1 row 4
}

TEST(InverterWord, RecognisesResetDistinctionAndWaitMode) {
  EXPECT_FALSE(inverter_ready(0x0000));
  EXPECT_TRUE(inverter_ready(0x8000));
  EXPECT_TRUE(inverter_idle(0x8000));
  EXPECT_TRUE(inverter_idle(0x8042));   // a mid-scan byte looks the same: the data is not checked
  EXPECT_FALSE(inverter_idle(0xA000));  // toggle 1
  EXPECT_FALSE(inverter_idle(0x8800));  // ACK
  EXPECT_FALSE(inverter_idle(0x9000));  // NAK
  EXPECT_FALSE(inverter_idle(0x0000));  // initialising
  EXPECT_TRUE(inverter_ack(0x88E8));
  EXPECT_TRUE(inverter_nak(0xB000));
  EXPECT_TRUE(inverter_toggle(0xB000));
}

TEST(CommWordMasks, DoNotOverlapAndCoverBothWords) {
  EXPECT_EQ(kMasterUnusedMask | kMasterToggle | kMasterCodeMask | kMasterNumberHighMask | kDataMask,
            0xFFFF);
  EXPECT_EQ(kMasterUnusedMask & kMasterToggle, 0);
  EXPECT_EQ(kMasterCodeMask & kMasterNumberHighMask, 0);
  EXPECT_EQ(kInverterReady | kInverterUnusedMask | kInverterToggle | kInverterNak | kInverterAck |
                kDataMask,
            0xFFFF);
  EXPECT_EQ(kInverterReady & (kInverterUnusedMask | kInverterToggle | kInverterNak | kInverterAck),
            0);
}

TEST(CommWordExplain, NamesUndefinedCodesAndUnusedBits) {
  EXPECT_EQ(explain_master_word(0x5000),
            "toggle 0, CODE 4 (undefined), byte 00H (as PNR: 0), unused bits 6/7 set");
  EXPECT_EQ(explain_master_word(0x0400), "toggle 0, CODE 1 value inquiry, byte 00H (as PNR: 0)");
  EXPECT_EQ(explain_inverter_word(0x8000),
            "ready, toggle 0, data 00H (wait mode, or a data byte 00H)");
}

}  // namespace
