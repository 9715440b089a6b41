#include <algorithm>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "ibs/devices/registry.hpp"
#include "ibs/devices/trace_adapters.hpp"
#include "ibs/sim/pcap_recorder.hpp"
#include "ibs/vf1000_channel/trace_adapters.hpp"
#include "output_files.hpp"
#include "trace_input.hpp"

namespace ibs::cli {

namespace {

namespace capture = sim::capture;

// What one trace step stands for in simulated time: its `step-time`, or the adapters' own.
Duration step_period(const trace::Header& h) {
  if (h.step_time) return *h.step_time;
  switch (h.words) {
    case trace::WordsKind::pd: {
      const devices::DriveKind* kind = devices::find_drive_kind(h.device);
      return kind != nullptr ? (*kind)->facts().sample_period : Duration{1ms};
    }
    case trace::WordsKind::comm: return vf1000_channel::kTraceStepPeriod;
    case trace::WordsKind::pcp: return 1ms;  // one master cycle (pcp/trace_adapters.hpp)
  }
  return 1ms;
}

// A replayed trace as a ring of one device (docs/pcap.md, "Replay"): its slices are the words a
// row carries, so a `words: comm` trace has one word each way that is the device's word 3, and a
// `words: pcp` trace only PCP words.
capture::Configuration trace_configuration(const trace::Trace& t, capture::Source source) {
  const trace::Header& h = t.header;
  capture::Configuration c;
  c.source = source;
  c.cycle_time = step_period(h);
  std::size_t pd = 0;
  std::size_t pcp = 0;
  const devices::DriveKind* kind = devices::find_drive_kind(h.device);
  const devices::DeviceSettings settings = kind != nullptr ? (*kind)->trace_settings(h) : devices::DeviceSettings{};
  capture::Device d = capture::describe(h.device, h.device, settings);
  if (kind != nullptr) {
    const devices::Configuration conf = (*kind)->configure(settings);
    switch (h.words) {
      case trace::WordsKind::pd: pd = conf.pd_words; break;
      case trace::WordsKind::comm:  // the VF1000's communication word, its process-data word 3
        pd = 1;
        d.first_word = 3;
        d.values = capture::Values::none;
        break;
      case trace::WordsKind::pcp:
        pcp = conf.pcp_words;
        d.values = capture::Values::none;
        break;
    }
  }
  d.in = {0, pd};
  d.out = {0, pd};
  d.pcp = {0, pcp};
  c.in_words = pd;
  c.out_words = pd;
  c.pcp_words = pcp;
  c.devices.push_back(std::move(d));
  return c;
}

// Writes one cycle packet per exchange step: the master's and the device's words of that step.
// The emulated side's words of a step are known one call before the other side's (it answers
// what it read in the step before), so each decorator holds its last output until the next call.
class CaptureWriter {
 public:
  CaptureWriter(const trace::Trace& t, capture::Source source, std::ostream& out)
      : config_(trace_configuration(t, source)), period_(config_.cycle_time), file_(out, sim::kLinktypeInterbus, sim::wall_clock_epoch()) {
    file_.write(Time{0}, capture::encode_configuration(config_));
  }

  // `valid` false: a step of `! no-data N`, a cycle that brought the device no valid data (the
  // master's words shown are the last the device took).
  void exchange(std::span<const Word> m2s, std::span<const Word> s2m, bool valid = true) {
    ++step_;
    const bool pcp = config_.pcp_words > 0;
    std::copy(m2s.begin(), m2s.end(), pcp ? image_.pcp_out.begin() : image_.out.begin());
    std::copy(s2m.begin(), s2m.end(), pcp ? image_.pcp_in.begin() : image_.in.begin());
    capture::encode_cycle(config_, step_, valid, image_, buffer_);
    file_.write(period_ * (step_ - 1), buffer_);
  }
  void close() { file_.close(); }
  [[nodiscard]] std::uint64_t packets() const { return file_.packets(); }

 private:
  capture::Configuration config_;
  Duration period_;
  sim::PcapFile file_;
  interbus::ProcessImage image_{};
  std::vector<std::uint8_t> buffer_;
  std::uint32_t step_ = 0;
};

class CapturingDevice final : public trace::DeviceSide {
 public:
  CapturingDevice(trace::DeviceSide& inner, CaptureWriter& w) : inner_(inner), w_(w) {}
  [[nodiscard]] std::size_t m2s_words() const override { return inner_.m2s_words(); }
  [[nodiscard]] std::size_t s2m_words() const override { return inner_.s2m_words(); }
  void initial(std::span<Word> s2m) override {
    inner_.initial(s2m);
    shown_.assign(s2m.begin(), s2m.end());
  }
  void step(std::span<const Word> m2s, std::span<Word> s2m) override {
    w_.exchange(m2s, shown_);  // the master's words of the step the device showed `shown_` in
    last_m2s_.assign(m2s.begin(), m2s.end());
    inner_.step(m2s, s2m);
    shown_.assign(s2m.begin(), s2m.end());
  }
  void step_without_data(std::span<Word> s2m) override {
    // The packet of a step of `! no-data N` (the step before this call, whose words the device
    // shows now): a cycle without valid data, the master's words the last the device took.
    w_.exchange(last_m2s_, shown_, false);
    inner_.step_without_data(s2m);
    shown_.assign(s2m.begin(), s2m.end());
  }
  [[nodiscard]] bool supports(trace::Event::Kind kind) const override { return inner_.supports(kind); }
  void apply(const trace::Event& event) override { inner_.apply(event); }
  // The last step: the device's words with the master's of that step, or with the words the
  // master kept sending when that step was not a row of the file (a gap that did not end).
  void flush(const std::optional<std::vector<Word>>& m2s) {
    if (shown_.empty()) return;
    w_.exchange(m2s ? std::span<const Word>(*m2s) : std::span<const Word>(last_m2s_), shown_);
  }

 private:
  trace::DeviceSide& inner_;
  CaptureWriter& w_;
  std::vector<Word> shown_;
  std::vector<Word> last_m2s_;
};

class CapturingMaster final : public trace::MasterSide {
 public:
  CapturingMaster(trace::MasterSide& inner, CaptureWriter& w) : inner_(inner), w_(w) {}
  [[nodiscard]] std::size_t m2s_words() const override { return inner_.m2s_words(); }
  [[nodiscard]] std::size_t s2m_words() const override { return inner_.s2m_words(); }
  void initial(std::span<Word> m2s) override {
    inner_.initial(m2s);
    shown_.assign(m2s.begin(), m2s.end());
  }
  void submit(const trace::Request& request) override { inner_.submit(request); }
  void step(std::span<const Word> s2m, std::span<const trace::WordPattern> row_m2s, std::span<Word> m2s) override {
    w_.exchange(shown_, s2m);
    last_s2m_.assign(s2m.begin(), s2m.end());
    inner_.step(s2m, row_m2s, m2s);
    shown_.assign(m2s.begin(), m2s.end());
  }
  [[nodiscard]] std::optional<trace::Outcome> outcome() const override { return inner_.outcome(); }
  void flush(const std::optional<std::vector<Word>>& s2m) {
    if (shown_.empty()) return;
    w_.exchange(shown_, s2m ? std::span<const Word>(*s2m) : std::span<const Word>(last_s2m_));
  }

 private:
  trace::MasterSide& inner_;
  CaptureWriter& w_;
  std::vector<Word> shown_;
  std::vector<Word> last_s2m_;
};

// The other side's words in the emulated side's last step, when that step is a row of the file:
// the last row after a full match (the master's extra step for `outcome` is not a row), the
// failing row after a mismatch unless a gap that never ended came before it.
std::optional<std::vector<Word>> last_row_words(const trace::Trace& t, const trace::ReplayResult& r, bool device) {
  std::vector<const trace::Row*> rows;
  std::vector<bool> after_gap;
  bool gap = false;
  for (const auto& row : t.rows) {
    if (row.gap) {
      gap = true;
      continue;
    }
    rows.push_back(&row);
    after_gap.push_back(gap);
    gap = false;
  }
  std::size_t index = 0;
  if (r.matched) {
    if (rows.empty() || (!device && t.header.outcome)) return std::nullopt;
    index = rows.size() - 1;
  } else {
    index = r.steps_matched;
    if (index >= rows.size() || after_gap[index]) return std::nullopt;
  }
  std::vector<Word> words;
  for (const auto& p : device ? rows[index]->m2s : rows[index]->s2m) words.push_back(p.value);
  return words;
}

// The replay's result for a program (`ibs replay --json`, docs/replay.md): one object on one line,
// as `ibs decode --json` prints one per file; `mismatches` holds the one mismatch replay stops at.
std::string result_json(const trace::Trace& t, const std::string& emulate, const trace::ReplayResult& r,
                        const trace::Explainer& e) {
  nlohmann::ordered_json mismatches = nlohmann::ordered_json::array();
  if (r.mismatch) {
    const trace::Mismatch& m = *r.mismatch;
    nlohmann::ordered_json j;
    j["kind"] = std::string(trace::to_string(m.kind));
    j["step"] = m.step;
    j["line"] = m.line;
    if (m.kind == trace::Mismatch::Kind::outcome) {
      j["expected"] = m.expected_outcome;
      j["actual"] = m.actual_outcome ? nlohmann::ordered_json(*m.actual_outcome) : nlohmann::ordered_json(nullptr);
    } else {
      const bool m2s = m.column == "m2s";
      nlohmann::ordered_json expected = nlohmann::ordered_json::array();
      std::vector<Word> expected_values;
      for (const trace::WordPattern& w : m.expected) {
        expected.push_back(w.to_string());
        expected_values.push_back(static_cast<Word>(w.value & w.mask));  // masked bits as 0
      }
      nlohmann::ordered_json actual = nlohmann::ordered_json::array();
      for (const Word w : m.actual) actual.push_back(trace::format_words(std::span<const Word>(&w, 1)));
      j["column"] = m.column;
      j["expected"] = std::move(expected);
      j["actual"] = std::move(actual);
      j["expected_decoded"] = m2s ? e.explain_m2s(expected_values) : e.explain_s2m(expected_values);
      j["actual_decoded"] = m2s ? e.explain_m2s(m.actual) : e.explain_s2m(m.actual);
    }
    j["message"] = r.message;
    mismatches.push_back(std::move(j));
  }
  nlohmann::ordered_json doc;
  doc["file"] = t.file;
  doc["emulate"] = emulate;
  doc["matched"] = r.matched;
  doc["steps_matched"] = r.steps_matched;
  doc["mismatches"] = std::move(mismatches);
  return doc.dump() + "\n";
}

}  // namespace

int replay(const std::string& emulate, const std::string& file, const std::string& pcap_file, bool json) {
  OutputFiles outputs;
  try {
    const trace::Trace t = load_trace_input(file);
    const bool device_side = emulate == "device";
    if (!device_side && !t.header.request) {
      std::cerr << t.file << ": no `request` header: --emulate master needs the request the master "
                << "is given (`# request: ...`, docs/replay.md); replay this trace with --emulate device\n";
      return kExitBadInput;
    }
    const auto explainer = devices::make_explainer(t);
    std::unique_ptr<CaptureWriter> writer;
    if (!pcap_file.empty()) {
      std::string error;
      std::ostream* out = outputs.open(pcap_file, error);
      if (out == nullptr) {
        std::cerr << error << "\n";
        return kExitBadInput;
      }
      try {
        writer = std::make_unique<CaptureWriter>(
            t, device_side ? capture::Source::replay_device : capture::Source::replay_master, *out);
      } catch (const std::exception& e) {
        std::cerr << pcap_file << ": " << e.what() << "\n";
        return kExitBadInput;
      }
    }
    trace::ReplayResult r;
    if (device_side) {
      const auto device = devices::make_device_side(t);
      if (writer) {
        CapturingDevice capturing(*device, *writer);
        r = trace::replay_device(t, capturing, *explainer);
        capturing.flush(last_row_words(t, r, true));
      } else {
        r = trace::replay_device(t, *device, *explainer);
      }
    } else {
      const auto master = devices::make_master_side(t);
      if (writer) {
        CapturingMaster capturing(*master, *writer);
        r = trace::replay_master(t, capturing, *explainer);
        capturing.flush(last_row_words(t, r, false));
      } else {
        r = trace::replay_master(t, *master, *explainer);
      }
    }
    // The capture is written whatever the outcome: a mismatch is what one wants to look at.
    if (writer) {
      std::string error;
      try {
        writer->close();
      } catch (const std::exception& e) {
        std::cerr << pcap_file << ": " << e.what() << "\n";
        return kExitBadInput;
      }
      if (!outputs.commit(error)) {
        std::cerr << error << "\n";
        return kExitBadInput;
      }
    }
    // With the capture on standard output (`--pcap -`), the result goes to standard error.
    std::ostream& say = outputs.uses_stdout() ? std::cerr : std::cout;
    if (json) {
      say << result_json(t, emulate, r, *explainer);
    } else if (!r.matched) {
      say << r.message << "\n";
      say << "replay: " << r.steps_matched << " steps matched before the mismatch\n";
    } else {
      say << r.message << "\n";
    }
    return r.matched ? kExitOk : kExitMismatch;
  } catch (const trace::TraceError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
}

int decode(const std::string& file, bool json) {
  try {
    const trace::Trace t = load_trace_input(file);
    const auto explainer = devices::make_explainer(t);
    if (json) {
      write_decoded_json(t, *explainer, std::cout);
    } else {
      std::cout << trace::write(trace::decode(t, *explainer));
    }
    return kExitOk;
  } catch (const trace::TraceError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
}

}  // namespace ibs::cli
