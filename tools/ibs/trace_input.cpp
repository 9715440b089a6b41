#include "trace_input.hpp"

#include <iostream>
#include <nlohmann/json.hpp>

#include "ibs/devices/trace_adapters.hpp"
#include "ibs/base/text_file.hpp"
#include "ibs/base/time_text.hpp"

namespace ibs::cli {

trace::Trace load_trace_input(const std::string& file) {
  if (file != "-") return devices::load_trace(file);
  std::string text;
  std::string chunk(64 * 1024, '\0');
  while (std::cin.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || std::cin.gcount() > 0) {
    text.append(chunk.data(), static_cast<std::size_t>(std::cin.gcount()));
    if (text.size() > kMaxInputFileBytes) {
      throw trace::TraceError(kStdinName, 0,
                              "more than " + std::to_string(kMaxInputFileBytes >> 20U) +
                                  " MiB: not a trace");
    }
  }
  if (std::cin.bad()) throw trace::TraceError(kStdinName, 0, "cannot read standard input");
  return devices::parse_trace(text, kStdinName);
}

std::string check_inputs(const std::vector<std::string>& files) {
  std::size_t stdin_count = 0;
  for (const std::string& f : files) stdin_count += f == "-" ? 1U : 0U;
  if (stdin_count > 1) return "'-' (standard input) can be given only once";
  return "";
}

namespace {

nlohmann::json words_json(const std::vector<trace::WordPattern>& words) {
  nlohmann::json a = nlohmann::json::array();
  for (const trace::WordPattern& w : words) a.push_back(w.to_string());
  return a;
}

std::vector<Word> values_of(const std::vector<trace::WordPattern>& words) {
  std::vector<Word> v;
  v.reserve(words.size());
  for (const trace::WordPattern& w : words) v.push_back(static_cast<Word>(w.value & w.mask));
  return v;
}

}  // namespace

void write_decoded_json(const trace::Trace& t, const trace::Explainer& e, std::ostream& out) {
  // decode() checks the rows' word counts against the explainer, with FILE:LINE.
  (void)trace::decode(t, e);
  const trace::Header& h = t.header;
  nlohmann::json header;
  header["device"] = h.device;
  header["words"] = std::string(trace::to_string(h.words));
  for (const trace::HeaderSetting& s : h.settings) header[s.key] = s.value;
  header["init"] = std::string(trace::to_string(h.init));
  if (h.request) {
    header["request"] = trace::to_string(*h.request);
    header["request_at"] = h.request_at;
  }
  if (h.outcome) header["outcome"] = trace::to_string(*h.outcome);
  header["max_gap"] = h.max_gap;
  if (h.watchdog_ms) header["watchdog_ms"] = *h.watchdog_ms;
  if (h.step_time) header["step_time"] = format_time(*h.step_time);
  // `setting: NAME VALUE`: each as its text, under `settings`.
  if (!h.device_settings.empty()) {
    nlohmann::json settings = nlohmann::json::object();
    for (const trace::DeviceSetting& d : h.device_settings) settings[d.name] = d.value;
    header["settings"] = std::move(settings);
  }
  nlohmann::json rows = nlohmann::json::array();
  for (const trace::Row& r : t.rows) {
    nlohmann::json row;
    row["line"] = r.line;
    if (r.gap) {
      row["gap"] = true;
    } else {
      row["step"] = r.step;
      row["m2s"] = words_json(r.m2s);
      row["s2m"] = words_json(r.s2m);
      row["m2s_decoded"] = e.explain_m2s(values_of(r.m2s));
      row["s2m_decoded"] = e.explain_s2m(values_of(r.s2m));
      if (!r.remark.empty()) row["remark"] = r.remark;
    }
    if (!r.comments_before.empty()) row["comments"] = r.comments_before;
    if (!r.events_before.empty()) {
      nlohmann::json events = nlohmann::json::array();
      for (const trace::Event& ev : r.events_before) {
        nlohmann::json event{{"event", std::string(trace::to_string(ev.kind))}, {"text", ev.text}, {"line", ev.line}};
        if (ev.kind == trace::Event::Kind::no_data) event["steps"] = ev.steps;
        if (ev.kind == trace::Event::Kind::write) {
          event["parameter"] = ev.parameter;
          event["value"] = ev.value;
          event["decoded"] = e.explain_write(ev.parameter, ev.value);
        }
        events.push_back(std::move(event));
      }
      row["events"] = std::move(events);
    }
    rows.push_back(std::move(row));
  }
  nlohmann::json doc;
  doc["file"] = t.file;
  doc["format"] = "ibs-trace 1";
  doc["header"] = std::move(header);
  doc["rows"] = std::move(rows);
  out << doc.dump() << "\n";
}

}  // namespace ibs::cli
