// Records a simulated run as a VCD file for gtkwave (docs/vcd.md): per device the words on the
// bus as vectors named by their meaning in the device's layout (control_word, reference,
// status_word, actual, ...) and its DRIVECOM state, reference and actual value as named signals.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "ibs/sim/simulator.hpp"
#include "ibs/vcd/gtkw_writer.hpp"
#include "ibs/vcd/vcd_writer.hpp"

namespace ibs::sim {

class VcdRecorder final : public Observer {
 public:
  // Declares every signal of the simulator's ring; add it with Simulator::add_observer. `date`
  // goes into the header's $date (the run's wall-clock start; empty: no $date).
  VcdRecorder(Simulator& sim, std::ostream& out, std::string date = {});

  void on_cycle(Time at, bool valid, const interbus::ProcessImage& image) override;
  void on_sample(Time at, std::size_t device, std::span<const Word> m2s, std::span<const Word> s2m) override;
  // Closes the file at the end of the run (throws vcd::VcdError when the stream failed).
  void finish(Time end);
  // The gtkwave translate filter for the state signals (docs/vcd.md).
  [[nodiscard]] std::string state_filter() const;
  // The gtkwave save file (docs/vcd.md, "The save file"): the bus, then per device its state by
  // name (through `filter_file`, the state_filter() text), reference and actual value as analog
  // traces under a line naming their unit and scale, the master's control and status words and
  // the device's words in hex; zoomed to the
  // whole run, 0..`end`. The paths are written as given.
  [[nodiscard]] std::string save_file(const std::string& dump_file, const std::string& filter_file,
                                      const std::string& save_file, Time end) const;

 private:
  struct DeviceSignals {
    std::vector<vcd::WireSignal> device_in;   // the words the device read at its last sample
    std::vector<vcd::WireSignal> device_out;  // the words the device shows
    vcd::WireSignal control;                  // the control word in the master's output image
    vcd::WireSignal status;                   // the status word in the master's input image
    vcd::WireSignal module_error;
    vcd::StateSignal state;
    vcd::RealSignal reference;
    vcd::RealSignal actual;
    std::string unit;
  };
  void at(Time t);

  Simulator& sim_;
  vcd::VcdWriter writer_;
  vcd::WireSignal valid_;
  vcd::WireSignal cycles_;
  std::uint64_t cycle_count_ = 0;
  std::vector<DeviceSignals> devices_;
};

}  // namespace ibs::sim
