#include "ibs/devices/mc6000/service.hpp"

#include <array>

#include "ibs/devices/mc6000/parameters.hpp"

namespace ibs::devices::mc6000 {

namespace {

using namespace std::string_view_literals;

// 11.3 texts (chosen; SIO 2, OPT1 4, RCON 0, RSIO 3, SCON 2, ROPT1 6 are the seeds' codes).
// 107-UNIT: the units the other parameters' `unit` index.
constexpr std::array kUnitTexts{"-"sv, "rpm"sv, "Hz"sv, "ms"sv, "s"sv, "V"sv, "A"sv, "%"sv, "Nm"sv, "Bd"sv};
constexpr std::uint8_t kUnitNone = 0, kUnitRpm = 1, kUnitMs = 3, kUnitBaud = 9;
// 300-CFCON: the control types in the order of the structure filter's bits (docs/pcp.md).
constexpr std::array kCfconTexts{"-"sv, "TCON"sv, "SCON"sv, "PCON"sv, "VFCON"sv, "EMAST"sv, "ESLAV"sv};
constexpr std::array kClselTexts{"TERM"sv, "KPAD"sv, "SIO"sv, "CAN"sv, "OPT1"sv, "OPT2"sv};
constexpr std::array kRsslTexts{"RCON"sv, "RA0"sv, "RA1"sv, "RSIO"sv, "RFIX"sv, "RCAN"sv, "OPT1"sv, "OPT2"sv};
constexpr std::array kInputTexts{"OFF"sv, "START"sv, "INV"sv, "QSTOP"sv, "RESET"sv, "FIX0"sv, "ROPT1"sv};
constexpr std::array kOutputTexts{"OFF"sv, "REF"sv, "LIMIT"sv, "ERROR"sv, "ACTIV"sv, "BRAKE"sv, "ROPT1"sv};
// 510..512: the five reaction steps of the LUSTBUS manual 8 (8.1.2: 5 "RESET"; the others chosen, MC-D7).
constexpr std::array kReactionTexts{"-"sv, "WARN"sv, "STOP"sv, "OFF"sv, "LOCK"sv, "RESET"sv};

constexpr ServiceEntry entry(std::uint16_t n, Subject s, Activity a = Activity::nothing,
                             std::uint8_t unit = kUnitNone,
                             std::span<const std::string_view> texts = {}) {
  ServiceEntry e;
  e.number = n;
  e.unit = unit;
  e.subject = s;
  e.activity = a;
  e.texts = texts;
  return e;
}

// One row per parameter of kParameters (a test checks they match).
constexpr std::array<ServiceEntry, kParameters.size()> kService{{
    entry(kProg, Subject::conf),
    entry(kPlrdy, Subject::conf),
    entry(kSpeed, Subject::val, Activity::nothing, kUnitRpm),
    entry(kSload, Subject::sio),
    // The serial interface's own settings are no dataset's: a download must not move the link.
    entry(kSbaud, Subject::sio, Activity::nothing, kUnitBaud),
    entry(kSaddr, Subject::sio),
    entry(kSdmmy, Subject::sio),
    entry(kSwdgt, Subject::sio, Activity::nothing, kUnitMs),
    entry(kSerr, Subject::sio),
    entry(kType, Subject::sys),
    entry(kUnit, Subject::menu, Activity::nothing, kUnitNone, kUnitTexts),
    entry(kStext, Subject::menu),
    entry(kCfcon, Subject::conf, Activity::drive, kUnitNone, kCfconTexts),
    entry(kClsel, Subject::conf, Activity::drive, kUnitNone, kClselTexts),
    entry(kSupi, Subject::opt1, Activity::opt1),
    entry(kIbcnf, Subject::opt1, Activity::opt1),
    entry(kIbstu, Subject::opt1),
    entry(kIbsta, Subject::opt1),
    entry(kButwd, Subject::opt1, Activity::opt1, kUnitMs),
    entry(kSctl1, Subject::sio),
    entry(kRssl1, Subject::ref, Activity::ref, kUnitNone, kRsslTexts),
    entry(kRssl2, Subject::ref, Activity::ref, kUnitNone, kRsslTexts),
    entry(kRssl3, Subject::ref, Activity::ref, kUnitNone, kRsslTexts),
    entry(kRssl4, Subject::ref, Activity::ref, kUnitNone, kRsslTexts),
    entry(kRsio, Subject::sio, Activity::nothing, kUnitRpm),
    entry(kFis00, Subject::ref, Activity::ref, kUnitNone, kInputTexts),
    entry(kFis01, Subject::ref, Activity::ref, kUnitNone, kInputTexts),
    entry(kFif0, Subject::ref, Activity::ref, kUnitNone, kInputTexts),
    entry(kFif1, Subject::ref, Activity::ref, kUnitNone, kInputTexts),
    entry(kFos00, Subject::ref, Activity::ref, kUnitNone, kOutputTexts),
    entry(kFos01, Subject::ref, Activity::ref, kUnitNone, kOutputTexts),
    // 11.2.1: SCTY 12, "Security-and-error-reaction parameter"; a system setting of the dataset.
    entry(kReop1, Subject::scty, Activity::sys, kUnitNone, kReactionTexts),
    entry(kResio, Subject::scty, Activity::sys, kUnitNone, kReactionTexts),
    entry(kRedev, Subject::scty, Activity::sys, kUnitNone, kReactionTexts),
}};

}  // namespace

const ServiceEntry* service_entry(std::uint16_t number) {
  for (const auto& e : kService) {
    if (e.number == number) return &e;
  }
  return nullptr;
}

bool card_writeable(std::uint16_t number) {
  const ServiceEntry* e = service_entry(number);
  return e != nullptr && e->activity != Activity::nothing;
}

std::string_view substitution_text_of(std::uint16_t number, std::uint32_t value) {
  const ServiceEntry* e = service_entry(number);
  if (e == nullptr || value >= e->texts.size()) return {};
  return e->texts[value];
}

}  // namespace ibs::devices::mc6000
