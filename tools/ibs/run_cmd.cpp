// `ibs run [SCENARIO] [--json] [--trace DIR] [--vcd FILE] [--threads N]`: the main job.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "commands.hpp"
#include "ibs/sim/report.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"
#include "ibs/sim/vcd_recorder.hpp"

namespace ibs::cli {

namespace {

bool write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  return static_cast<bool>(out);
}

}  // namespace

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
  // Recordings go to files named up front, so a path that cannot be written fails before the run.
  if (!o.trace_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.trace_dir, ec);
    if (ec || !std::filesystem::is_directory(o.trace_dir)) {
      std::cerr << o.trace_dir << ": cannot create the trace directory" << (ec ? ": " + ec.message() : "") << "\n";
      return kExitBadInput;
    }
  }
  std::unique_ptr<std::ofstream> vcd_file;
  std::unique_ptr<sim::VcdRecorder> vcd;
  if (!o.vcd_file.empty()) {
    vcd_file = std::make_unique<std::ofstream>(o.vcd_file, std::ios::binary);
    if (!*vcd_file) {
      std::cerr << o.vcd_file << ": cannot write the VCD file\n";
      return kExitBadInput;
    }
    vcd = std::make_unique<sim::VcdRecorder>(*simulator, *vcd_file);
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
      vcd_file->close();
    } catch (const std::exception& e) {
      std::cerr << o.vcd_file << ": " << e.what() << "\n";
      return kExitBadInput;
    }
    // The state names for gtkwave's translate filter (docs/vcd.md), beside the VCD file.
    if (!write_file(o.vcd_file + ".states.txt", vcd->state_filter()) || !*vcd_file) {
      std::cerr << o.vcd_file << ": cannot write the VCD file\n";
      return kExitBadInput;
    }
  }

  const sim::Summary& summary = simulator->summary();
  std::cout << (o.json ? sim::format_json(summary) : sim::format_text(summary));
  if (!o.trace_dir.empty()) {
    for (const auto& r : simulator->traces()) {
      const auto path = std::filesystem::path(o.trace_dir) / r.file_name;
      if (!write_file(path, trace::write(r.trace))) {
        std::cerr << path.string() << ": cannot write the trace\n";
        return kExitBadInput;
      }
      if (!o.json) std::cout << "trace written: " << path.string() << "\n";
    }
  }
  if (vcd && !o.json) {
    std::cout << "VCD written: " << o.vcd_file << " (state names for gtkwave: " << o.vcd_file << ".states.txt)\n";
  }
  return kExitOk;
}

}  // namespace ibs::cli
