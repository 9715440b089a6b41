// Traces of the devices' words, recorded sample by sample (../shared/specs/trace-format.md).
#include "simulator_internal.hpp"

namespace ibs::sim {

using detail::fmt_value;

void Simulator::record_sample(Device& d, const std::array<Word, 4>& before, Time t) {
  // In the trace timing convention: this row's m2s is what the device read now, its s2m what the
  // device showed before this sample (its answer to the previous row). A sample that no valid
  // cycle reached since the one before (a corrupted cycle and its recovery cycles, a lost device,
  // a stopped bus, or a bus cycle slower than the device's samples) is a step without data: no
  // row, counted in `! no-data N` -- replay runs the device without feeding its watchdog, as
  // the run did. Before the device ever got data, its samples are rows as any other (they see
  // the words it starts with; its watchdog is not yet armed).
  const bool data = d.delivered || !d.ever_delivered;
  d.delivered = false;
  if (!d.recording && !d.module_error(t) && data) {
    // Start (again) once the device shows exactly what a freshly started device of a trace
    // `init` shows: initialised, START-UP INHIBIT after BLOCK POWER, channel at rest.
    const DeviceStart init = d.emu->trace_start();
    const std::array<Word, 4>& fresh = init == DeviceStart::operational ? d.fresh_operational : d.fresh_initialised;
    if (std::equal(before.begin(), before.begin() + static_cast<std::ptrdiff_t>(d.pd_words), fresh.begin())) {
      d.recording = true;
      d.recordings.back().trace.header.init = init;
    }
  }
  if (d.recording && !data && !d.recordings.back().trace.rows.empty()) {
    Recording& r = d.recordings.back();
    ++r.step;
    if (!r.between.empty() && r.between.back().kind == trace::Event::Kind::no_data) {
      ++r.between.back().steps;
    } else {
      r.between.push_back({trace::Event::Kind::no_data, "", 0, 1});
    }
  } else if (d.recording && data) {
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
    row.events_before = std::move(r.between);
    r.between.clear();
    r.trace.rows.push_back(std::move(row));
  }
  if (d.recording && !d.recordings.back().trace.rows.empty()) {
    // Injected before this sample: they act before the step after it.
    Recording& r = d.recordings.back();
    r.between.insert(r.between.end(), r.events_pending.begin(), r.events_pending.end());
    r.events_pending.clear();
  }
}

void Simulator::record_changes(Device& d) {
  // What the drive's other channels changed (the MC6000's PCP, a test bench's LUSTBUS face) since
  // the last sample: `! write PNR VALUE` before the step whose sample comes next, as an injected
  // fault (trace-format.md, "Events"). Outside a recording they are dropped.
  std::array<drive::ParameterChange, drive::ParameterJournal::kCapacity> changes{};
  const std::size_t n = d.emu->take_changes(changes);
  if (n == 0 || !d.recording) return;
  Recording& r = d.recordings.back();
  for (std::size_t i = 0; i < n; ++i) {
    trace::Event e;
    e.kind = trace::Event::Kind::write;
    e.parameter = changes[i].number;
    e.value = changes[i].value;
    r.events_pending.push_back(std::move(e));
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
