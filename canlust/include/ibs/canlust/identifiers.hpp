// CANLust identifiers (CANLust manual 5.5; public-facts "CANLust", "Identifiers"): one base per
// telegram kind, the station's identifier = base + step x address, and one broadcast identifier
// for System Start/Stop.
//
// The step is a setting. The manual's text says base + address (step 1); every worked example
// with 571-CLADR = 1 uses base + 2 (663, 883, 1103, 1323, 1545). ibs takes step 2 by default:
// erratum CAN-E1 in docs/errata.md, reasoning in docs/canlust.md "Decisions" D1.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace ibs::canlust {

using Address = std::uint8_t;

enum class TelegramKind : std::uint8_t {
  error,              // 441 + address, 3 bytes, drive -> master (5.5, 6.2)
  logon,              // 1543 + address, no data, drive -> master every 100 ms (5.2, 5.5.4)
  control,            // 661 + address, up to 6 bytes, master -> drive (5.5.5)
  status,             // 881 + address, up to 6 bytes, drive -> master (5.5.6)
  parameter_request,  // 1101 + address, 8 bytes, master -> drive (4.5)
  parameter_reply,    // 1321 + address, 8 bytes, drive -> master (4.5)
  system,             // 221, 1 byte, master -> every drive: System Start / Stop (5.5.4)
};
std::string_view to_string(TelegramKind k);

inline constexpr std::uint16_t kBaseError = 441;               // 1B9H
inline constexpr std::uint16_t kBaseLogon = 1543;              // 607H
inline constexpr std::uint16_t kBaseControl = 661;             // 295H
inline constexpr std::uint16_t kBaseStatus = 881;              // 371H
inline constexpr std::uint16_t kBaseParameterRequest = 1101;   // 44DH
inline constexpr std::uint16_t kBaseParameterReply = 1321;     // 529H
inline constexpr std::uint16_t kIdSystem = 221;                // DDH, the broadcast
inline constexpr std::uint16_t base_of(TelegramKind k) {
  switch (k) {
    case TelegramKind::error: return kBaseError;
    case TelegramKind::logon: return kBaseLogon;
    case TelegramKind::control: return kBaseControl;
    case TelegramKind::status: return kBaseStatus;
    case TelegramKind::parameter_request: return kBaseParameterRequest;
    case TelegramKind::parameter_reply: return kBaseParameterReply;
    case TelegramKind::system: return kIdSystem;
  }
  return 0;
}

// D1 / CAN-E1: the examples' step.
inline constexpr std::uint8_t kDefaultIdStep = 2;
// Addresses 0..99 (public-facts: "addresses run 0..99"); with step 2 the six blocks, 220 apart,
// do not overlap (base + 2 x 99 = base + 198 < base + 220).
inline constexpr Address kDefaultMaxAddress = 99;

struct Classified {
  TelegramKind kind = TelegramKind::system;
  Address address = 0;  // 0 for the broadcast
  friend constexpr bool operator==(const Classified&, const Classified&) = default;
};

// The identifier map of one bus: every node and the master must use the same one.
struct IdentifierMap {
  std::uint8_t step = kDefaultIdStep;      // 1 (the text) or 2 (the examples); >= 1
  Address max_address = kDefaultMaxAddress;

  // nullopt when the address is above max_address or the identifier would leave 11 bits.
  [[nodiscard]] constexpr std::optional<std::uint16_t> id(TelegramKind k, Address a) const {
    if (k == TelegramKind::system) return kIdSystem;
    if (a > max_address || step == 0) return std::nullopt;
    const unsigned v = base_of(k) + static_cast<unsigned>(step) * a;
    if (v > 0x7FFU) return std::nullopt;
    return static_cast<std::uint16_t>(v);
  }
  // What an identifier means on this bus; nullopt for identifiers CANLust does not use (between
  // the blocks, odd offsets with step 2, above max_address).
  [[nodiscard]] std::optional<Classified> classify(std::uint16_t id) const;
  // True when no two (kind, address) pairs share an identifier (checked at configuration).
  [[nodiscard]] bool unambiguous() const;
  // The identifier that classify() takes for (k, a), nullopt when none does (an address above
  // max_address, a kind whose block an earlier one overlaps there, the broadcast): what a drive
  // compares its frames with instead of classifying each (issue 26).
  [[nodiscard]] std::optional<std::uint16_t> own_id(TelegramKind k, Address a) const;
};

// The identifiers of one selective kind: match(id) is classify(id)'s address when classify(id)
// is of that kind, nullopt else, without classify's walk over the other kinds' blocks (issue 26:
// the client classifies every frame on the bus). Where an earlier kind's block claims one of
// this kind's identifiers (a map that is not unambiguous()), or for the broadcast, it asks
// classify itself. Built once from a copy of the map.
class KindMatcher {
 public:
  KindMatcher() : KindMatcher(IdentifierMap{}, TelegramKind::parameter_reply) {}
  KindMatcher(const IdentifierMap& ids, TelegramKind k);

  [[nodiscard]] std::optional<Address> match(std::uint16_t id) const {
    if (general_) {
      const auto c = ids_.classify(id);
      if (!c || c->kind != kind_) return std::nullopt;
      return c->address;
    }
    if (id < base_) return std::nullopt;
    const unsigned off = static_cast<unsigned>(id) - base_;
    if (off >= span_) return std::nullopt;
    const unsigned a = step_ == 2 ? off >> 1U : off / step_;
    if (a * step_ != off) return std::nullopt;
    return static_cast<Address>(a);
  }

 private:
  IdentifierMap ids_;
  TelegramKind kind_;
  bool general_ = true;
  unsigned base_ = 0;
  unsigned step_ = 1;
  unsigned span_ = 0;
};

}  // namespace ibs::canlust
