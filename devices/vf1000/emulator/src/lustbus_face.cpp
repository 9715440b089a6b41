// The VF1000 as the registry's LUSTBUS face: its LustbusDevice made from the emulate options and
// its parameter table as the host commands read it.
#include "ibs/devices/vf1000/lustbus_face.hpp"

#include <charconv>
#include <stdexcept>
#include <string>

#include "ibs/devices/vf1000/device.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/devices/vf1000/settings.hpp"

namespace ibs::devices::vf1000 {

namespace {

// On a drive of its own (`drive` empty) or on an existing one (the bench: `drive` is its INTERBUS
// face's).
LustbusEmulated make_on(std::shared_ptr<Drive> drive, const LustbusFaceOptions& o) {
  LustbusTiming timing;
  // 10: "1...60 ms" with a KEYPAD, "1...30 ms" without, unless a fixed time is asked for.
  timing.reaction = o.reaction_ms >= 0 ? lustbus::ReactionModel::fixed(std::chrono::milliseconds(o.reaction_ms))
                                       : lustbus_reaction(o.settings.boolean(kKeypadSetting), o.seed);
  // The emulator serves an RS-485 line (LUSTBUS manual is LUSTBUS on RS-485), so the drive needs
  // 61-SOUTA = 7 to answer (4). Section 4 makes setting it, like the line's rate in 81-SIOC, a step
  // of commissioning done at the drive (e.g. via the KEYPAD): the emulator's drive comes
  // commissioned with both, kept in its EEPROM (VF-E20). A host that writes another SOUTA, or
  // 71-PROG = 1, loses the drive as it would a real one.
  timing.rs485 = true;
  auto d = drive ? std::make_unique<LustbusDevice>(std::move(drive), timing) : std::make_unique<LustbusDevice>(timing);
  if (!d->set_line_baud(o.baud)) {
    throw std::invalid_argument("a VF1000 runs at 2400, 4800 or 9600 baud (LUSTBUS manual 4), not " +
                                std::to_string(o.baud));
  }
  d->drive().set_value(pnr::kSouta, kSoutaRs485);
  LustbusDevice* p = d.get();
  // Events act on the core the face serves, at the time given (the face advances it first).
  return {std::move(d), [p](Time t) { p->advance(t); }, [p]() { return p->line_baud(); },
          [p](const PlantEvent& e, Time t) {
            p->advance(t);
            return p->drive().apply(e, t);
          }};
}

LustbusEmulated make(const LustbusFaceOptions& o) { return make_on(nullptr, o); }

LustbusEmulated attach(DeviceEmulator& interbus, const LustbusFaceOptions& o) {
  auto* face = dynamic_cast<Vf1000Device*>(&interbus);
  if (face == nullptr) throw std::invalid_argument("not a VF1000's INTERBUS face: no LUSTBUS face can share its drive");
  return make_on(face->shared_drive(), o);
}

std::optional<LustbusParameter> find_parameter(std::string_view text) {
  unsigned n = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), n);
  const bool numeric = !text.empty() && r.ec == std::errc{} && r.ptr == text.data() + text.size();
  for (const drive::ParameterInfo& p : parameters()) {
    if (p.number > 99) continue;  // 2.4.1: the CODE carries two digits
    if (numeric ? p.number == n : p.name == text) {
      return LustbusParameter{p.number, std::string(p.name), std::string(p.unit), lustbus_type(p.type),
                              p.min,    p.max,               drive::writable(p.category),
                              p.number == pnr::kProg, false};
    }
  }
  return std::nullopt;
}

}  // namespace

const LustbusFace& lustbus_face() {
  static const LustbusFace face{lustbus::Family::standard, &make, &attach, &find_parameter, " (1..99)", nullptr,
                                kLustbusSettings};
  return face;
}

}  // namespace ibs::devices::vf1000
