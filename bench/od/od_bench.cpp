// The object dictionary's hot paths (od/, issue 38), beside today's code they will replace: a
// lookup by number (od::Dictionary::slot against the CDA3000's kRowByNumber and
// drive::ParameterTable::slot), a store read (od::Store::ram), a served read and write through the
// one interface (od::ServedParameters, one virtual call, against drive::ParameterAccess), and the
// configuration-time text (find by name, parse and format a value).
//
// Both dictionaries are today's tables converted entry by entry: the CDA3000's at compile time
// (its table is constexpr), the VF1000's at run time. The *_once functions are out of line, so
// that bench/callgrind_per_call.sh counts the instructions of one call:
//   bench/callgrind_per_call.sh build/release/bench/od/od_bench 'BM_OdSlot$' od_slot_once
#include <benchmark/benchmark.h>

#include <array>
#include <vector>

#include "ibs/devices/cda3000/parameters.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/drive/parameter_access.hpp"
#include "ibs/od/dictionary.hpp"
#include "ibs/od/stored_served.hpp"
#include "ibs/od/value_text.hpp"

namespace {

using namespace ibs;
namespace cda = ibs::devices::cda3000;

constexpr od::Type type_of(canlust::DataType t) {
  switch (t) {
    case canlust::DataType::usign8:
      return od::Type::usign8;
    case canlust::DataType::int8:
      return od::Type::int8;
    case canlust::DataType::usign16:
      return od::Type::usign16;
    case canlust::DataType::int16:
      return od::Type::int16;
    case canlust::DataType::usign32:
      return od::Type::usign32;
    case canlust::DataType::int32:
      return od::Type::int32;
    case canlust::DataType::int32q16:
      return od::Type::int32q16;
    case canlust::DataType::fixpoint16:
      return od::Type::fixpoint16;
    case canlust::DataType::err_struc:
      return od::Type::error32;
    case canlust::DataType::string:
      return od::Type::string;
  }
  return od::Type::usign32;
}

// The CDA3000's 28 rows as od entries, at compile time (what W3 writes by hand).
constexpr auto kCdaEntries = [] {
  std::array<od::Entry, cda::kParameters.size()> e{};
  for (std::size_t i = 0; i < e.size(); ++i) {
    const cda::ParameterInfo& p = cda::kParameters[i];
    e[i].number = p.number;
    e[i].name = p.name;
    e[i].text = p.text;
    e[i].type = type_of(p.type);
    e[i].min = p.min;
    e[i].max = p.max;
    e[i].default_value = p.is_string() ? 0 : p.factory;
    e[i].default_text = p.number == cda::kName    ? cda::kNameFactory
                        : p.number == cda::kOptn2 ? cda::kOptn2Module
                                                  : "";
    e[i].unit = p.unit;
    e[i].storage = !p.writable()                    ? od::Storage::ram_actual
                   : p.memory == cda::Memory::flash ? od::Storage::flash
                                                    : od::Storage::ram_control;
    e[i].effect =
        p.effect == cda::Effect::after_mains_reset ? od::Effect::at_restart : od::Effect::at_once;
    e[i].role = p.number == cda::kProg    ? od::Role::load_defaults
                : p.number == cda::kSave  ? od::Role::save
                : p.number == cda::kSload ? od::Role::download
                                          : od::Role::value;
    e[i].in_data_set = cda::card_writeable(p);
    e[i].invented = p.invented;
    e[i].source = p.source;
  }
  return e;
}();
constexpr od::Dictionary kCda{kCdaEntries};

// The numbers a CANLust master asks for: the table's, and some it lacks.
constexpr std::array<std::uint16_t, 8> kAsked{574, 575, 406, 4, 999, 280, 651, 1};

// ---- lookup by number ----------------------------------------------------------------------

[[gnu::noinline]] od::Slot od_slot_once(const od::Dictionary& d, std::uint16_t n) {
  return d.slot(n);
}
[[gnu::noinline]] std::optional<std::size_t> today_cda_index_once(std::uint16_t n) {
  return cda::parameter_index(n);
}
[[gnu::noinline]] int today_drive_slot_once(const drive::ParameterTable& t, std::uint16_t n) {
  return t.slot(n);
}

void BM_OdSlot(benchmark::State& state) {
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(od_slot_once(kCda, kAsked[i++ & 7U]));
  }
}
BENCHMARK(BM_OdSlot);

void BM_TodayCdaParameterIndex(benchmark::State& state) {
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(today_cda_index_once(kAsked[i++ & 7U]));
  }
}
BENCHMARK(BM_TodayCdaParameterIndex);

void BM_TodayDriveTableSlot(benchmark::State& state) {
  const drive::ParameterTable table(devices::vf1000::parameters());
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(today_drive_slot_once(table, kAsked[i++ & 7U]));
  }
}
BENCHMARK(BM_TodayDriveTableSlot);

// ---- the VF1000's table as od entries, at run time --------------------------------------------

od::Storage storage_of(drive::Category c) {
  switch (drive::storage(c)) {
    case drive::Storage::ram_control:
      return od::Storage::ram_control;
    case drive::Storage::ram_actual:
      return od::Storage::ram_actual;
    case drive::Storage::eeprom:
      return od::Storage::eeprom;
    case drive::Storage::eeprom_ram:
      return od::Storage::eeprom_ram;
  }
  return od::Storage::ram_control;
}
od::Type type_of(drive::DataType t) {
  switch (t) {
    case drive::DataType::binary8:
      return od::Type::binary8;
    case drive::DataType::fixpoint16:
      return od::Type::fixpoint16;
    case drive::DataType::usign16:
      return od::Type::usign16;
    case drive::DataType::usign8:
      return od::Type::usign8;
    case drive::DataType::vf_error:
      return od::Type::error16;
    case drive::DataType::password:
      return od::Type::password;
    case drive::DataType::integer16:
      return od::Type::int16;
  }
  return od::Type::usign16;
}

std::vector<od::Entry> vf_entries() {
  std::vector<od::Entry> v;
  for (const drive::ParameterInfo& p : devices::vf1000::parameters()) {
    od::Entry e;
    e.number = p.number;
    e.name = p.name;
    e.text = p.meaning;
    e.type = type_of(p.type);
    e.min = od::number(e.type, p.min);
    e.max = od::number(e.type, p.max);
    e.default_value = od::number(e.type, p.default_value);
    e.unit = p.unit;
    e.scale = p.scale / drive::natural_scale(p.type);
    e.storage = storage_of(p.category);
    e.specific = drive::inverter_specific(p.category);
    e.role = p.number == drive::kSiofNumber            ? od::Role::error_flags
             : p.number == devices::vf1000::pnr::kProg ? od::Role::load_defaults
                                                       : od::Role::value;
    v.push_back(e);
  }
  return v;
}

struct Vf {
  std::vector<od::Entry> entries = vf_entries();
  od::Dictionary dictionary{entries, od::Profile::lust_standard};
  od::StoredServed served{dictionary};
  drive::StoredParameters today{devices::vf1000::parameters(), devices::vf1000::pnr::kProg};
  od::Slot fssio = dictionary.slot(devices::vf1000::pnr::kFssio);
  Vf() {
    served.clear_error_flags(0xFF);
    today.clear_siof(0xFF);
  }
};

// ---- reads and writes ----------------------------------------------------------------------

[[gnu::noinline]] od::Raw od_ram_once(const od::Store& s, od::Slot slot) {
  return s.ram(slot);
}
[[gnu::noinline]] od::Reading od_served_read_once(od::ServedParameters& p, od::Slot s, Time now) {
  return p.read(s, now);
}
[[gnu::noinline]] Word today_drive_read_once(const drive::ParameterAccess& p, std::size_t slot) {
  return p.read(slot);
}
[[gnu::noinline]] od::Answer od_served_write_once(od::ServedParameters& p, od::Slot s, od::Raw r,
                                                  Time now) {
  return p.write(s, r, now);
}
[[gnu::noinline]] drive::WriteEffect today_drive_write_once(drive::ParameterAccess& p,
                                                            std::size_t slot, Word w, Time now) {
  const drive::ParameterInfo& info = p.table().params()[slot];
  if (p.siof() != 0 || p.check_write(&info, w, false) != drive::WriteCheck::ok) return {};
  return p.write(slot, w, false, now);
}

void BM_OdStoreRam(benchmark::State& state) {
  const Vf vf;
  for (auto _ : state) benchmark::DoNotOptimize(od_ram_once(vf.served.store(), vf.fssio));
}
BENCHMARK(BM_OdStoreRam);

void BM_OdServedRead(benchmark::State& state) {
  Vf vf;
  Time now{};
  for (auto _ : state) benchmark::DoNotOptimize(od_served_read_once(vf.served, vf.fssio, now));
}
BENCHMARK(BM_OdServedRead);

void BM_TodayDriveStoredParametersRead(benchmark::State& state) {
  Vf vf;
  for (auto _ : state) benchmark::DoNotOptimize(today_drive_read_once(vf.today, vf.fssio));
}
BENCHMARK(BM_TodayDriveStoredParametersRead);

void BM_OdServedWrite(benchmark::State& state) {
  Vf vf;
  Time now{};
  od::Raw r = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(od_served_write_once(vf.served, vf.fssio, r++ % 19999U, now));
}
BENCHMARK(BM_OdServedWrite);

void BM_TodayDriveStoredParametersWrite(benchmark::State& state) {
  Vf vf;
  Time now{};
  unsigned r = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        today_drive_write_once(vf.today, vf.fssio, static_cast<Word>(r++ % 19999U), now));
  }
}
BENCHMARK(BM_TodayDriveStoredParametersWrite);

// ---- configuration time --------------------------------------------------------------------

[[gnu::noinline]] const od::Entry* od_find_once(const od::Dictionary& d, std::string_view text) {
  return d.find(text);
}

void BM_OdFindByName(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(od_find_once(kCda, "CDSSL"));
}
BENCHMARK(BM_OdFindByName);

void BM_OdFindByNumberAndName(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(od_find_once(kCda, "651-CDSSL"));
}
BENCHMARK(BM_OdFindByNumberAndName);

void BM_OdParseValue(benchmark::State& state) {
  const od::Entry& reff = *kCda.find(cda::kReff);
  for (auto _ : state) benchmark::DoNotOptimize(od::parse_value(reff, "20.5"));
}
BENCHMARK(BM_OdParseValue);

void BM_TodayCdaParseValue(benchmark::State& state) {
  const cda::ParameterInfo& reff = *cda::find_parameter(cda::kReff);
  for (auto _ : state) benchmark::DoNotOptimize(cda::parse_value(reff, "20.5"));
}
BENCHMARK(BM_TodayCdaParseValue);

void BM_OdFormatValue(benchmark::State& state) {
  const od::Entry& reff = *kCda.find(cda::kReff);
  for (auto _ : state) benchmark::DoNotOptimize(od::format_value(reff, 0x00148000U));
}
BENCHMARK(BM_OdFormatValue);

}  // namespace
