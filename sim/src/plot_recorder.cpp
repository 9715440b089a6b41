#include "ibs/sim/plot_recorder.hpp"

#include <algorithm>
#include <array>
#include <utility>
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
constexpr int kBlock = 465;    // one drive: its two panels and their labels
constexpr int kTitle = 30;     // a drive's panel title
constexpr int kValues = 200;   // the values panel
constexpr int kGap = 8;
constexpr int kStates = 170;   // the state panel, with the transaction bars and their label rows
constexpr int kBottom = 10;
constexpr int kLeft = 175;     // the state names
constexpr int kRight = 230;    // the key
constexpr int kPlotWidth = kWidth - kLeft - kRight;

// Fault labels stand upright (rotated, font 8: about 11 pixels wide); two closer than this share
// one label, so that no two overlap however the events cluster.
constexpr double kFaultLabelSpacing = 14.0;
constexpr std::size_t kFaultLabelChars = 40;  // what fits along the values panel
// Transaction labels lie flat (font 7, at most 5 pixels a character): a label takes its row for
// its text and room for a count (" +9") and a gap. Three rows above the bars; a label that finds
// none free is counted into the one before it ("read 85 +2").
constexpr double kCharWidth = 5.0;
constexpr double kLabelReserve = 3 * kCharWidth + 6.0;
double label_width(const std::string& text) { return static_cast<double>(text.size()) * kCharWidth + kLabelReserve; }
constexpr std::array<const char*, 3> kLabelRows = {"9", "9.9", "10.8"};  // state axis units
constexpr const char* kBarRow = "8.2";
constexpr const char* kStateRange = "[-0.5:11.4]";

struct FaultLabel {
  double t = 0.0;  // the first event's time
  std::string text;
};

// The labels of one drive's fault events (sorted by time): an event closer than the spacing to
// the first event of the label before it joins that label, which then says how many events it
// stands for and of which kinds ("3 events: corrupt x2, lost").
std::vector<FaultLabel> fault_labels(const std::vector<const FaultRecord*>& faults, double seconds_per_px) {
  std::vector<FaultLabel> out;
  std::size_t i = 0;
  while (i < faults.size()) {
    const double t0 = seconds(faults[i]->at);
    std::vector<std::pair<std::string, int>> kinds;  // in order of first appearance
    std::size_t j = i;
    for (; j < faults.size() && (seconds(faults[j]->at) - t0) / seconds_per_px < kFaultLabelSpacing; ++j) {
      auto it = std::find_if(kinds.begin(), kinds.end(), [&](const auto& k) { return k.first == faults[j]->kind; });
      if (it == kinds.end()) {
        kinds.emplace_back(faults[j]->kind, 1);
      } else {
        ++it->second;
      }
    }
    const std::size_t count = j - i;
    std::string text;
    if (count == 1) {
      text = faults[i]->kind;
    } else {
      text = std::to_string(count) + " events: ";
      for (std::size_t k = 0; k < kinds.size(); ++k) {
        text += (k ? ", " : "") + kinds[k].first + (kinds[k].second > 1 ? " x" + std::to_string(kinds[k].second) : "");
      }
      if (text.size() > kFaultLabelChars) text = std::to_string(count) + " events";
    }
    out.push_back({t0, std::move(text)});
    i = j;
  }
  return out;
}

struct TransactionLabel {
  double t = 0.0;
  std::size_t row = 0;
  bool right = false;  // ends at t (near the right edge) instead of starting there
  std::string text;
  int more = 0;  // transactions counted into it
};

// Rows for the labels of one drive's transactions (sorted by submission): each label takes the
// lowest row free at its place; with none free it counts into the label placed before it.
std::vector<TransactionLabel> transaction_labels(const std::vector<const TransactionRecord*>& trs,
                                                 double seconds_per_px) {
  std::vector<TransactionLabel> out;
  std::array<double, kLabelRows.size()> row_end{};
  row_end.fill(-1e300);
  for (const TransactionRecord* tr : trs) {
    const double t = seconds(tr->submitted);
    const double x = t / seconds_per_px;
    std::string text = std::string(op_word(tr->op)) + ' ' + std::to_string(tr->number);
    const double width = label_width(text);
    const bool right = x + width > kPlotWidth;
    const double start = right ? x - width : x;
    std::size_t row = 0;
    while (row < row_end.size() && row_end[row] > start) ++row;
    if (row == row_end.size() && !out.empty()) {
      ++out.back().more;
      continue;
    }
    if (row == row_end.size()) row = 0;
    row_end[row] = start + width;
    out.push_back({t, row, right, std::move(text), 0});
  }
  return out;
}

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
  for (auto& b : binned_) {
    b.bins.resize(drives_.size());
    b.index.assign(drives_.size(), 0);
  }
  last_state_.assign(drives_.size(), -1);
  last_seen_.assign(drives_.size(), -1);
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
    devices::DeviceDriver& driver = sim_.driver(i);
    add(d.reference, binned_[0].bins[i], binned_[0].index[i], index, {t, driver.reference()});
    add(d.actual, binned_[1].bins[i], binned_[1].index[i], index, {t, driver.actual()});
    add(d.device_actual, binned_[2].bins[i], binned_[2].index[i], index, {t, sim_.device_actual(i)});
    const int state = static_cast<int>(sim_.device_state(i));
    if (state != last_state_[i]) {
      d.state.push_back({t, static_cast<double>(state)});
      last_state_[i] = state;
    }
    // The master's view: the state its sequencer decoded from the last status word it took. A
    // word that matches no state (or none yet) leaves the line where it was.
    if (const auto seen = driver.sequencer().report().state_seen) {
      const int code = static_cast<int>(*seen);
      if (code != last_seen_[i]) {
        d.seen_state.push_back({t, static_cast<double>(code)});
        last_seen_[i] = code;
      }
    }
  }
}

void PlotRecorder::finish(Time end) {
  if (finished_) return;
  finished_ = true;
  const double t = seconds(end);
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = drives_[i];
    flush(d.reference, binned_[0].bins[i]);
    flush(d.actual, binned_[1].bins[i]);
    flush(d.device_actual, binned_[2].bins[i]);
    if (!d.state.empty() && d.state.back().t < t) d.state.push_back({t, d.state.back().v});
    if (!d.seen_state.empty() && d.seen_state.back().t < t) d.seen_state.push_back({t, d.seen_state.back().v});
  }
}

std::string PlotRecorder::script(const Summary& summary, PlotFormat format) const {
  const std::size_t n = drives_.size();
  const int height = kTop + static_cast<int>(n) * kBlock + kBottom;
  const double end = seconds(summary.simulated);
  const double seconds_per_px = std::max(end, 1e-9) / kPlotWidth;
  const auto sx = [](int px) { return num(static_cast<double>(px) / kWidth); };
  const auto sy = [&](int px_from_top) { return num(1.0 - static_cast<double>(px_from_top) / height); };

  std::string s;
  s += "# ibs run --plot: each drive's reference, actual value and DRIVECOM state over time, as the master sees\n";
  s += "# them and as the device has them, with the run's faults and parameter transactions\n";
  s += "# (docs/simulator.md, \"Plots\"). gnuplot writes the image to stdout.\n";
  if (format == PlotFormat::svg) {
    s += "set terminal svg size " + std::to_string(kWidth) + "," + std::to_string(height) +
         " font \"sans,10\" noenhanced background rgb \"white\"\n";
  } else {
    s += "set terminal pngcairo size " + std::to_string(kWidth) + "," + std::to_string(height) +
         " font \"sans,10\" noenhanced background rgb \"white\"\n";
  }
  s += "set encoding utf8\n";

  std::vector<std::vector<const FaultRecord*>> faults(n);
  std::vector<std::vector<const TransactionRecord*>> transactions(n);
  std::vector<int> label_sides(n, 0);  // bit 0: labels starting at their transaction, bit 1: ending there
  for (std::size_t i = 0; i < n; ++i) {
    for (const auto& f : summary.faults) {
      if (f.device.empty() || f.device == drives_[i].name) faults[i].push_back(&f);
    }
    for (const auto& tr : summary.transactions) {
      if (tr.device == drives_[i].name) transactions[i].push_back(&tr);
    }
    std::stable_sort(faults[i].begin(), faults[i].end(), [](auto* a, auto* b) { return a->at < b->at; });
    std::stable_sort(transactions[i].begin(), transactions[i].end(),
                     [](auto* a, auto* b) { return a->submitted < b->submitted; });
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::string k = std::to_string(i);
    datablock(s, "$reference" + k, drives_[i].reference);
    datablock(s, "$actual" + k, drives_[i].actual);
    datablock(s, "$device_actual" + k, drives_[i].device_actual);
    datablock(s, "$state" + k, drives_[i].state);
    datablock(s, "$seen_state" + k, drives_[i].seen_state);
    std::string ok, failed, left, right;
    for (const TransactionRecord* tr : transactions[i]) {
      const Time stop = tr->finished ? *tr->finished : (tr->answered ? *tr->answered : summary.simulated);
      const double t0 = seconds(tr->submitted);
      const double dt = std::max(seconds(stop) - t0, end / 400.0);  // visible even when short
      (succeeded(tr->kind) ? ok : failed) += num(t0) + ' ' + kBarRow + ' ' + num(dt) + " 0\n";
    }
    for (const auto& l : transaction_labels(transactions[i], seconds_per_px)) {
      const std::string text = l.more > 0 ? l.text + " +" + std::to_string(l.more) : l.text;
      (l.right ? right : left) += num(l.t) + ' ' + kLabelRows[l.row] + ' ' + quoted(text) + '\n';
      label_sides[i] |= l.right ? 2 : 1;
    }
    s += "$ok" + k + " << EOD\n" + ok + "EOD\n";
    s += "$failed" + k + " << EOD\n" + failed + "EOD\n";
    s += "$labels" + k + " << EOD\n" + left + "EOD\n";
    s += "$labels_right" + k + " << EOD\n" + right + "EOD\n";
  }

  s += "set multiplot title " + quoted("ibs run: " + summary.scenario + ", " + num(end) + " s simulated") +
       " font \",12\"\n";
  s += "set lmargin at screen " + sx(kLeft) + "\nset rmargin at screen " + sx(kWidth - kRight) + "\n";
  s += "set xrange [0:" + num(end) + "]\n";
  // A grid at every tic, and fainter at the minor time tics between them.
  s += "set mxtics 5\n";
  s += "set grid xtics ytics mxtics lt 1 lw 1 lc rgb \"#d0d0d0\", lt 1 lw 0.5 lc rgb \"#ececec\"\n";
  s += "set key outside right top vertical Left reverse samplen 2 font \",9\"\n";
  std::string state_tics = "set ytics (";
  for (std::size_t st = 0; st < drivecom::kStateTable.size(); ++st) {
    state_tics += (st ? ", " : "") + quoted(std::string(drivecom::kStateTable[st].name)) + ' ' + std::to_string(st);
  }
  state_tics += ") font \",8\"\n";
  const std::string fault_key = ", keyentry with lines dashtype 2 lw 1.5 lc rgb \"#d62728\" title \"fault events\"";

  for (std::size_t i = 0; i < n; ++i) {
    const Drive& d = drives_[i];
    const std::string k = std::to_string(i);
    const int top = kTop + static_cast<int>(i) * kBlock;
    // Faults: a dashed red line each, named in the values panel (close ones under one label).
    std::string lines, names;
    for (const FaultRecord* f : faults[i]) {
      const double t = seconds(f->at);
      lines += "set arrow from " + num(t) + ", graph 0 to " + num(t) +
               ", graph 1 nohead dashtype 2 lw 1.5 lc rgb \"#d62728\" front\n";
    }
    for (const auto& l : fault_labels(faults[i], seconds_per_px)) {
      names += "set label " + quoted(l.text) + " at " + num(l.t) +
               ", graph 0.97 rotate by 90 right offset 0.8,0 font \",8\" tc rgb \"#d62728\" front\n";
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
         quoted("reference (" + d.unit + ")") + ", $actual" + k +
         " using 1:2 with lines lw 2.5 lc rgb \"#ff7f0e\" title " + quoted("actual, master's view (" + d.unit + ")") +
         ", $device_actual" + k + " using 1:2 with lines lw 1 lc rgb \"#8c564b\" title " +
         quoted("actual, device (" + d.unit + ")");
    if (has_faults) s += fault_key;
    s += "\nunset arrow\nunset label\n";

    // State panel.
    s += "set tmargin at screen " + sy(top + kTitle + kValues + kGap) + "\nset bmargin at screen " +
         sy(top + kTitle + kValues + kGap + kStates) + "\n";
    s += "unset title\nset format x \"%g\"\nset xlabel \"time (s)\"\nset ylabel \"\"\n";
    s += std::string("set offsets 0, 0, 0, 0\nset yrange ") + kStateRange + "\n" + state_tics;
    s += lines;
    s += "plot $seen_state" + k + " using 1:2 with steps lw 4 lc rgb \"#98df8a\" title \"state, master's view\", $state" +
         k + " using 1:2 with steps lw 1.5 dashtype 2 lc rgb \"#2ca02c\" title \"state, device\"";
    if (!transactions[i].empty()) {
      // Both colours in the key whenever the drive has transactions, so that either reads alone.
      const bool any_ok = std::any_of(transactions[i].begin(), transactions[i].end(),
                                      [](auto* tr) { return succeeded(tr->kind); });
      const bool any_failed = std::any_of(transactions[i].begin(), transactions[i].end(),
                                          [](auto* tr) { return !succeeded(tr->kind); });
      const std::string done_style = " with vectors nohead lw 5 lc rgb \"#17becf\" title \"done transactions\"";
      const std::string failed_style = " with vectors nohead lw 5 lc rgb \"#d62728\" title \"failed transactions\"";
      s += any_ok ? ", $ok" + k + " using 1:2:3:4" + done_style : ", keyentry" + done_style;
      s += any_failed ? ", $failed" + k + " using 1:2:3:4" + failed_style : ", keyentry" + failed_style;
      if (label_sides[i] & 1) s += ", $labels" + k + " using 1:2:3 with labels left font \",7\" notitle";
      if (label_sides[i] & 2) s += ", $labels_right" + k + " using 1:2:3 with labels right font \",7\" notitle";
    }
    s += "\nunset arrow\nset ytics auto\n";
  }
  s += "unset multiplot\n";
  return s;
}

}  // namespace ibs::sim
