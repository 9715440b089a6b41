#include "ibs/sim/vcd_recorder.hpp"

#include <algorithm>

namespace ibs::sim {

namespace {

std::vector<std::string> state_names() {
  std::vector<std::string> names;
  for (const auto& row : drivecom::kStateTable) {
    std::string n(row.name);
    std::replace(n.begin(), n.end(), ' ', '_');
    names.push_back(n);
  }
  return names;
}

std::string signal_name(const std::string& device) {
  std::string n = device;
  for (char& c : n) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) c = '_';
  }
  return n;
}

// The wire names of one direction's words: each word's role in the device's layout (`ibs
// layout`: control_word, reference, status_word, actual, reference_q16_high, ...), else
// `<fallback>N`. A name the scope already has gets the direction appended (`no_data_out`).
std::vector<std::string> word_names(const std::vector<devices::WordMeaning>& meanings, std::size_t count,
                                    const char* fallback, const char* direction, std::vector<std::string>& taken) {
  std::vector<std::string> names;
  for (std::size_t w = 0; w < count; ++w) {
    std::string n = fallback + std::to_string(w + 1);
    for (const devices::WordMeaning& m : meanings) {
      if (m.word == static_cast<int>(w + 1) && !m.role.empty()) n = signal_name(m.role);
    }
    if (std::find(taken.begin(), taken.end(), n) != taken.end()) n += direction;
    while (std::find(taken.begin(), taken.end(), n) != taken.end()) n += "_";
    taken.push_back(n);
    names.push_back(n);
  }
  return names;
}

}  // namespace

VcdRecorder::VcdRecorder(Simulator& sim, std::ostream& out, std::string date)
    : sim_(sim), writer_(out, vcd::VcdHeader{std::move(date), "", "ibs cycle simulator"}) {
  writer_.begin_scope("bus");
  valid_ = writer_.add_wire("cycle_valid", 1, 1);
  cycles_ = writer_.add_wire("cycles", 32, 0);
  writer_.end_scope();
  const interbus::BusConfig& cfg = sim_.bus();
  for (std::size_t i = 0; i < sim_.device_count(); ++i) {
    const interbus::Device& d = cfg.devices[i];
    DeviceSignals s;
    writer_.begin_scope(signal_name(d.name));
    // The names the scope's other signals take; the words must not collide with them.
    std::vector<std::string> taken{"master_control", "master_status", "module_error", "state"};
    const devices::LayoutDescription layout = sim_.layout(i);
    for (const std::string& n : word_names(layout.out_words, d.pd_out_words, "m2s_w", "_out", taken)) {
      s.device_in.push_back(writer_.add_wire(n, 16));
    }
    for (const std::string& n : word_names(layout.in_words, d.pd_in_words, "s2m_w", "_in", taken)) {
      s.device_out.push_back(writer_.add_wire(n, 16));
    }
    s.unit = std::string(sim_.driver(i).unit());
    s.control = writer_.add_wire("master_control", 16);
    s.status = writer_.add_wire("master_status", 16);
    s.module_error = writer_.add_wire("module_error", 1);
    s.state = writer_.add_state("state", state_names(), static_cast<std::uint64_t>(sim_.device_state(i)));
    s.reference = writer_.add_real(std::string("reference_") + std::string(sim_.driver(i).unit()));
    s.actual = writer_.add_real(std::string("actual_") + std::string(sim_.driver(i).unit()));
    writer_.end_scope();
    devices_.push_back(std::move(s));
  }
}

void VcdRecorder::at(Time t) {
  if (t > writer_.now()) writer_.advance(t);
}

void VcdRecorder::on_cycle(Time t, bool valid, const interbus::ProcessImage& image) {
  at(t);
  ++cycle_count_;
  writer_.change(valid_, valid ? 1U : 0U);
  writer_.change(cycles_, cycle_count_ & 0xFFFFFFFFU);
  const interbus::BusConfig& cfg = sim_.bus();
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    const auto in = interbus::in_slice(image, cfg.devices[i]);
    const auto out = interbus::out_slice(image, cfg.devices[i]);
    if (!out.empty()) writer_.change(devices_[i].control, out[0]);
    if (!in.empty()) writer_.change(devices_[i].status, in[0]);
    writer_.change(devices_[i].reference, sim_.driver(i).reference());
  }
}

void VcdRecorder::on_sample(Time t, std::size_t i, std::span<const Word> m2s, std::span<const Word> s2m) {
  at(t);
  DeviceSignals& s = devices_[i];
  for (std::size_t w = 0; w < s.device_in.size() && w < m2s.size(); ++w) writer_.change(s.device_in[w], m2s[w]);
  for (std::size_t w = 0; w < s.device_out.size() && w < s2m.size(); ++w) writer_.change(s.device_out[w], s2m[w]);
  writer_.change(s.state, static_cast<std::uint64_t>(sim_.device_state(i)));
  writer_.change(s.actual, sim_.device_actual(i));
  writer_.change(s.module_error, sim_.module_error(i, t) ? 1U : 0U);
}

void VcdRecorder::finish(Time end) {
  at(end);
  writer_.finish();
}

std::string VcdRecorder::save_file(const std::string& dump_file, const std::string& filter_file,
                                   const std::string& save_file, Time end) const {
  vcd::GtkwSave g(writer_, dump_file, save_file, end);
  const interbus::BusConfig& cfg = sim_.bus();
  g.open_scope("bus");
  g.comment("bus");
  g.add(valid_);
  g.add(cycles_);
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    const DeviceSignals& s = devices_[i];
    const interbus::Device& d = cfg.devices[i];
    g.open_scope(signal_name(d.name));
    g.comment(d.name + " (ID code " + interbus::to_hex(d.id) + ")");
    g.add(s.state, filter_file);
    // Each analog row spans its own values over the whole run (gtkwave's Resizing > All Data), so
    // its height means the same wherever the window is scrolled; the line above names the unit (short:
    // gtkwave widens the signal pane to its longest line).
    g.comment("reference, actual: " + s.unit);
    g.add(s.reference);
    g.add(s.actual);
    g.add(s.control);
    g.add(s.status);
    g.add(s.module_error);
    for (const auto& w : s.device_in) g.add(w);
    for (const auto& w : s.device_out) g.add(w);
  }
  return g.text();
}

std::string VcdRecorder::state_filter() const {
  return devices_.empty() ? std::string() : writer_.translate_filter(devices_.front().state);
}

}  // namespace ibs::sim
