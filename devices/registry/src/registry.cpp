#include "ibs/devices/registry.hpp"

#include <algorithm>
#include <array>
#include <tuple>
#include <type_traits>

#include "ibs/devices/mc6000/campaign_profile.hpp"
#include "ibs/devices/mc6000/capture.hpp"
#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/vf1000/campaign_profile.hpp"
#include "ibs/devices/vf1000/capture.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/devices/vf1000/device.hpp"
#include "ibs/drivecom/sequencer.hpp"

namespace ibs::devices {

namespace {

// The one list of drive kinds, sorted by name. A new drive adds its line here.
const auto& kinds() {
  static const auto k = std::to_array<DriveKind>({
      {&mc6000::descriptor(), &mc6000::make_emulator, &mc6000::campaign_profile(), &mc6000::capture_face()},
      {&vf1000::descriptor(), &vf1000::make_emulator, &vf1000::campaign_profile(), &vf1000::capture_face()},
  });
  return k;
}

constexpr std::size_t kKindCount = std::tuple_size_v<std::remove_cvref_t<decltype(kinds())>>;

const std::array<std::string_view, kKindCount>& names() {
  static const std::array<std::string_view, kKindCount> n = [] {
    std::array<std::string_view, kKindCount> a{};
    std::transform(kinds().begin(), kinds().end(), a.begin(), [](const DriveKind& k) { return k->name(); });
    return a;
  }();
  return n;
}

}  // namespace

std::span<const DriveKind> drive_kinds() { return kinds(); }

const DriveKind* find_drive_kind(std::string_view name) {
  for (const DriveKind& k : kinds()) {
    if (k->name() == name) return &k;
  }
  return nullptr;
}

std::string drive_kind_names(std::string_view separator, std::string_view last, std::string_view quote) {
  std::string s;
  const auto n = names().size();
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) s += i + 1 == n ? last : separator;
    s += std::string(quote) + std::string(names()[i]) + std::string(quote);
  }
  return s;
}

trace::Vocabulary trace_vocabulary() { return {names(), drivecom::kTargetKeys}; }

}  // namespace ibs::devices
