// Pictures of a run (docs/simulator.md, "Plots"): each drive's reference and actual value and its
// DRIVECOM state over time, with the faults and parameter transactions of the run summary marked,
// as a gnuplot script whose output is an SVG or PNG image. The recorder follows the run through
// the simulator's Observer interface at every bus cycle end and keeps a bounded number of points
// per drive: the run is cut into `bins` equal intervals and each keeps its first, lowest, highest
// and last value, so peaks survive however long the run. Not the cycle path: it allocates.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "ibs/sim/simulator.hpp"

namespace ibs::sim {

enum class PlotFormat { svg, png };

class PlotRecorder final : public Observer {
 public:
  // `duration`: the run's length (the scenario's), for the bins.
  PlotRecorder(Simulator& sim, Duration duration, std::size_t bins = 2000);

  void on_cycle(Time at, bool valid, const interbus::ProcessImage& image) override;
  void on_sample(Time /*at*/, std::size_t /*device*/, std::span<const Word> /*m2s*/,
                 std::span<const Word> /*s2m*/) override {}
  // Ends the recording at `end` (the last bins, the states' last step).
  void finish(Time end);

  // The gnuplot script that draws the recording with the faults and transactions of `summary`
  // (the same run's): one pair of panels per drive, the values above (reference, and the actual
  // value as the master reads it and as the device has it, in its unit; faults as red dashed
  // lines), the state below (the master's view and the device's own, named on the axis;
  // parameter transactions as bars from submission to the end of the transfer, cyan if they
  // were done, red if they failed). Labels of events too close to be read apart are merged
  // (faults) or stacked in rows (transactions): docs/simulator.md, "Plots". The image goes to
  // gnuplot's standard output.
  [[nodiscard]] std::string script(const Summary& summary, PlotFormat format) const;

  struct Point {
    double t = 0.0;  // seconds
    double v = 0.0;
  };
  // Both viewpoints of one drive: the master's (what its driver decoded from the device's words,
  // which stand still while no valid cycle arrives) and the device's own.
  struct Drive {
    std::string name;
    std::string kind;  // "ID code 33BH"
    std::string unit;
    std::vector<Point> reference;      // the master's reference
    std::vector<Point> actual;         // the actual value as the master reads it
    std::vector<Point> device_actual;  // the actual value in the device
    std::vector<Point> state;          // the device's state (drivecom::State), one point per change
    std::vector<Point> seen_state;     // the state the master decoded from the status word
  };
  [[nodiscard]] const std::vector<Drive>& drives() const { return drives_; }

 private:
  struct Bin {
    bool used = false;
    Point first, low, high, last;
  };
  void add(std::vector<Point>& out, Bin& bin, std::size_t& bin_index, std::size_t index, Point p);
  static void flush(std::vector<Point>& out, Bin& bin);

  // One binned series of every drive: reference, actual (master), actual (device).
  struct Binned {
    std::vector<Bin> bins;
    std::vector<std::size_t> index;
  };
  static constexpr std::size_t kSeries = 3;

  Simulator& sim_;
  Duration bin_width_;
  std::vector<Drive> drives_;
  std::array<Binned, kSeries> binned_;
  std::vector<int> last_state_, last_seen_;
  bool finished_ = false;
};

}  // namespace ibs::sim
