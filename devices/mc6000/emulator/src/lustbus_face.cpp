// The MC6000 as the registry's LUSTBUS face: its LustbusDevice made from the emulate options and
// its parameter table as the host commands read it.
#include "ibs/devices/mc6000/lustbus_face.hpp"

#include <charconv>
#include <stdexcept>
#include <string>

#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/settings.hpp"

namespace ibs::devices::mc6000 {

namespace {

// On a drive of its own (`drive` empty) or on an existing one (the bench: `drive` is its INTERBUS
// face's).
LustbusEmulated make_on(std::shared_ptr<Drive> drive, const LustbusFaceOptions& o) {
  LustbusTiming timing;
  // 10: up to 30 ms with a KEYPAD, 25 ms without, unless a fixed time is asked for.
  timing.reaction = o.reaction_ms >= 0 ? lustbus::ReactionModel::fixed(std::chrono::milliseconds(o.reaction_ms))
                                       : lustbus_reaction(o.settings.boolean(kLustbusKeypadSetting), o.seed);
  auto d = drive ? std::make_unique<LustbusDevice>(std::move(drive), timing) : std::make_unique<LustbusDevice>(timing);
  if (!d->set_line_baud(o.baud)) {
    throw std::invalid_argument("an MC6000 runs at 2400, 4800, 9600, 19200, 38400 or 57600 baud (LUSTBUS manual 4), not " + std::to_string(o.baud));
  }
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
  auto* face = dynamic_cast<Mc6000Device*>(&interbus);
  if (face == nullptr) throw std::invalid_argument("not an MC6000's INTERBUS face: no LUSTBUS face can share its drive");
  return make_on(face->shared_drive(), o);
}

std::optional<LustbusParameter> find_parameter(std::string_view text) {
  unsigned n = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), n);
  const bool numeric = !text.empty() && r.ec == std::errc{} && r.ptr == text.data() + text.size();
  for (const pcp::ParameterInfo& p : parameters()) {
    if (numeric ? p.number == n : p.name == text) {
      // 11.4: 80-SLOAD runs the download; it is no part of the dataset. 10.2.2: the servo saves
      // an EEPROM value in the background, its data width x 15 ms.
      LustbusParameter lp{p.number, std::string(p.name),   "",    lustbus_type(p.type), p.min, p.max,
                          p.writable(), p.number == kProg, p.writable() && p.number != kSload};
      if (p.category == pcp::Category::eeprom) lp.eeprom_width = static_cast<std::uint8_t>(pcp::size_of(p.type));
      return lp;
    }
  }
  return std::nullopt;
}

lustbus::DeviceProcedures make_procedures() {
  lustbus::DeviceProcedures p;
  // 11.4: SLOAD = -1 opens the download, -2 ends it; SLOAD then reads -1 while the servo tests
  // and saves, 0 when taken, the number of the first invalid parameter otherwise.
  p.download = lustbus::DownloadProcedure{lustbus::Family::enhanced, kSload,
                                          static_cast<std::int16_t>(kSloadBegin),
                                          static_cast<std::int16_t>(kSloadEnd)};
  // 11.3: STEXT = the value, then ENQUIRY 61ppp.
  p.indexed_text = lustbus::IndexedTextProcedure{lustbus::Family::enhanced, kStext};
  // 11.6.1: "0 ... 80 Byte ASCII-Data (use-data)"; 11.6: after a NAK "the Host computer
  // ascertains the error using the read command %RDF" (a request telegram, status byte 31H).
  lustbus::BlockTransferProcedure b;
  b.code = lustbus::kPosmodCode;
  b.max_user_data = 80;
  b.error_read = lustbus::make_value("1%RDF");
  b.asks_answer = &lustbus::posmod_asks_answer;  // 11.6.3: the status byte leads the user data
  p.block_transfer = b;
  return p;
}

}  // namespace

const lustbus::DeviceProcedures& lustbus_procedures() {
  static const lustbus::DeviceProcedures procedures = make_procedures();
  return procedures;
}

const LustbusFace& lustbus_face() {
  static const LustbusFace face{lustbus::Family::enhanced, &make, &attach, &find_parameter, "",
                                &lustbus_procedures(), kLustbusSettings};
  return face;
}

}  // namespace ibs::devices::mc6000
