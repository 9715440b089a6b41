// `ibs run [SCENARIO] [--json] [--trace DIR] [--vcd FILE] [--threads N]`: the main job.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "commands.hpp"
#include "output_files.hpp"
#include "ibs/sim/report.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"
#include "ibs/sim/vcd_recorder.hpp"

namespace ibs::cli {

int run(const RunOptions& o) {
  sim::Scenario scenario;
  try {
    scenario = o.scenario.empty() ? sim::default_scenario() : sim::load_scenario(o.scenario);
  } catch (const sim::ScenarioError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
  std::unique_ptr<sim::Simulator> simulator;
  try {
    simulator = std::make_unique<sim::Simulator>(scenario);
  } catch (const std::invalid_argument& e) {
    std::cerr << (o.scenario.empty() ? std::string("default scenario") : o.scenario) << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  // Every output is written under a temporary name and renamed into place only when all of them
  // have been written; a path that cannot be created fails before the run.
  OutputFiles outputs;
  std::string error;
  if (!o.trace_dir.empty() && !outputs.make_directory(o.trace_dir, error)) {
    std::cerr << error << "\n";
    return kExitBadInput;
  }
  std::unique_ptr<sim::VcdRecorder> vcd;
  if (!o.vcd_file.empty()) {
    std::ostream* vcd_stream = outputs.open(o.vcd_file, error);
    if (vcd_stream == nullptr) {
      std::cerr << error << "\n";
      return kExitBadInput;
    }
    vcd = std::make_unique<sim::VcdRecorder>(*simulator, *vcd_stream);
    simulator->add_observer(vcd.get());
  }

  sim::SimOptions options;
  options.record_traces = !o.trace_dir.empty();
  options.threads = o.threads;
  // A long run shows its progress on a terminal (never in pipes or files).
  const bool tty = isatty(fileno(stderr)) != 0;
  auto last = std::chrono::steady_clock::now();
  bool shown = false;
  if (tty) {
    options.progress = [&](Time now, Duration total) {
      const auto w = std::chrono::steady_clock::now();
      if (w - last < std::chrono::milliseconds(250)) return;
      last = w;
      shown = true;
      std::fprintf(stderr, "\r  simulated %.1f s of %.1f s (%3.0f %%)", to_ms(now) / 1000.0, to_ms(total) / 1000.0,
                   100.0 * to_ms(now) / to_ms(total));
      std::fflush(stderr);
    };
  }
  simulator->run(options);
  if (shown) std::fprintf(stderr, "\r%60s\r", "");
  if (vcd) {
    try {
      vcd->finish(scenario.duration);
    } catch (const std::exception& e) {
      std::cerr << o.vcd_file << ": " << e.what() << "\n";
      return kExitBadInput;
    }
    // The state names for gtkwave's translate filter (docs/vcd.md), beside the VCD file.
    if (!outputs.write(o.vcd_file + ".states.txt", vcd->state_filter(), error)) {
      std::cerr << error << "\n";
      return kExitBadInput;
    }
  }
  std::vector<std::string> written;
  if (!o.trace_dir.empty()) {
    for (const auto& r : simulator->traces()) {
      const auto path = std::filesystem::path(o.trace_dir) / r.file_name;
      if (!outputs.write(path, trace::write(r.trace), error)) {
        std::cerr << error << "\n";
        return kExitBadInput;
      }
      written.push_back(path.string());
    }
  }
  if (!outputs.commit(error)) {
    std::cerr << error << "\n";
    return kExitBadInput;
  }

  // The summary only once every file is in place: a run that could not be saved says nothing else.
  const sim::Summary& summary = simulator->summary();
  std::cout << (o.json ? sim::format_json(summary) : sim::format_text(summary));
  if (!o.json) {
    for (const auto& path : written) std::cout << "trace written: " << path << "\n";
    if (vcd) {
      std::cout << "VCD written: " << o.vcd_file << " (state names for gtkwave: " << o.vcd_file << ".states.txt)\n";
    }
  }
  return kExitOk;
}

}  // namespace ibs::cli
