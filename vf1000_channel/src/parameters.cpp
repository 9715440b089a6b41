#include "ibs/vf1000_channel/parameters.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace ibs::vf1000_channel {

namespace {

using C = Category;
using T = DataType;

// Frequencies in PT_FIXPOINT16 are limited to 999.95 Hz, the KP100's display range for the type
// (seed 000, 2.3.1), where the manuals give no parameter-specific range.
constexpr Word kFixpointDisplayMax = 19999;

// The table. Rows the manuals specify completely cite them; every other value is a modelling
// choice listed in docs/vf1000_channel.md ("Parameter table").
constexpr std::array kVf1000Parameters = {
    // 3.1.1: INTERBUS default 4; seed 000, 7.1: 0 = terminals or serial interface.
    ParameterInfo{pnr::kMode, "MODE", "", C::eeprom, T::usign8, 0, 4, 4, 1.0, "Mode select"},
    // 3.1.1: INTERBUS default 5; seed 000, 7.1: 3 = serial interface.
    ParameterInfo{pnr::kCsel, "CSEL", "", C::eeprom, T::usign8, 0, 5, 5, 1.0,
                  "Control location selector"},
    // seed 000, 7.1: 128 = start clockwise; a bit pattern of one byte.
    ParameterInfo{pnr::kCntl, "CNTL", "", C::ram_control, T::binary8, 0, 0xFF, 0, 1.0,
                  "Control word (serial interface)"},
    // 3.1.1: INTERBUS default 25; seed 000, 7.1: 8 = reference from 5-FSSIO.
    ParameterInfo{pnr::kFssel, "FSSEL", "", C::eeprom, T::usign8, 0, 25, 25, 1.0,
                  "Frequency reference selector"},
    // seed 000, 6.2.2 / 7.1: 50.00 Hz = 03E8H, 23.15 Hz = 463; an EEPROM/RAM (FSEL) variable.
    ParameterInfo{pnr::kFssio, "FSSIO", "Hz", C::eeprom_ram, T::fixpoint16, 0, kFixpointDisplayMax,
                  0, 0.05, "Frequency reference (serial interface)"},
    // seed 000, 8.1.1: written with 000FH to reset a fault, so it is a control variable.
    ParameterInfo{pnr::kStat, "STAT", "", C::ram_control, T::binary8, 0, 0xFF, 0, 1.0,
                  "Inverter status / fault reset"},
    // 4.1.3.1.1: actual value 3E8H (50.00 Hz); 4.1.3.2.1: 1F4H = 25 Hz, so PT_FIXPOINT16.
    ParameterInfo{pnr::kFmax1, "FMAX1", "Hz", C::eeprom, T::fixpoint16, 0, kFixpointDisplayMax,
                  1000, 0.05, "Maximum frequency 1"},
    // 5.2.1: 36-RSTOP <> 0 programs a stop ramp, 0 disables the power stage. No manual gives the
    // factory value; 50.00 Hz/s (a modelling choice) lets EMERGENCY STOP brake as 5.2.1 describes.
    ParameterInfo{pnr::kRstop, "RSTOP", "Hz/s", C::eeprom, T::fixpoint16, 0, kFixpointDisplayMax, 1000,
                  0.05, "Stop function / stop ramp"},
    // 4.1.3.3.1, completely: "VB2", "%", EEPROM, decimal, 0, 1F4H, A0H.
    ParameterInfo{pnr::kVb2, "VB2", "%", C::eeprom, T::fixpoint16, 0, 0x01F4, 0x00A0, 0.05,
                  "Voltage boost 2"},
    // seed 000, 4: 7 switches the RS-485 data direction.
    ParameterInfo{pnr::kSouta, "SOUTA", "", C::eeprom, T::usign8, 0, 15, 0, 1.0,
                  "Function of output A"},
    // seed 000, 10, exception 1: 1 loads the factory settings.
    ParameterInfo{pnr::kProg, "PROG", "", C::eeprom, T::usign8, 0, 1, 0, 1.0,
                  "Load factory settings"},
    // seed 000, 4 and 5.2: 81..85 and 91 are numerically compatible across the drive family.
    ParameterInfo{pnr::kSioc, "SIOC", "", C::eeprom, T::usign8, 0, 2, 2, 1.0,
                  "Baud rate (0: 2400, 1: 4800, 2: 9600)"},
    ParameterInfo{pnr::kSioa, "SIOA", "", C::eeprom, T::usign8, 1, 30, 1, 1.0, "Serial address"},
    ParameterInfo{pnr::kSiow, "SIOW", "", C::ram_control, T::usign16, 0, 0xFFFF, 0, 1.0,
                  "Dummy / watchdog trigger"},
    ParameterInfo{pnr::kSiot, "SIOT", "ms", C::eeprom, T::usign16, 0, 0xFFFF, 0, 1.0,
                  "Serial watchdog time (0: off)"},
    // seed 000, 9.2: the error bits; read-only, cleared by reading.
    ParameterInfo{pnr::kSiof, "SIOF", "", C::ram_actual, T::binary8, 0, 0xFF, 0, 1.0,
                  "Serial interface error flags"},
    ParameterInfo{pnr::kType, "TYPE", "", C::ram_actual, T::usign16, 0, 0xFFFF, 1000, 1.0,
                  "Device type"},
    // 4.1.1, completely (Integer 16 of 905/912 see DataType::integer16).
    ParameterInfo{pnr::kIcntl, "ICNTL", "", C::ram_control, T::usign16, 0x0000, 0xFFFF, 0x0000, 1.0,
                  "DRIVECOM control word"},
    ParameterInfo{pnr::kFdriv, "FDRIV", "Hz", C::ram_control, T::integer16, 0x8000, 0x7FFF, 0, 0.05,
                  "Frequency reference"},
    ParameterInfo{pnr::kIbWd, "IB-WD", "ms", C::eeprom, T::usign16, 8, 0xFFFF, 200, 1.0,
                  "PD monitoring time"},
    ParameterInfo{pnr::kIbcod, "IBCOD", "", C::eeprom, T::usign16, 0, 3, 0, 1.0,
                  "PD monitoring selection code"},
    ParameterInfo{pnr::kIbsta, "IBSTA", "", C::ram_actual, T::usign16, 0x0000, 0xFFFF, 0, 1.0,
                  "DRIVECOM status word"},
    ParameterInfo{pnr::kFist, "FIST", "Hz", C::ram_actual, T::integer16, 0x8000, 0x7FFF, 0, 0.05,
                  "Actual speed"},
};

bool printable(std::string_view s) {
  for (const char c : s) {
    if (c < 0x20 || c > 0x7E) return false;
  }
  return true;
}

std::string label(const ParameterInfo& p) {
  return "parameter " + std::to_string(p.number) + "-" + std::string(p.name);
}

}  // namespace

std::span<const ParameterInfo> vf1000_parameters() {
  return kVf1000Parameters;
}

std::optional<double> to_engineering(const ParameterInfo& p, Word raw) {
  return to_engineering(p.type, raw, p.scale);
}

std::optional<Word> from_engineering(const ParameterInfo& p, double value) {
  return from_engineering(p.type, value, p.scale);
}

std::string_view to_string(WriteCheck c) {
  switch (c) {
    case WriteCheck::ok:
      return "ok";
    case WriteCheck::no_parameter:
      return "no parameter";
    case WriteCheck::no_change:
      return "no change permitted";
    case WriteCheck::invalid_value:
      return "invalid value";
  }
  return "?";
}

DescriptionRecord make_description(const ParameterInfo& p) {
  DescriptionRecord r{};
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = description_byte(p, i);
  return r;
}

Description decode_description(const DescriptionRecord& record) {
  const auto text = [&record](std::size_t from) {
    std::string s;
    for (std::size_t i = from; i < from + 5; ++i) s.push_back(static_cast<char>(record[i]));
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
  };
  Description d;
  d.name = text(0);
  d.unit = text(5);
  d.category = category_from_code(static_cast<char>(record[10]));
  d.type = data_type_from_code(static_cast<char>(record[11]));
  d.min = make_word(record[12], record[13]);
  d.max = make_word(record[14], record[15]);
  d.default_value = make_word(record[16], record[17]);
  return d;
}

ParameterTable::ParameterTable(std::span<const ParameterInfo> params) : params_(params) {
  index_.fill(-1);
  if (params.size() > static_cast<std::size_t>(kMaxParameterNumber) + 1) {
    throw std::invalid_argument("parameter table: " + std::to_string(params.size()) +
                                " entries, but numbers only run from 0 to 3FFH");
  }
  for (std::size_t i = 0; i < params.size(); ++i) {
    const ParameterInfo& p = params[i];
    const std::string where =
        "parameter table entry " + std::to_string(i) + " (" + label(p) + "): ";
    if (p.number > kMaxParameterNumber) {
      throw std::invalid_argument(where + "number above 3FFH (seed 001, 4.1.3)");
    }
    if (index_[p.number] >= 0) throw std::invalid_argument(where + "number used twice");
    if (p.name.empty() || p.name.size() > 5 || !printable(p.name)) {
      throw std::invalid_argument(where + "name must be 1 to 5 printable characters (4.1.3.3)");
    }
    if (p.unit.size() > 5 || !printable(p.unit)) {
      throw std::invalid_argument(where + "unit must be at most 5 printable characters (4.1.3.3)");
    }
    const auto n = [&p](Word w) { return raw_as_number(p.type, w); };
    if (n(p.min) < n(type_min_raw(p.type)) || n(p.max) > n(type_max_raw(p.type))) {
      throw std::invalid_argument(where + "min/max outside the range of " +
                                  std::string(to_string(p.type)));
    }
    if (n(p.min) > n(p.max)) throw std::invalid_argument(where + "min above max");
    if (!in_range(p, p.default_value)) {
      throw std::invalid_argument(where + "default outside min/max");
    }
    if (!(p.scale > 0.0)) throw std::invalid_argument(where + "scale must be positive");
    index_[p.number] = static_cast<std::int16_t>(i);
  }
}

ParameterStore::ParameterStore(std::span<const ParameterInfo> params)
    : params_(params), cells_(params.size()) {
  load_defaults();
}

void ParameterStore::write(std::size_t slot, Word raw, bool power_stage_enabled) {
  Cell& c = cells_[slot];
  c.ram = raw;
  switch (storage(params_[slot].category)) {
    case Storage::eeprom:
      c.eeprom = raw;
      break;
    case Storage::eeprom_ram:
      if (!power_stage_enabled) c.eeprom = raw;
      break;
    case Storage::ram_control:
    case Storage::ram_actual:
      break;
  }
}

void ParameterStore::set(std::size_t slot, Word raw) {
  Cell& c = cells_[slot];
  c.ram = raw;
  const Storage s = storage(params_[slot].category);
  if (s == Storage::eeprom || s == Storage::eeprom_ram) c.eeprom = raw;
}

void ParameterStore::power_up() {
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    const Storage s = storage(params_[i].category);
    cells_[i].ram = (s == Storage::eeprom || s == Storage::eeprom_ram) ? cells_[i].eeprom
                                                                       : params_[i].default_value;
  }
}

void ParameterStore::load_defaults() {
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    cells_[i].ram = params_[i].default_value;
    cells_[i].eeprom = params_[i].default_value;
  }
}

}  // namespace ibs::vf1000_channel
