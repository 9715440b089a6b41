#include "ibs/sim/plot_recorder.hpp"

#include <algorithm>
#include <cstdio>

#include "ibs/drivecom/status_word.hpp"
#include "ibs/interbus/id_code.hpp"

namespace ibs::sim {

namespace {

double seconds(Time t) { return static_cast<double>(t.count()) / 1e9; }

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// A gnuplot string literal in double quotes (the terminals run `noenhanced`: no markup).
std::string quoted(const std::string& s) {
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + '"';
}

void datablock(std::string& out, const std::string& name, const std::vector<PlotRecorder::Point>& points) {
  out += name + " << EOD\n";
  for (const auto& p : points) out += num(p.t) + ' ' + num(p.v) + '\n';
  out += "EOD\n";
}

const char* op_word(devices::ParamOp op) {
  switch (op) {
    case devices::ParamOp::read: return "read";
    case devices::ParamOp::write: return "write";
    case devices::ParamOp::describe: return "describe";
  }
  return "?";
}

bool succeeded(devices::ParamKind k) {
  return k == devices::ParamKind::value || k == devices::ParamKind::written || k == devices::ParamKind::description;
}

// Layout in pixels; converted to screen fractions for gnuplot.
constexpr int kWidth = 1200;
constexpr int kTop = 50;       // the overall title
constexpr int kBlock = 425;    // one drive: its two panels and their labels
constexpr int kTitle = 30;     // a drive's panel title
constexpr int kValues = 200;   // the values panel
constexpr int kGap = 8;
constexpr int kStates = 130;   // the state panel
constexpr int kBottom = 10;
constexpr int kLeft = 175;     // the state names
constexpr int kRight = 230;    // the key
constexpr std::size_t kMaxFaultLabels = 30;  // per drive; every fault still gets its line

}  // namespace

PlotRecorder::PlotRecorder(Simulator& sim, Duration duration, std::size_t bins)
    : sim_(sim), bin_width_(std::max(Duration{1}, duration / static_cast<std::int64_t>(std::max<std::size_t>(bins, 1)))) {
  const interbus::BusConfig& bus = sim_.bus();
  for (std::size_t i = 0; i < sim_.device_count(); ++i) {
    Drive d;
    d.name = bus.devices[i].name;
    d.kind = "ID code " + interbus::to_hex(bus.devices[i].id);
    d.unit = std::string(sim_.driver(i).unit());
    drives_.push_back(std::move(d));
  }
  ref_bins_.resize(drives_.size());
  act_bins_.resize(drives_.size());
  ref_index_.assign(drives_.size(), 0);
  act_index_.assign(drives_.size(), 0);
  last_state_.assign(drives_.size(), -1);
}

void PlotRecorder::flush(std::vector<Point>& out, Bin& bin) {
  if (!bin.used) return;
  Point pts[4] = {bin.first, bin.low, bin.high, bin.last};
  std::sort(std::begin(pts), std::end(pts), [](const Point& a, const Point& b) { return a.t < b.t; });
  for (const Point& p : pts) {
    if (!out.empty() && out.back().t == p.t && out.back().v == p.v) continue;
    out.push_back(p);
  }
  bin = Bin{};
}

void PlotRecorder::add(std::vector<Point>& out, Bin& bin, std::size_t& bin_index, std::size_t index, Point p) {
  if (bin.used && index != bin_index) flush(out, bin);
  bin_index = index;
  if (!bin.used) {
    bin.used = true;
    bin.first = bin.low = bin.high = p;
  }
  if (p.v < bin.low.v) bin.low = p;
  if (p.v > bin.high.v) bin.high = p;
  bin.last = p;
}

void PlotRecorder::on_cycle(Time at, bool /*valid*/, const interbus::ProcessImage& /*image*/) {
  if (finished_) return;
  const auto index = static_cast<std::size_t>(at / bin_width_);
  const double t = seconds(at);
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = drives_[i];
    add(d.reference, ref_bins_[i], ref_index_[i], index, {t, sim_.driver(i).reference()});
    add(d.actual, act_bins_[i], act_index_[i], index, {t, sim_.driver(i).actual()});
    const int state = static_cast<int>(sim_.device_state(i));
    if (state != last_state_[i]) {
      d.state.push_back({t, static_cast<double>(state)});
      last_state_[i] = state;
    }
  }
}

void PlotRecorder::finish(Time end) {
  if (finished_) return;
  finished_ = true;
  const double t = seconds(end);
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = drives_[i];
    flush(d.reference, ref_bins_[i]);
    flush(d.actual, act_bins_[i]);
    if (!d.state.empty() && d.state.back().t < t) d.state.push_back({t, d.state.back().v});
  }
}

std::string PlotRecorder::script(const Summary& summary, PlotFormat format) const {
  const std::size_t n = drives_.size();
  const int height = kTop + static_cast<int>(n) * kBlock + kBottom;
  const double end = seconds(summary.simulated);
  const auto sx = [](int px) { return num(static_cast<double>(px) / kWidth); };
  const auto sy = [&](int px_from_top) { return num(1.0 - static_cast<double>(px_from_top) / height); };

  std::string s;
  s += "# ibs run --plot: each drive's reference, actual value and DRIVECOM state over time, with the run's\n";
  s += "# faults and parameter transactions (docs/simulator.md, \"Plots\"). gnuplot writes the image to stdout.\n";
  if (format == PlotFormat::svg) {
    s += "set terminal svg size " + std::to_string(kWidth) + "," + std::to_string(height) +
         " font \"sans,10\" noenhanced background rgb \"white\"\n";
  } else {
    s += "set terminal pngcairo size " + std::to_string(kWidth) + "," + std::to_string(height) +
         " font \"sans,10\" noenhanced background rgb \"white\"\n";
  }
  s += "set encoding utf8\n";

  std::vector<std::vector<const FaultRecord*>> faults(n);
  for (const auto& f : summary.faults) {
    for (std::size_t i = 0; i < n; ++i) {
      if (f.device.empty() || f.device == drives_[i].name) faults[i].push_back(&f);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::string k = std::to_string(i);
    datablock(s, "$reference" + k, drives_[i].reference);
    datablock(s, "$actual" + k, drives_[i].actual);
    datablock(s, "$state" + k, drives_[i].state);
    std::string ok, failed, labels;
    int lane = 0;
    for (const auto& tr : summary.transactions) {
      if (tr.device != drives_[i].name) continue;
      const Time stop = tr.finished ? *tr.finished : (tr.answered ? *tr.answered : summary.simulated);
      const double t0 = seconds(tr.submitted);
      const double dt = std::max(seconds(stop) - t0, end / 400.0);  // visible even when short
      (succeeded(tr.kind) ? ok : failed) += num(t0) + " 8.1 " + num(dt) + " 0\n";
      static constexpr const char* kLanes[] = {"8.5", "8.95", "9.4"};  // labels of close transactions apart
      labels += num(t0) + ' ' + kLanes[lane % 3] + ' ' +
                quoted(std::string(op_word(tr.op)) + ' ' + std::to_string(tr.number)) + '\n';
      ++lane;
    }
    s += "$ok" + k + " << EOD\n" + ok + "EOD\n";
    s += "$failed" + k + " << EOD\n" + failed + "EOD\n";
    s += "$labels" + k + " << EOD\n" + labels + "EOD\n";
  }

  s += "set multiplot title " + quoted("ibs run: " + summary.scenario + ", " + num(end) + " s simulated") +
       " font \",12\"\n";
  s += "set lmargin at screen " + sx(kLeft) + "\nset rmargin at screen " + sx(kWidth - kRight) + "\n";
  s += "set xrange [0:" + num(end) + "]\n";
  s += "set grid xtics ytics lc rgb \"#dddddd\"\n";
  s += "set key outside right top vertical Left reverse samplen 2 font \",9\"\n";
  std::string state_tics = "set ytics (";
  for (std::size_t st = 0; st < drivecom::kStateTable.size(); ++st) {
    state_tics += (st ? ", " : "") + quoted(std::string(drivecom::kStateTable[st].name)) + ' ' + std::to_string(st);
  }
  state_tics += ") font \",8\"\n";

  for (std::size_t i = 0; i < n; ++i) {
    const Drive& d = drives_[i];
    const std::string k = std::to_string(i);
    const int top = kTop + static_cast<int>(i) * kBlock;
    // Faults: a dashed red line each, named in the values panel.
    std::string lines, names;
    for (std::size_t f = 0; f < faults[i].size(); ++f) {
      const double t = seconds(faults[i][f]->at);
      lines += "set arrow from " + num(t) + ", graph 0 to " + num(t) +
               ", graph 1 nohead dashtype 2 lw 1.5 lc rgb \"#d62728\" front\n";
      if (f < kMaxFaultLabels) {
        names += "set label " + quoted(faults[i][f]->kind) + " at " + num(t) +
                 ", graph 0.97 rotate by 90 right offset 0.8,0 font \",8\" tc rgb \"#d62728\" front\n";
      }
    }
    const bool has_faults = !faults[i].empty();

    // Values panel.
    s += "\n# " + d.name + "\n";
    s += "set tmargin at screen " + sy(top + kTitle) + "\nset bmargin at screen " + sy(top + kTitle + kValues) + "\n";
    s += "set title " + quoted(d.name + " (" + d.kind + ")") + " font \",11\"\n";
    s += "unset xlabel\nset format x \"\"\nset ytics auto font \",9\"\nset yrange [*:*]\n";
    s += "set offsets 0, 0, graph 0.08, graph 0.08\n";  // the curves clear of the frame
    s += "set ylabel " + quoted("reference, actual (" + d.unit + ")") + "\n";
    s += lines + names;
    s += "plot $reference" + k + " using 1:2 with lines lw 2 dashtype 2 lc rgb \"#1f77b4\" title " +
         quoted("reference (" + d.unit + ")") + ", $actual" + k + " using 1:2 with lines lw 1.5 lc rgb \"#ff7f0e\" title " +
         quoted("actual (" + d.unit + ")");
    if (has_faults) s += ", keyentry with lines dashtype 2 lw 1.5 lc rgb \"#d62728\" title \"fault events\"";
    s += "\nunset arrow\nunset label\n";

    // State panel.
    s += "set tmargin at screen " + sy(top + kTitle + kValues + kGap) + "\nset bmargin at screen " +
         sy(top + kTitle + kValues + kGap + kStates) + "\n";
    s += "unset title\nset format x \"%g\"\nset xlabel \"time (s)\"\nset ylabel \"\"\n";
    s += "set offsets 0, 0, 0, 0\nset yrange [-0.5:9.9]\n" + state_tics;
    s += lines;
    s += "plot $state" + k + " using 1:2 with steps lw 2 lc rgb \"#2ca02c\" title \"DRIVECOM state\"";
    bool any_ok = false, any_failed = false;
    for (const auto& tr : summary.transactions) {
      if (tr.device != d.name) continue;
      (succeeded(tr.kind) ? any_ok : any_failed) = true;
    }
    if (any_ok) {
      s += ", $ok" + k + " using 1:2:3:4 with vectors nohead lw 5 lc rgb \"#17becf\" title \"parameter transactions\"";
    }
    if (any_failed) {
      s += ", $failed" + k +
           " using 1:2:3:4 with vectors nohead lw 5 lc rgb \"#d62728\" title \"failed transactions\"";
    }
    if (any_ok || any_failed) s += ", $labels" + k + " using 1:2:3 with labels left font \",7\" notitle";
    s += "\nunset arrow\nset ytics auto\n";
  }
  s += "unset multiplot\n";
  return s;
}

}  // namespace ibs::sim
