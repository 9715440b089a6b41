// Downloading a parameter data set (CANLust manual 4.x "Downloading parameter data sets"): the master
// opens the download through the drive's handshake parameter, sends the values "without
// individual checking of the parameter values", and closes it; "when the upload is finished the
// drive controller checks the now complete new data set for plausibility. If the data set is
// valid the parameters are accepted with the attribute Card Writeable into the EEPROM. The drive
// is enabled again". Which parameter is the handshake and which parameters a data set may hold
// are the drive's (its wing); this core names no drive.
//
//   DataSetParse p = parse_data_set(text, resolve);      // `PARAM VALUE` lines, the drive's table
//   DataSetDownload d(handshake, address, p.records);
//   while (d.step(client), !d.finished()) { client.step(now); ... frames ... }
//
// The parser and the constructor allocate (configuration time); step() submits one request at a
// time to the ParameterClient and allocates nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/canlust/parameter_client.hpp"

namespace ibs::canlust {

struct DataSetRecord {
  std::uint16_t parameter = 0;
  std::uint32_t value = 0;  // the wire image (bytes 3-6)
  std::size_t line = 0;     // in the data set's text, from 1
};

// What the caller's table makes of one line's PARAM and VALUE: the number and wire image, or why
// not (error not empty: "574-CAWDG: 300 ms is above the maximum 255 ms").
struct ResolvedRecord {
  std::uint16_t parameter = 0;
  std::uint32_t value = 0;
  std::string error;
};
using DataSetResolver = std::function<ResolvedRecord(std::string_view parameter, std::string_view value)>;

struct DataSetParse {
  std::vector<DataSetRecord> records;
  std::size_t error_line = 0;  // the first bad line (error not empty)
  std::string error;
  explicit operator bool() const { return error.empty(); }
};

// A data set's text: one `PARAM VALUE` a line, '#' starts a comment, blank lines skipped; a
// parameter given twice, a line with more or fewer than two words, NUL bytes or a line longer
// than kMaxDataSetLine are refused with the line's number, as is a text with no record at all
// (line 0). The resolver is asked once per record line.
inline constexpr std::size_t kMaxDataSetLine = 200;
inline constexpr std::size_t kMaxDataSetRecords = 1000;
DataSetParse parse_data_set(std::string_view text, const DataSetResolver& resolve);

// The drive's handshake parameter and its codes (decision D39 for the CDA3000: 80-SLOAD).
struct DownloadHandshake {
  std::uint16_t parameter = 0;
  std::uint32_t start = 0;   // written to open the download
  std::uint32_t end = 0;     // written to close it: the drive checks the whole set, then answers
  std::uint32_t cancel = 0;  // written to drop an open download (the old data set stays)
  Duration end_timeout = 2s; // the check and the EEPROM may take this long
  // Read after the end: 0 = the set was valid and is in the EEPROM; any other value = the number
  // of the first implausible parameter (nothing was taken).
};

enum class DownloadState : std::uint8_t {
  running,
  downloaded,  // the drive took the set into its EEPROM
  rejected,    // the drive found it implausible: rejected_parameter
  refused,     // a step was refused (outcome.status); a refused record cancels the download
  failed,      // a step timed out or its reply broke the protocol
};
std::string_view to_string(DownloadState s);

struct DownloadResult {
  DownloadState state = DownloadState::running;
  // The step that ended it (refused / failed): 0 the start, 1..n the records, n + 1 the end,
  // n + 2 the reading of the result.
  std::size_t step = 0;
  Outcome outcome{};
  std::uint16_t rejected_parameter = 0;
};

class DataSetDownload {
 public:
  DataSetDownload(const DownloadHandshake& h, Address a, std::vector<DataSetRecord> records);

  // Collects the outcome of the request in flight and submits the next one. Call it after every
  // client.step / receive; it returns the result, `running` until the end.
  const DownloadResult& step(ParameterClient& client);
  [[nodiscard]] const DownloadResult& result() const { return result_; }
  // Ended, and the cancel that follows a refused record (if any) answered: nothing in flight.
  [[nodiscard]] bool finished() const { return result_.state != DownloadState::running && !cancelling_; }
  // Progress: the steps finished of steps() (start, records, end, result).
  [[nodiscard]] std::size_t steps() const { return records_.size() + 3; }
  [[nodiscard]] std::size_t finished_steps() const { return step_; }
  [[nodiscard]] const std::vector<DataSetRecord>& records() const { return records_; }

 private:
  [[nodiscard]] Request request_for(std::size_t step) const;

  DownloadHandshake h_;
  Address address_;
  std::vector<DataSetRecord> records_;
  std::size_t step_ = 0;     // the step in flight (or next)
  RequestId in_flight_ = 0;
  bool cancelling_ = false;  // the cancel write after a refused record is in flight
  DownloadResult result_{};
};

}  // namespace ibs::canlust
