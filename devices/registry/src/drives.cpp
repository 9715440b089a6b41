#include "ibs/devices/drives.hpp"

#include <algorithm>
#include <array>

#include "ibs/devices/cda3000/bus_face.hpp"
#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/mc6000/lustbus_face.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/devices/vf1000/lustbus_face.hpp"

namespace ibs::devices {

namespace {

// The one list of drives, sorted by name. A new drive adds its line here; a new bus face of a
// known drive fills its field (docs/architecture.md, "Adding a drive", "Adding a bus face").
const auto& list() {
  static const auto d = std::to_array<Drive>({
      {cda3000::kDriveName, nullptr, nullptr, nullptr, &cda3000::bus_face()},
      {dfs1::kDriveName, nullptr, nullptr, &dfs1::bus_face(), nullptr},
      {mc6000::kName, find_drive_kind(mc6000::kName), &mc6000::lustbus_face(), nullptr, nullptr},
      {vf1000::kName, find_drive_kind(vf1000::kName), &vf1000::lustbus_face(), nullptr, nullptr},
  });
  return d;
}

}  // namespace

std::string_view to_string(Bus b) {
  switch (b) {
    case Bus::interbus: return "INTERBUS";
    case Bus::lustbus: return "LUSTBUS";
    case Bus::dfs1: return "DFS-1";
    case Bus::canlust: return "CANLust";
  }
  return "?";
}

bool Drive::speaks(Bus b) const {
  switch (b) {
    case Bus::interbus: return interbus != nullptr;
    case Bus::lustbus: return lustbus != nullptr;
    case Bus::dfs1: return dfs1 != nullptr;
    case Bus::canlust: return canlust != nullptr;
  }
  return false;
}

std::span<const Drive> drives() { return list(); }

const Drive* find_drive(std::string_view name) {
  for (const Drive& d : list()) {
    if (d.name == name) return &d;
  }
  return nullptr;
}

const Drive* find_drive(std::string_view name, Bus bus) {
  const Drive* d = find_drive(name);
  return d != nullptr && d->speaks(bus) ? d : nullptr;
}

std::vector<const Drive*> drives_on(Bus bus) {
  std::vector<const Drive*> v;
  for (const Drive& d : list()) {
    if (d.speaks(bus)) v.push_back(&d);
  }
  if (bus == Bus::lustbus) {
    std::stable_sort(v.begin(), v.end(), [](const Drive* a, const Drive* b) {
      return static_cast<int>(a->lustbus->family) < static_cast<int>(b->lustbus->family);
    });
  }
  return v;
}

std::string drive_names(Bus bus, std::string_view separator, std::string_view last, std::string_view suffix) {
  const auto v = drives_on(bus);
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) s += i + 1 == v.size() ? last : separator;
    s += std::string(v[i]->name) + std::string(suffix);
  }
  return s;
}

std::vector<DriveOnBus> drive_bus_pairs() {
  std::vector<DriveOnBus> v;
  for (const Drive& d : list()) {
    for (const Bus b : kBuses) {
      if (d.speaks(b)) v.push_back({&d, b});
    }
  }
  return v;
}

const Drive* find_lustbus_drive(lustbus::Family family) {
  for (const Drive& d : list()) {
    if (d.lustbus != nullptr && d.lustbus->family == family) return &d;
  }
  return nullptr;
}

lustbus::ParameterLookup lustbus_parameter_lookup() {
  return [](lustbus::Family f, std::uint16_t number) -> std::optional<lustbus::ParameterFacts> {
    const Drive* d = find_lustbus_drive(f);
    if (d == nullptr) return std::nullopt;
    const auto p = d->lustbus->find_parameter(std::to_string(number));
    if (!p) return std::nullopt;
    return lustbus::ParameterFacts{p->number, p->name, p->unit, p->type};
  };
}

}  // namespace ibs::devices
