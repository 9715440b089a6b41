// INTERBUS manual 5.1.3: the device states in the status word, bits 4/5 and the device bits.
#include <gtest/gtest.h>

#include "ibs/drivecom/status_word.hpp"

namespace ibs::drivecom {
namespace {

TEST(StatusWord, StateTableOf513) {
  // Status bits 6 5 3 2 1 0 of the table, X = either.
  EXPECT_EQ(decode_state(0x0000), State::not_ready);
  EXPECT_EQ(decode_state(0x0020), State::not_ready);
  EXPECT_EQ(decode_state(0x0040), State::start_up_inhibit);
  EXPECT_EQ(decode_state(0x0060), State::start_up_inhibit);
  EXPECT_EQ(decode_state(0x0021), State::ready);
  EXPECT_EQ(decode_state(0x0023), State::on);
  EXPECT_EQ(decode_state(0x0027), State::enabled);
  EXPECT_EQ(decode_state(0x0008), State::fault);
  EXPECT_EQ(decode_state(0x0028), State::fault);
  EXPECT_EQ(decode_state(0x000F), State::fault_response_active);
  EXPECT_EQ(decode_state(0x002F), State::fault_response_active);
  EXPECT_EQ(decode_state(0x0007), State::emergency_stop_active);
  EXPECT_FALSE(decode_state(0x0001).has_value());  // READY needs bit 5
  EXPECT_FALSE(decode_state(0x0041).has_value());
}

TEST(StatusWord, NoWordShowsTwoStates) {
  for (unsigned w = 0; w <= 0xFFFF; ++w) {
    int n = 0;
    for (const auto& row : kStateTable) n += (w & row.mask) == row.value ? 1 : 0;
    ASSERT_LE(n, 1) << std::hex << w;
  }
}

TEST(StatusWord, Bits4And5ShowTheReceivedRequestsAs534Shows) {
  const StatusExtras remote{};
  EXPECT_EQ(status_word(State::start_up_inhibit, 0x0000, remote), 0x0240);
  EXPECT_EQ(status_word(State::ready, 0x0006, remote), 0x0231);
  EXPECT_EQ(status_word(State::enabled, 0x000F, remote), 0x0237);
  StatusExtras reached{};
  reached.reference_reached = true;
  EXPECT_EQ(status_word(State::enabled, 0x000F, reached), 0x0637);
  // Block power alone (bit 1 = 0, bit 2 = 1) clears bit 4 only; e-stop alone clears bit 5 only.
  EXPECT_EQ(status_word(State::start_up_inhibit, 0x0004, remote), 0x0260);
  EXPECT_EQ(status_word(State::start_up_inhibit, 0x0002, remote), 0x0250);
  // EMERGENCY STOP ACTIVE shows bit 5 = 0 even when the master no longer requests it.
  EXPECT_EQ(status_word(State::emergency_stop_active, 0x000F, remote), 0x0217);
  EXPECT_EQ(decode_state(status_word(State::emergency_stop_active, 0x000F, remote)),
            State::emergency_stop_active);
}

TEST(StatusWord, EveryStateRoundTripsForEveryControlWord) {
  for (const auto& row : kStateTable) {
    for (unsigned c = 0; c <= 0xFFFF; c += 7) {
      ASSERT_EQ(decode_state(status_word(row.state, static_cast<Word>(c), {})), row.state);
    }
  }
}

TEST(StatusWord, TheLookupAgreesWithTheStateBitsForEveryStateAndControlWord) {
  // status_word() reads bits 0-6 from a table built at compile time; every one of the 65536
  // control words must give what state_bits() and the extra bits say.
  for (const auto& row : kStateTable) {
    for (unsigned c = 0; c <= 0xFFFF; ++c) {
      for (const bool reached : {false, true}) {
        StatusExtras e{};
        e.reference_reached = reached;
        e.bit15 = (c & 1U) != 0;
        const auto w = static_cast<Word>(c);
        ASSERT_EQ(status_word(row.state, w, e), static_cast<Word>(state_bits(row.state, w) | extras_bits(e)))
            << "state " << to_string(row.state) << ", control word " << c;
      }
    }
  }
}

TEST(StatusWord, StateNamesAndKeysComeFromTheStateTableAlone) {
  for (const auto& row : kStateTable) {
    EXPECT_EQ(to_string(row.state), row.name);
    EXPECT_EQ(key(row.state), row.key);
    EXPECT_EQ(state_named(row.key), row.state);
  }
  EXPECT_EQ(kStateKeys.front(), "not-ready");
  EXPECT_EQ(kStateKeys.back(), "emergency-stop-active");
  EXPECT_EQ(state_named("running"), std::nullopt);
  EXPECT_EQ(state_named("START-UP INHIBIT"), std::nullopt) << "files spell the key, reports the name";
}

}  // namespace
}  // namespace ibs::drivecom
