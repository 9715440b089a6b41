// A parameter data set's text, for a download (LUSTBUS manual 11.4, the MC6000's 80-SLOAD over LUSTBUS;
// CANLust manual "Downloading parameter data sets", the CDA3000's D39): one `PARAM VALUE` a line, '#'
// starts a comment, blank lines are skipped. The one reader of such files (it replaces
// canlust::parse_data_set and the LUSTBUS download's own reader in tools/ibs). Every refusal
// names its line. Library ibs_od_text: configuration time, allocates, throws nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/od/dictionary.hpp"
#include "ibs/od/value_text.hpp"

namespace ibs::od {

inline constexpr std::size_t kMaxDataSetLine = 200;
inline constexpr std::size_t kMaxDataSetRecords = 1000;

struct DataSetRecord {
  std::uint16_t number = 0;
  Raw raw = 0;           // canonical (a CANLust wire image as it is; other codecs mask it)
  std::size_t line = 0;  // in the text, from 1
};

struct DataSet {
  std::vector<DataSetRecord> records;
  std::size_t error_line = 0;  // the first bad line (0: the text as a whole); error not empty
  std::string error;
  explicit operator bool() const { return error.empty(); }
};

// What one line's PARAM and VALUE are: the number and the Raw, or why not (error not empty).
struct ResolvedRecord {
  std::uint16_t number = 0;
  Raw raw = 0;
  std::string error;
};
using DataSetResolver =
    std::function<ResolvedRecord(std::string_view parameter, std::string_view value)>;

// The lines, each resolved by `resolve` (asked once per record line, in order). Refused with the
// line's number: a line of other than two words, a NUL byte, a line longer than kMaxDataSetLine,
// a parameter given twice, more than kMaxDataSetRecords records, a resolver's refusal; and a text
// with no record at all (line 0). A refusal keeps no records.
DataSet parse_data_set(std::string_view text, const DataSetResolver& resolve);

struct DataSetOptions {
  // false: the values are checked for their type only, the drive tests the whole set (LUSTBUS manual
  // 11.4 "without individual testing"); true: each against its entry as well (CANLust manual D39).
  bool check_limits = true;
  TextStyle style{};
  // Who the parameters belong to, for "'999' is not a CDA3000 parameter" ("" : "a parameter").
  std::string_view title{};
};
// The lines resolved by a drive's dictionary: PARAM as Dictionary::find takes it ("CAWDG",
// "574", "574-CAWDG"), only entries in the data set ("77-SPEED cannot be part of a data set (it is
// not Card Writeable)"), VALUE by parse_value.
DataSet parse_data_set(std::string_view text, const Dictionary& dictionary,
                       const DataSetOptions& options = {});

}  // namespace ibs::od
