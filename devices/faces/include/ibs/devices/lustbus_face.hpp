// A drive's LUSTBUS face (LUSTBUS manual) as the registry of drive and bus lists it
// (ibs/devices/drives.hpp): the Responder the emulator serves, made from the options of
// `ibs lustbus emulate`, the protocol family the drive speaks, its parameters as the host
// commands and the byte-log reader need them, and the procedures of the LUSTBUS manual 11 it offers. Each
// wing that speaks LUSTBUS fills one of these in its own source
// (devices/<drive>/emulator/src/lustbus_face.cpp); this header names no drive.
// Configuration time: making a face and looking a parameter up may allocate and throw.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "ibs/base/time.hpp"
#include "ibs/devices/plant_event.hpp"
#include "ibs/devices/settings.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/responder.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::devices {

class DeviceEmulator;

// What `ibs lustbus emulate` gives every drive it serves (docs/lustbus.md, "Emulator").
struct LustbusFaceOptions {
  // The drive's own settings, among those its face declares (LustbusFace::settings) and within
  // their ranges (the caller checks); one not given reads as its declaration's fallback.
  SettingValues settings;
  std::uint64_t seed = 1;  // of the drawn reaction times (the command adds the address)
  int reaction_ms = -1;    // >= 0: a fixed reaction time instead of the drawn ones
  std::uint32_t baud = 9600;  // the rate of the line (4)
};

// A made face: the drive behind a lustbus::Receiver, its clock (the 5.2 watchdog, self tests)
// and the rate it answers at (11.5).
struct LustbusEmulated {
  std::unique_ptr<lustbus::Responder> responder;
  std::function<void(Time)> advance;
  std::function<std::uint32_t()> line_baud;
  // A plant or fault event (plant_event.hpp) on the drive's core, checked against its descriptor's
  // EventFacts beforehand: `ibs lustbus emulate --control`. False: the drive does not take it.
  std::function<bool(const PlantEvent&, Time)> apply_event;
};

// A parameter of the drive's table as a LUSTBUS host sees it.
struct LustbusParameter {
  std::uint16_t number = 0;
  std::string name;
  std::string unit;
  lustbus::DataType type = lustbus::DataType::usign16;
  std::int64_t min = 0;  // as numbers of the type (signed where the type is)
  std::int64_t max = 0;
  bool writable = true;
  bool prog = false;        // PROG: 1 takes up to 10 s (10 exception 1)
  bool in_dataset = false;  // may be part of an 11.4 dataset download
  // 10.2.2: the data width of an EEPROM parameter the drive saves after its ACK, for
  // lustbus::Request::eeprom_width (0: RAM, or a drive that answers once it is saved).
  std::uint8_t eeprom_width = 0;
};

struct LustbusFace {
  lustbus::Family family = lustbus::Family::standard;
  // The drive's Responder; throws std::invalid_argument "a <TITLE> runs at ... baud (LUSTBUS manual,
  // 4), not <baud>" for a rate the drive does not run at.
  LustbusEmulated (*make)(const LustbusFaceOptions& options) = nullptr;
  // The test bench (docs/testbench.md): the LUSTBUS face of the drive behind `interbus`, an
  // emulator the same wing's INTERBUS factory made (registry.hpp), so that one drive core answers
  // on both buses. Throws std::invalid_argument as make() does, and for another wing's emulator.
  LustbusEmulated (*attach)(DeviceEmulator& interbus, const LustbusFaceOptions& options) = nullptr;
  // PARAM by number or by name (case-sensitive, as the table spells it); nullopt for none.
  std::optional<LustbusParameter> (*find_parameter)(std::string_view text) = nullptr;
  // What a refusal of an unknown parameter adds: the numbers the CODE can carry (" (1..99)").
  std::string_view parameter_numbers;
  // The procedures of the LUSTBUS manual 11 the drive offers a host (download, indexed texts, block
  // transfer), as lustbus::Host runs them; nullptr: none.
  const lustbus::DeviceProcedures* procedures = nullptr;
  // The drive's own settings this face takes (settings.hpp, each with SettingFace::lustbus):
  // `ibs lustbus emulate` offers them as options and gives each drive those its face declares.
  std::span<const SettingSpec> settings{};
};

}  // namespace ibs::devices
