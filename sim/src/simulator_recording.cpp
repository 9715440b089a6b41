// Traces of the devices' words, recorded sample by sample (../shared/specs/trace-format.md).
#include "simulator_internal.hpp"

namespace ibs::sim {

using detail::fmt_value;

void Simulator::record_sample(Device& d, const std::array<Word, 4>& before, Time t) {
  // In the trace timing convention: this row's m2s is what the device read now, its s2m what the
  // device showed before this sample (its answer to the previous row).
  if (!d.recording && !d.module_error(t)) {
    // Start (again) once the device shows exactly what a freshly started device of a trace
    // `init` shows: initialised, START-UP INHIBIT after BLOCK POWER, channel at rest.
    const DeviceStart init = d.emu->trace_start();
    const std::array<Word, 4>& fresh = init == DeviceStart::operational ? d.fresh_operational : d.fresh_initialised;
    if (std::equal(before.begin(), before.begin() + static_cast<std::ptrdiff_t>(d.pd_words), fresh.begin())) {
      d.recording = true;
      d.recordings.back().trace.header.init = init;
    }
  }
  if (d.recording) {
    Recording& r = d.recordings.back();
    trace::Row row;
    row.step = r.step++;
    for (std::size_t w = 0; w < d.pd_words; ++w) {
      row.m2s.push_back(trace::WordPattern::exact(d.m2s[w]));
      row.s2m.push_back(trace::WordPattern::exact(before[w]));
    }
    row.remark = fmt_value(to_ms(t)) + " ms";
    if (!r.remark.empty()) row.remark += ": " + r.remark;
    r.remark.clear();
    row.events_before = std::move(r.events_ready);
    r.events_ready = std::move(r.events_pending);
    r.events_pending.clear();
    r.trace.rows.push_back(std::move(row));
  }
}

std::vector<Simulator::RecordedTrace> Simulator::traces() const {
  std::vector<RecordedTrace> out;
  for (const auto& d : devices_) {
    for (const auto& r : d->recordings) {
      if (r.trace.rows.empty()) continue;
      out.push_back({r.file_name, r.trace});
    }
  }
  return out;
}

}  // namespace ibs::sim
