// The one registry of drive and bus: every drive the project knows, and for each bus it speaks
// what that bus needs from it. INTERBUS: the drive kind (registry.hpp: descriptor, emulator
// factory, capture facts); LUSTBUS: the drive's lustbus::Responder face, its protocol family and
// its parameter lookup (lustbus_face.hpp); DFS-1: the controller factory; CANLust: the emulated drive, the
// master driver and the parameter lookup (canlust_face.hpp). Every emulator and host on every bus finds a drive here by the name the user gives
// it. Each wing declares its faces in its own sources; the list in drives.cpp is where they meet
// (docs/architecture.md, "The registry of drive and bus").
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/devices/canlust_face.hpp"
#include "ibs/devices/dfs1/bus_face.hpp"
#include "ibs/devices/lustbus_face.hpp"
#include "ibs/devices/registry.hpp"
#include "ibs/lustbus/byte_log.hpp"

namespace ibs::devices {

enum class Bus : std::uint8_t { interbus, lustbus, dfs1, canlust };
std::string_view to_string(Bus b);
inline constexpr Bus kBuses[] = {Bus::interbus, Bus::lustbus, Bus::dfs1, Bus::canlust};

struct Drive {
  std::string_view name;  // as the user gives it: "vf1000", "dfs1@7" starts with it
  const DriveKind* interbus = nullptr;
  const LustbusFace* lustbus = nullptr;
  const dfs1::Dfs1Face* dfs1 = nullptr;
  const CanlustFace* canlust = nullptr;

  [[nodiscard]] bool speaks(Bus b) const;
};

// Every drive, sorted by name (static data).
std::span<const Drive> drives();
const Drive* find_drive(std::string_view name);
// The drive that speaks `bus` under `name`; nullptr when there is none or it does not speak it.
const Drive* find_drive(std::string_view name, Bus bus);
// The drives that speak `bus`: sorted by name, except LUSTBUS, in the order of the protocol's
// families (lustbus::Family: the inverter first, as the LUSTBUS manual lists them).
std::vector<const Drive*> drives_on(Bus bus);
// Their names for messages: joined by `separator`, the last two by `last`, each followed by
// `suffix`: drive_names(Bus::lustbus, " or ", " or ", "@ADDR") = "vf1000@ADDR or mc6000@ADDR".
std::string drive_names(Bus bus, std::string_view separator, std::string_view last, std::string_view suffix = "");

// Every (drive, bus) pair the wings declare, drives by name, buses in kBuses' order.
struct DriveOnBus {
  const Drive* drive = nullptr;
  Bus bus = Bus::interbus;
};
std::vector<DriveOnBus> drive_bus_pairs();

// The drive that speaks LUSTBUS as `family`; nullptr for none.
const Drive* find_lustbus_drive(lustbus::Family family);
// The LUSTBUS parameters of every drive by family and number, for lustbus::read_byte_log.
lustbus::ParameterLookup lustbus_parameter_lookup();

}  // namespace ibs::devices
