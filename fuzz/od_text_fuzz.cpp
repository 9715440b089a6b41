// The object dictionary's text readers (od/value_text.hpp, od/data_set.hpp, Dictionary::find),
// on arbitrary text, over a dictionary with an entry of every kind of type.
//
// Asserts:
// - parse_value: an accepted value is canonical and, with the limits checked, fits its entry;
//   its text (its number or substitution text) parses again to the same Raw; a refusal names the
//   parameter;
// - parse_data_set: an accepted set has records, each of an entry in the data set, fitting it,
//   numbers unique, lines rising within the text; written back as `NUMBER VALUE` lines it reads
//   to the same records; a refusal keeps no record and names a line of the text (0: the whole);
// - find: a found entry is found again by its number, by its name and by NUMBER-NAME.
//
// Input: byte 0 selects the part (mod 3: 0 a value, 1 a data set, 2 a lookup), byte 1 the entry
// and the limit check for a value; the rest is the text.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "ibs/od/data_set.hpp"
#include "ibs/od/value_text.hpp"

namespace {

using namespace ibs;
using namespace ibs::od;

constexpr std::array kChoices{Choice{0, "OFF", ""}, Choice{6, "OPTN2", ""}, Choice{11, "FMAX", ""}};
constexpr std::array kEntries{
    Entry{.number = 4, .name = "PROG", .type = Type::usign8, .max = 1, .role = Role::load_defaults},
    Entry{.number = 5,
          .name = "FSSIO",
          .type = Type::fixpoint16,
          .max = 19999,
          .unit = "Hz",
          .storage = Storage::eeprom_ram,
          .in_data_set = true},
    Entry{.number = 80,
          .name = "SLOAD",
          .type = Type::int16,
          .min = -2,
          .max = 999,
          .role = Role::download},
    Entry{.number = 95,
          .name = "ERR1",
          .type = Type::error32,
          .max = 0xFFFFFFFFLL,
          .storage = Storage::ram_actual},
    Entry{.number = 280,
          .name = "RSSL1",
          .type = Type::usign8,
          .max = 11,
          .default_value = 11,
          .storage = Storage::flash,
          .in_data_set = true,
          .choices = kChoices,
          .choices_only = true},
    Entry{.number = 406,
          .name = "REFF",
          .type = Type::int32q16,
          .min = -2147483648LL,
          .max = 2147483647LL,
          .unit = "Hz",
          .in_data_set = true},
    Entry{.number = 574,
          .name = "CAWDG",
          .type = Type::usign8,
          .max = 255,
          .unit = "ms",
          .storage = Storage::flash,
          .in_data_set = true},
    Entry{.number = 600,
          .name = "GAIN",
          .type = Type::float_ieee,
          .max = 0x42C80000,
          .default_value = 0x3F800000,
          .storage = Storage::eeprom,
          .in_data_set = true},
    Entry{.number = 601,
          .name = "TRIM",
          .type = Type::int8,
          .min = -100,
          .max = 100,
          .in_data_set = true},
    Entry{.number = 602,
          .name = "COUNT",
          .type = Type::usign32,
          .max = 0xFFFFFFFFLL,
          .in_data_set = true},
    Entry{.number = 906,
          .name = "IB-WD",
          .type = Type::usign16,
          .min = 8,
          .max = 0xFFFF,
          .default_value = 200,
          .unit = "ms",
          .storage = Storage::eeprom,
          .in_data_set = true},
    Entry{.number = 911,
          .name = "FDRIV",
          .type = Type::int16,
          .min = -32768,
          .max = 32767,
          .unit = "Hz",
          .scale = 0.05,
          .in_data_set = true},
    Entry{.number = 90,
          .name = "NAME",
          .type = Type::string,
          .max = 99,
          .default_text = "CDA3000",
          .storage = Storage::flash},
};
constexpr Dictionary kDictionary{kEntries};

// The text a person would write for a value: its substitution text, its number, or (the error
// structures) its raw pattern.
std::string text_of(const Entry& e, Raw r) {
  if (const Choice* c = e.choice(r)) return std::string(c->name);
  if (e.type == Type::error32 || e.type == Type::error16) {
    char b[16];
    std::snprintf(b, sizeof b, "0x%X", static_cast<unsigned>(r));
    return b;
  }
  return number_text(e, r);
}

void value_part(const Entry& e, bool check_limits, std::string_view text) {
  const ParsedValue p = parse_value(e, text, {check_limits, {}});
  if (!p) {
    IBS_FUZZ_REQUIRE(!p.error.empty() && p.error.rfind(display_name(e), 0) == 0,
                     "a refusal that names no parameter");
    return;
  }
  IBS_FUZZ_REQUIRE(p.error.empty(), "an accepted value with an error");
  const Raw r = *p.raw;
  IBS_FUZZ_REQUIRE(is_canonical(e.type, r), "an accepted value that is not canonical");
  if (check_limits) IBS_FUZZ_REQUIRE(fit(e, r) == Fit::ok, "an accepted value outside its entry");
  const std::string t = text_of(e, r);
  const ParsedValue q = parse_value(e, t, {false, {}});
  IBS_FUZZ_REQUIRE(q.raw.has_value(), "the value's own text does not parse: " + t + ": " + q.error);
  IBS_FUZZ_REQUIRE(text_of(e, *q.raw) == t, "the value's text changes when read again: " + t);
  IBS_FUZZ_REQUIRE(*q.raw == r, "the value's text reads to another value: " + t);
  const std::string f = format_value(e, r);
  IBS_FUZZ_REQUIRE(!f.empty(), "a value without a text");
}

void data_set_part(std::string_view text) {
  const DataSet p = parse_data_set(text, kDictionary, {.check_limits = true});
  const std::size_t lines = ibs::fuzz::count_lines(text);
  if (!p) {
    IBS_FUZZ_REQUIRE(p.records.empty() && !p.error.empty() && p.error_line <= lines,
                     "a refusal without its line");
    return;
  }
  IBS_FUZZ_REQUIRE(!p.records.empty(), "an accepted data set without records");
  std::string again;
  for (std::size_t i = 0; i < p.records.size(); ++i) {
    const DataSetRecord& r = p.records[i];
    const Entry* e = kDictionary.find(r.number);
    IBS_FUZZ_REQUIRE(e != nullptr && e->in_data_set, "a record no data set may hold");
    IBS_FUZZ_REQUIRE(fit(*e, r.raw) == Fit::ok, "a record its entry refuses");
    IBS_FUZZ_REQUIRE(r.line >= 1 && r.line <= lines && (i == 0 || r.line > p.records[i - 1].line),
                     "a record outside the text's lines");
    for (std::size_t j = 0; j < i; ++j)
      IBS_FUZZ_REQUIRE(p.records[j].number != r.number, "a parameter twice");
    again += std::to_string(r.number) + " " + text_of(*e, r.raw) + "\n";
  }
  const DataSet q = parse_data_set(again, kDictionary, {.check_limits = true});
  IBS_FUZZ_REQUIRE(q && q.records.size() == p.records.size(),
                   "the records written back do not parse: " + q.error);
  for (std::size_t i = 0; i < q.records.size(); ++i) {
    IBS_FUZZ_REQUIRE(
        q.records[i].number == p.records[i].number && q.records[i].raw == p.records[i].raw,
        "the records written back are others");
  }
}

void find_part(std::string_view text) {
  const Entry* e = kDictionary.find(text);
  if (e == nullptr) return;
  IBS_FUZZ_REQUIRE(kDictionary.find(e->number) == e, "not found again by its number");
  IBS_FUZZ_REQUIRE(kDictionary.find(std::string_view(e->name)) == e, "not found again by its name");
  IBS_FUZZ_REQUIRE(kDictionary.find(display_name(*e)) == e, "not found again by NUMBER-NAME");
  IBS_FUZZ_REQUIRE(kDictionary.slot(text) == kDictionary.slot(e->number), "slot and find disagree");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 2, size - 2);
  switch (data[0] % 3) {
    case 0: {
      const Entry& e = kEntries[data[1] % kEntries.size()];
      value_part(e, (data[1] & 0x80U) == 0, text);
      break;
    }
    case 1:
      data_set_part(text);
      break;
    default:
      find_part(text);
      break;
  }
  return 0;
}
