// The test bench (docs/testbench.md): while `ibs run --realtime` runs a scenario, the devices that
// have `lustbus = ADDR` answer on the scenario's LUSTBUS line too, and its DFS-1 controllers on
// their line -- a new pseudo-terminal or a serial port the user names. A drive served on both buses
// is one drive: its LUSTBUS face is attached to the drive core of the simulator's own emulator
// (LustbusFace::attach), so that what one bus writes the other reads. The lines are served from the
// simulator's thread once per bus cycle (turn(), called by the real-time runner's each_cycle hook
// between two deadlines): nothing is shared between threads, nothing locks. Floor 4: it opens the
// ports; the faces and the controllers stay sans-I/O. The command line's: it builds each line's
// drives through their wings' faces, as the emulate commands do.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/base/time.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"


namespace ibs::cli {

// What one served drive or controller heard and answered, for the run summary.
struct BenchDeviceReport {
  std::string name;
  std::string line;   // "lustbus" or "dfs1"
  int address = 0;    // LUSTBUS address or DFS-1 unit id
  std::uint64_t telegrams = 0;   // requests taken (LUSTBUS: ENQUIRY + SELECT + broadcasts)
  std::uint64_t answers = 0;     // answers sent
  std::uint64_t errors = 0;      // check-character errors
  std::uint64_t dropped = 0;     // improper or cut telegrams thrown away (fragments after silence included)
};

struct BenchReport {
  std::vector<std::string> lines;  // as ready_lines() said them
  std::vector<BenchDeviceReport> devices;
  std::vector<std::string> events;  // controllers' timeline events as applied ("1.000 s press: ...")
};

class Bench {
 public:
  // After `sim` is built and before it runs. Makes the faces on the simulator's drive cores and
  // the controllers, and opens the lines; throws std::invalid_argument naming `file` for a rate a
  // drive does not run at, a port that cannot be opened, a drive that does not speak LUSTBUS.
  Bench(sim::Simulator& sim, const sim::Scenario& scenario, const std::string& file);
  ~Bench();
  Bench(const Bench&) = delete;
  Bench& operator=(const Bench&) = delete;

  // One line per served line, the words a script waits for: "lustbus pty: /dev/pts/3",
  // "dfs1 port: /dev/ttyUSB0".
  [[nodiscard]] std::vector<std::string> ready_lines() const;
  // Notes the ports gave when opened (RS-485 refused by the driver ...).
  [[nodiscard]] std::vector<std::string> notes() const;

  // One turn of every line at `now` (the simulator's time): what arrived is heard, what is due
  // goes out; the controllers' timeline entries due by `now` are applied first. Allocates nothing
  // but the summary's line of such an entry (a rare event, not the cycle's work); writes wait for
  // the driver as SerialPort::write does (on a pty: at once).
  void turn(Time now);

  // Whether `name` is one of the bench's DFS-1 controllers.
  [[nodiscard]] bool serves_controller(const std::string& name) const;
  // What is wrong with an entry for one of them (its event as the DFS-1 wing reads control lines:
  // a cause of the DFS-1 manual, an input, a load in range), nullopt when nothing is or the entry is not
  // a controller's.
  [[nodiscard]] std::optional<std::string> check(const sim::TimelineEntry& e) const;
  // A timeline or control entry for a DFS-1 controller of the bench, applied at `now` (an entry
  // check() refuses is not applied): true when `e.device` is one, false when it is not the bench's.
  // Allocates (the summary's line): the control channel's and the timeline's rare events only.
  bool apply(const sim::TimelineEntry& e, Time now);

  [[nodiscard]] BenchReport report() const;
  // The same counters as report()'s devices, one served drive or controller at a time, without
  // allocating (`ibs run --stats-every`, on the simulator's thread between two deadlines).
  struct Counters {
    std::string_view name;
    std::string_view line;  // "lustbus" or "dfs1"
    int address = 0;
    std::uint64_t telegrams = 0, answers = 0, errors = 0, dropped = 0;
  };
  [[nodiscard]] std::size_t served() const;
  [[nodiscard]] Counters counters(std::size_t i) const;

  // Whether the bench serves the line `key` ("lustbus", "dfs1").
  [[nodiscard]] bool serves_line(std::string_view key) const;
  // Records the served line `key` as a capture into `out` (docs/pcap.md, "Serial lines"): every
  // telegram, the host's and the served devices', stamped with the simulated time of the turn
  // that read or wrote it plus `epoch` (the run's wall-clock start, as the INTERBUS capture has
  // it, so that the two merge into one timeline). Before the run. Throws std::invalid_argument
  // when the bench serves no such line, pcap::PcapError when libpcap refuses.
  void capture(std::string_view key, std::ostream& out, Time epoch);
  // After the run: the telegrams still pending written and the capture closed; its packets.
  // Throws pcap::PcapError when the stream failed.
  std::uint64_t finish_capture(std::string_view key);
  // Drops the captures not finished (a run that fails or is interrupted): what they hold goes into
  // their streams now, while those still exist, and is then thrown away with them.
  void drop_captures();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The report as the run summary's text ("test bench" section) and as a JSON object.
std::string format_bench_text(const BenchReport& r);
std::string format_bench_json(const BenchReport& r);

}  // namespace ibs::cli
