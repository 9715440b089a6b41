#include "ibs/canlust/data_set.hpp"

#include <utility>

namespace ibs::canlust {

namespace {

bool space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// The words of a line without its comment.
std::vector<std::string_view> words(std::string_view line) {
  if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
  std::vector<std::string_view> w;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && space(line[i])) ++i;
    const std::size_t b = i;
    while (i < line.size() && !space(line[i])) ++i;
    if (i > b) w.push_back(line.substr(b, i - b));
  }
  return w;
}

}  // namespace

DataSetParse parse_data_set(std::string_view text, const DataSetResolver& resolve) {
  DataSetParse p;
  const auto fail = [&p](std::size_t line, std::string why) {
    p.records.clear();
    p.error_line = line;
    p.error = std::move(why);
    return std::move(p);
  };
  std::size_t n = 0;
  while (!text.empty()) {
    ++n;
    const auto nl = text.find('\n');
    const std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    if (line.size() > kMaxDataSetLine) {
      return fail(n, "the line has " + std::to_string(line.size()) + " characters, at most " +
                         std::to_string(kMaxDataSetLine) + " are read");
    }
    if (line.find('\0') != std::string_view::npos) return fail(n, "a NUL byte: this is no data set text");
    const auto w = words(line);
    if (w.empty()) continue;
    if (w.size() != 2) return fail(n, "expected `PARAM VALUE`");
    ResolvedRecord r = resolve(w[0], w[1]);
    if (!r.error.empty()) return fail(n, std::move(r.error));
    for (const DataSetRecord& earlier : p.records) {
      if (earlier.parameter == r.parameter) {
        return fail(n, "parameter " + std::to_string(r.parameter) + " is given twice (first on line " +
                           std::to_string(earlier.line) + ")");
      }
    }
    if (p.records.size() == kMaxDataSetRecords) {
      return fail(n, "more than " + std::to_string(kMaxDataSetRecords) + " records");
    }
    p.records.push_back({r.parameter, r.value, n});
  }
  if (p.records.empty()) return fail(0, "no `PARAM VALUE` line: the data set is empty");
  return p;
}

std::string_view to_string(DownloadState s) {
  switch (s) {
    case DownloadState::running: return "running";
    case DownloadState::downloaded: return "downloaded";
    case DownloadState::rejected: return "rejected";
    case DownloadState::refused: return "refused";
    case DownloadState::failed: return "failed";
  }
  return "?";
}

DataSetDownload::DataSetDownload(const DownloadHandshake& h, Address a, std::vector<DataSetRecord> records)
    : h_(h), address_(a), records_(std::move(records)) {}

Request DataSetDownload::request_for(std::size_t step) const {
  const std::size_t n = records_.size();
  if (step == 0) return write(address_, h_.parameter, h_.start);
  if (step <= n) return write(address_, records_[step - 1].parameter, records_[step - 1].value);
  if (step == n + 1) {
    Request r = write(address_, h_.parameter, h_.end);
    r.timeout = h_.end_timeout;  // the drive answers once the set is checked (and saved)
    return r;
  }
  return read(address_, h_.parameter);
}

const DownloadResult& DataSetDownload::step(ParameterClient& client) {
  if (result_.state != DownloadState::running && !cancelling_) return result_;
  if (in_flight_ != 0) {
    const Poll p = client.poll(in_flight_);
    if (p.state != RequestState::done) return result_;
    in_flight_ = 0;
    if (cancelling_) {
      // The cancel's own outcome changes nothing: the step that failed is what is reported.
      cancelling_ = false;
      return result_;
    }
    const Outcome o = p.outcome != nullptr ? *p.outcome : Outcome{};
    const std::size_t n = records_.size();
    if (o.kind != OutcomeKind::done) {
      result_.state = o.kind == OutcomeKind::refused ? DownloadState::refused : DownloadState::failed;
      result_.step = step_;
      result_.outcome = o;
      // A record the drive did not take leaves its download open: drop it, so that the drive
      // keeps its old data set and is enabled again.
      if (step_ >= 1 && step_ <= n) {
        const Submitted s = client.submit(write(address_, h_.parameter, h_.cancel));
        if (s) {
          in_flight_ = s.id;
          cancelling_ = true;
        }
      }
      return result_;
    }
    if (step_ == n + 2) {
      result_.outcome = o;
      result_.step = step_;
      // 0: taken into the EEPROM; else the first implausible parameter's number.
      const auto v = static_cast<std::uint16_t>(o.value & 0xFFFFU);
      if (o.value == 0) {
        result_.state = DownloadState::downloaded;
      } else {
        result_.state = DownloadState::rejected;
        result_.rejected_parameter = v;
      }
      ++step_;
      return result_;
    }
    ++step_;
  }
  const Submitted s = client.submit(request_for(step_));
  if (!s) {
    result_.state = DownloadState::failed;
    result_.step = step_;
    return result_;
  }
  in_flight_ = s.id;
  return result_;
}

}  // namespace ibs::canlust
