#include "ibs/canlust/identifiers.hpp"

#include <array>

namespace ibs::canlust {

std::string_view to_string(TelegramKind k) {
  switch (k) {
    case TelegramKind::error: return "error";
    case TelegramKind::logon: return "logon";
    case TelegramKind::control: return "control";
    case TelegramKind::status: return "status";
    case TelegramKind::parameter_request: return "parameter request";
    case TelegramKind::parameter_reply: return "parameter reply";
    case TelegramKind::system: return "system start/stop";
  }
  return "?";
}

namespace {
constexpr std::array<TelegramKind, 6> kSelective = {
    TelegramKind::error,  TelegramKind::logon,
    TelegramKind::control, TelegramKind::status,
    TelegramKind::parameter_request, TelegramKind::parameter_reply};
}  // namespace

std::optional<Classified> IdentifierMap::classify(std::uint16_t id) const {
  if (id == kIdSystem) return Classified{TelegramKind::system, 0};
  if (step == 0) return std::nullopt;
  // Each kind's block is step x (max_address + 1) identifiers from its base: the range decides
  // first, so only the block that holds the identifier divides (issue 26: every frame on the bus
  // is classified, by the client and by every drive).
  const unsigned span = static_cast<unsigned>(step) * (static_cast<unsigned>(max_address) + 1U);
  for (const auto k : kSelective) {
    const std::uint16_t base = base_of(k);
    if (id < base) continue;
    const unsigned off = id - base;
    if (off >= span) continue;
    const unsigned a = step == 2 ? off >> 1U : off / step;
    if (a * step != off) continue;
    return Classified{k, static_cast<Address>(a)};
  }
  return std::nullopt;
}

bool IdentifierMap::unambiguous() const {
  if (step == 0) return false;
  std::array<bool, 0x800> used{};
  used[kIdSystem] = true;
  for (const auto k : kSelective) {
    for (unsigned a = 0; a <= max_address; ++a) {
      const auto v = id(k, static_cast<Address>(a));
      if (!v || used[*v]) return false;
      used[*v] = true;
    }
  }
  return true;
}

std::optional<std::uint16_t> IdentifierMap::own_id(TelegramKind k, Address a) const {
  if (k == TelegramKind::system || step == 0 || a > max_address) return std::nullopt;
  const unsigned v = base_of(k) + static_cast<unsigned>(step) * a;
  if (v > 0xFFFFU) return std::nullopt;
  const auto id = static_cast<std::uint16_t>(v);
  if (classify(id) != Classified{k, a}) return std::nullopt;
  return id;
}

KindMatcher::KindMatcher(const IdentifierMap& ids, TelegramKind k) : ids_(ids), kind_(k) {
  if (k == TelegramKind::system || ids.step == 0) return;  // general: classify decides
  base_ = base_of(k);
  step_ = ids.step;
  span_ = step_ * (static_cast<unsigned>(ids.max_address) + 1U);
  // The block's identifiers must all be this kind's for classify (no earlier kind overlaps).
  for (unsigned a = 0; a <= ids.max_address; ++a) {
    const unsigned v = base_ + step_ * a;
    if (v > 0xFFFFU) break;
    const auto c = ids.classify(static_cast<std::uint16_t>(v));
    if (!c || c->kind != k || c->address != a) return;
  }
  general_ = false;
}

}  // namespace ibs::canlust
