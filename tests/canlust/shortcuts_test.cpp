// Issue 26's shortcuts on the CANLust frame path, each compared with the general path it stands
// for on random maps, identifiers and telegrams: KindMatcher and IdentifierMap::own_id against
// IdentifierMap::classify (what the client and the node use instead of classifying every frame),
// and the parameter telegram's 64-bit coding against the bytes of 4.5 written one by one.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "ibs/canlust/identifiers.hpp"
#include "ibs/canlust/telegrams.hpp"

namespace ibs::canlust {
namespace {

constexpr std::array<TelegramKind, 7> kAllKinds = {
    TelegramKind::error,  TelegramKind::logon,   TelegramKind::control,
    TelegramKind::status, TelegramKind::parameter_request, TelegramKind::parameter_reply,
    TelegramKind::system};

// The default map, the text's step 1, overlapping blocks (step 3 with 100 addresses reaches into
// the next block, 220 further), step 0, and random ones.
std::vector<IdentifierMap> maps(std::mt19937& rng, int random_ones) {
  std::vector<IdentifierMap> m = {IdentifierMap{}, IdentifierMap{1, 99}, IdentifierMap{3, 99},
                                  IdentifierMap{0, 99}, IdentifierMap{255, 255}, IdentifierMap{2, 0}};
  std::uniform_int_distribution<int> step(0, 255);
  std::uniform_int_distribution<int> small(1, 4);
  std::uniform_int_distribution<int> address(0, 255);
  for (int i = 0; i < random_ones; ++i) {
    const int s = i % 2 == 0 ? small(rng) : step(rng);
    m.push_back({static_cast<std::uint8_t>(s), static_cast<Address>(address(rng))});
  }
  return m;
}

TEST(CanlustShortcuts, KindMatcherIsClassifyOfItsKindForEveryIdentifier) {
  std::mt19937 rng(26);
  for (const IdentifierMap& ids : maps(rng, 24)) {
    std::vector<KindMatcher> matchers;
    for (const auto k : kAllKinds) matchers.emplace_back(ids, k);
    for (unsigned id = 0; id <= 0xFFFFU; ++id) {
      const auto c = ids.classify(static_cast<std::uint16_t>(id));
      for (std::size_t i = 0; i < kAllKinds.size(); ++i) {
        const std::optional<Address> want =
            c && c->kind == kAllKinds[i] ? std::optional<Address>(c->address) : std::nullopt;
        ASSERT_EQ(matchers[i].match(static_cast<std::uint16_t>(id)), want)
            << "step " << int{ids.step} << " max " << int{ids.max_address} << " kind "
            << to_string(kAllKinds[i]) << " id " << id;
      }
    }
  }
}

TEST(CanlustShortcuts, OwnIdIsTheOneIdentifierClassifyTakesForTheKindAndAddress) {
  std::mt19937 rng(27);
  for (const IdentifierMap& ids : maps(rng, 24)) {
    std::map<std::pair<TelegramKind, unsigned>, std::uint16_t> seen;
    for (unsigned id = 0; id <= 0xFFFFU; ++id) {
      if (const auto c = ids.classify(static_cast<std::uint16_t>(id))) {
        // classify is a function of the identifier and id(k, a) unique: one per pair at most.
        ASSERT_TRUE(seen.emplace(std::pair{c->kind, unsigned{c->address}},
                                 static_cast<std::uint16_t>(id)).second ||
                    c->kind == TelegramKind::system);
      }
    }
    for (const auto k : kAllKinds) {
      if (k == TelegramKind::system) {
        EXPECT_EQ(ids.own_id(k, 0), std::nullopt);
        continue;
      }
      for (unsigned a = 0; a <= 255; ++a) {
        const auto it = seen.find({k, a});
        const std::optional<std::uint16_t> want =
            it == seen.end() ? std::nullopt : std::optional<std::uint16_t>(it->second);
        ASSERT_EQ(ids.own_id(k, static_cast<Address>(a)), want)
            << "step " << int{ids.step} << " max " << int{ids.max_address} << " kind "
            << to_string(k) << " address " << a;
      }
    }
  }
}

// 4.5: bytes 0-1 the parameter number (low, high), 2 the mode / status, 3-6 the data (Intel
// order), 7 the block; written and read one byte at a time.
CanFrame reference_encode(std::uint16_t id, const ParameterTelegram& t) {
  CanFrame f;
  f.id = id;
  f.dlc = 8;
  f.data[0] = static_cast<std::uint8_t>(t.parameter & 0xFFU);
  f.data[1] = static_cast<std::uint8_t>(t.parameter >> 8U);
  f.data[2] = t.code;
  for (unsigned i = 0; i < 4; ++i) f.data[3 + i] = static_cast<std::uint8_t>((t.data >> (8U * i)) & 0xFFU);
  f.data[7] = t.block;
  return f;
}

Decoded<ParameterTelegram> reference_decode(const CanFrame& f) {
  if (f.rtr) return {{}, DecodeError::remote};
  if (f.dlc < 8) return {{}, DecodeError::too_short};
  ParameterTelegram t;
  t.parameter = static_cast<std::uint16_t>(f.data[0] | (f.data[1] << 8U));
  t.code = f.data[2];
  for (unsigned i = 0; i < 4; ++i) t.data |= static_cast<std::uint32_t>(f.data[3 + i]) << (8U * i);
  t.block = f.data[7];
  return {t, DecodeError::none};
}

TEST(CanlustShortcuts, ParameterTelegramCodingIsTheBytesOf45) {
  std::mt19937 rng(28);
  std::uniform_int_distribution<unsigned> byte(0, 255);
  std::uniform_int_distribution<std::uint32_t> word(0, 0xFFFF'FFFFU);
  std::uniform_int_distribution<int> address(0, 120);
  const IdentifierMap ids;
  for (int i = 0; i < 200'000; ++i) {
    const ParameterTelegram t{static_cast<std::uint16_t>(word(rng) & 0xFFFFU),
                              static_cast<std::uint8_t>(byte(rng)), word(rng),
                              static_cast<std::uint8_t>(byte(rng))};
    const auto a = static_cast<Address>(address(rng));
    const auto req = encode_parameter_request(ids, a, t);
    const auto rep = encode_parameter_reply(ids, a, t);
    const auto req_id = ids.id(TelegramKind::parameter_request, a);
    const auto rep_id = ids.id(TelegramKind::parameter_reply, a);
    ASSERT_EQ(req.has_value(), req_id.has_value());
    ASSERT_EQ(rep.has_value(), rep_id.has_value());
    if (req) {
      const CanFrame want = reference_encode(*req_id, t);
      ASSERT_EQ(req->id, want.id);
      ASSERT_EQ(req->dlc, want.dlc);
      ASSERT_EQ(req->rtr, want.rtr);
      ASSERT_EQ(req->data, want.data);
      ASSERT_EQ(decode_parameter(*req).value, t);
    }
    if (rep) {
      ASSERT_EQ(rep->data, reference_encode(*rep_id, t).data);
    }
    // Arbitrary frames: every byte, DLC and RTR flag.
    CanFrame f;
    f.id = static_cast<std::uint16_t>(word(rng) & 0x7FFU);
    f.dlc = static_cast<std::uint8_t>(byte(rng) % 16);
    f.rtr = byte(rng) < 16;
    for (auto& b : f.data) b = static_cast<std::uint8_t>(byte(rng));
    const auto got = decode_parameter(f);
    const auto want = reference_decode(f);
    ASSERT_EQ(got.error, want.error);
    ASSERT_EQ(got.value, want.value);
  }
}

}  // namespace
}  // namespace ibs::canlust
