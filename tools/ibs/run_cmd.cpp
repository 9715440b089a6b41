// `ibs run [SCENARIO] [--json] [--trace DIR] [--vcd FILE] [--pcap FILE] [--plot FILE] [--threads N]
// [--realtime [--rt-priority N] [--control SPEC] [--lustbus-pcap FILE] [--dfs1-pcap FILE]]`:
// the main job.
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <string_view>
#include <variant>

#include <nlohmann/json.hpp>

#include "bench.hpp"
#include "commands.hpp"
#include "gnuplot.hpp"
#include "output_files.hpp"
#include "progress.hpp"
#include "run_stats.hpp"
#include "stop_signals.hpp"
#include "trace_input.hpp"
#include "ibs/base/text_file.hpp"
#include "ibs/control/channel.hpp"
#include "ibs/sim/canlust_scenario.hpp"
#include "ibs/sim/pcap_recorder.hpp"
#include "ibs/sim/plot_recorder.hpp"
#include "ibs/sim/realtime.hpp"
#include "ibs/sim/report.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/scenario_file.hpp"
#include "ibs/sim/simulator.hpp"
#include "ibs/sim/vcd_recorder.hpp"
#include "ibs/tool/format.hpp"

namespace ibs::cli {

namespace {

// The simulated time run between two looks for SIGINT / SIGTERM (the run is the same in slices).
constexpr Duration kRunSlice = std::chrono::milliseconds(200);

// The image format a --plot file asks for by its extension.
std::optional<sim::PlotFormat> plot_format(const std::string& file) {
  std::string ext = std::filesystem::path(file).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".svg") return sim::PlotFormat::svg;
  if (ext == ".png") return sim::PlotFormat::png;
  return std::nullopt;
}

// The live control channel of `ibs run --realtime --control SPEC`: once per cycle, the lines that
// have arrived (control::Limits bounds them) are read as timeline entries without `at` and applied
// at the simulated time reached; a bad one is reported on stderr as `control:LINE: what is wrong`
// (`control:CLIENT:LINE` for a socket's client) and skipped.
// An entry for a DFS-1 controller of the test bench goes to the bench, which lists it in its part
// of the summary; every other to the simulator.
std::function<void(Time)> control_each_cycle(control::Channel& input, sim::Simulator& simulator,
                                             const sim::Scenario& scenario, Bench* bench) {
  return [&input, &simulator, &scenario, bench](Time now) {
    input.poll(
        [&](const control::Origin& from, std::string_view text) {
          try {
            sim::TimelineEntry e = sim::parse_control_line(std::string(text), from.line, scenario, std::string(from.name));
            e.source_client = from.client;
            if (bench != nullptr && bench->serves_controller(e.device)) {
              if (const auto why = bench->check(e)) {
                std::cerr << from << ": " << *why << "\n";
              } else {
                bench->apply(e, now);
              }
            } else {
              simulator.control(std::move(e));
            }
          } catch (const sim::ScenarioError& e) {
            std::cerr << e.what() << "\n";
          }
        },
        [](const control::Origin& from, std::string_view what) { std::cerr << from << ": " << what << "\n"; },
        [](std::string_view notice) { std::cerr << notice << "\n"; });
  };
}

// The scenario of `ibs run`: a file (its extension gives the format unless --format does), or
// standard input for `-` (--format required); every problem a sim::ScenarioError naming
// FILE:LINE (`<stdin>:LINE` for `-`).
sim::AnyScenario load_run_scenario(const RunOptions& o) {
  const auto format = [&o]() {
    return o.format == "json" ? sim::ScenarioFormat::json : sim::ScenarioFormat::toml;
  };
  if (o.scenario != "-") {
    if (o.format.empty()) return sim::load_any_scenario(o.scenario);
    try {
      return sim::load_any_scenario_text(read_text_file(o.scenario), format(), o.scenario);
    } catch (const FileReadError& e) {
      throw sim::ScenarioError(o.scenario, 0, e.what());
    }
  }
  if (o.format.empty()) {
    throw sim::ScenarioError(kStdinName, 0, "give the format of a scenario on standard input: --format toml or --format json");
  }
  std::string text;
  std::string chunk(64 * 1024, '\0');
  while (std::cin.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || std::cin.gcount() > 0) {
    text.append(chunk.data(), static_cast<std::size_t>(std::cin.gcount()));
    if (text.size() > kMaxInputFileBytes) {
      throw sim::ScenarioError(kStdinName, 0,
                               "more than " + std::to_string(kMaxInputFileBytes >> 20U) + " MiB: not a scenario");
    }
  }
  if (std::cin.bad()) throw sim::ScenarioError(kStdinName, 0, "cannot read standard input");
  return sim::load_any_scenario_text(text, format(), kStdinName);
}

// A scenario with a CANLust bus (docs/scenarios.md, "A CANLust bus"): its own simulation, in
// simulated time, or with --realtime paced at absolute deadlines, its drives served on the
// scenario's `bus` for the user's master when it names one, with entries from --control between.
int run_canlust(const RunOptions& o, const sim::canlust::Scenario& scenario) {
  for (const auto& [flag, given] : {std::pair{"--trace", !o.trace_dir.empty()}, {"--vcd", !o.vcd_file.empty()},
                                    {"--plot", !o.plot_file.empty()}, {"--threads", o.threads != 1},
                                    {"--rt-priority", o.rt_priority != 0}, {"--lustbus-pcap", !o.lustbus_pcap.empty()},
                                    {"--dfs1-pcap", !o.dfs1_pcap.empty()}, {"--stats-every", !o.stats_every.empty()}}) {
    if (given) {
      std::cerr << o.scenario << ": " << flag
                << " is for INTERBUS scenarios; a CANLust run has --json, --pcap, --realtime and --control\n";
      return kExitBadInput;
    }
  }
  if (!scenario.bus.empty() && !o.realtime) {
    std::cerr << o.scenario << ":" << scenario.bus_line << ": bus = \"" << scenario.bus
              << "\" serves the drives to your own master in real time: run it with --realtime\n";
    return kExitBadInput;
  }
  if (!o.control.empty() && !o.realtime) {
    std::cerr << "--control " << o.control
              << " needs --realtime: without it the simulation runs faster than real time, so a live entry would "
                 "have no time to land in\n";
    return kExitBadInput;
  }
  std::unique_ptr<control::Channel> control;
  if (!o.control.empty()) {
    std::string error;
    control = control::Channel::open(o.control, error);
    if (!control) {
      std::cerr << "--control " << o.control << ": " << error << "\n";
      return kExitBadInput;
    }
  }
  // The capture goes under the rules of every output (output_files.hpp): a temporary renamed into
  // place when the run has written it, never a user's file replaced or removed.
  OutputFiles outputs;
  std::string error;
  std::string pcap_path;
  if (!o.pcap_file.empty()) {
    if (o.pcap_file == "-" && ::isatty(STDOUT_FILENO) != 0) {
      std::cerr << "--pcap -: standard output is a terminal; pipe the capture on (| tshark -r -) or give a file\n";
      return kExitBadInput;
    }
    const auto path = outputs.reserve(o.pcap_file, error);
    if (!path) {
      std::cerr << error << "\n";
      return kExitBadInput;
    }
    pcap_path = path->string();
  }
  sim::canlust::Report report;
  try {
    if (o.realtime) {
      StopSignals signals;
      sim::canlust::RealtimeOptions rt;
      std::ostream& ready = outputs.uses_stdout() ? std::cerr : std::cout;
      rt.ready = [&ready](const std::string& line) { ready << line << "\n" << std::flush; };
      rt.stop = [&signals]() { return signals.raised(); };
      if (control) {
        rt.each_step = [&](Time, std::vector<sim::canlust::Entry>& out) {
          control->poll(
              [&](const control::Origin& from, std::string_view text) {
                try {
                  out.push_back(sim::canlust::parse_control_entry(scenario, std::string(text), from.line,
                                                                  std::string(from.name)));
                } catch (const sim::ScenarioError& e) {
                  std::cerr << e.what() << "\n";  // "control:LINE: what is wrong"; the run goes on
                }
              },
              [](const control::Origin& from, std::string_view what) { std::cerr << from << ": " << what << "\n"; },
              [](std::string_view notice) { std::cerr << notice << "\n"; });
        };
      }
      report = sim::canlust::run_realtime(scenario, rt, pcap_path);
    } else {
      report = sim::canlust::run(scenario, pcap_path);
    }
  } catch (const std::exception& e) {
    std::string what = e.what();
    // Name the capture as the user gave it, not its temporary.
    if (!pcap_path.empty() && what.rfind(pcap_path, 0) == 0) what = o.pcap_file + what.substr(pcap_path.size());
    std::cerr << (o.scenario.empty() ? std::string() : o.scenario + ": ") << what << "\n";
    return kExitBadInput;
  }
  if (!outputs.commit(error)) {
    std::cerr << error << "\n";
    return kExitBadInput;
  }
  // With the capture on standard output (`-`), the report goes to standard error.
  std::ostream& say = outputs.uses_stdout() ? std::cerr : std::cout;
  say << (o.json ? sim::canlust::format_json(report) : sim::canlust::format_text(report));
  if (!o.json && !o.pcap_file.empty()) {
    say << "capture written: " << (o.pcap_file == "-" ? std::string("standard output") : o.pcap_file) << "\n";
  }
  return kExitOk;
}

}  // namespace

int run(const RunOptions& o) {
  if (o.rt_priority != 0 && !o.realtime) {
    std::cerr << "--rt-priority " << o.rt_priority << " needs --realtime\n";
    return kExitBadInput;
  }
  StatsEvery stats;
  if (!o.stats_every.empty()) {
    stats = parse_stats_every(o.stats_every);
    if (stats.error.empty() && !o.realtime) stats.error = "--stats-every " + o.stats_every + " needs --realtime";
    if (!stats.error.empty()) {
      std::cerr << stats.error << "\n";
      return kExitBadInput;
    }
  }
  // The file is read once; its [bus] says which bus's simulation runs it.
  sim::Scenario scenario;
  try {
    if (o.scenario.empty()) {
      scenario = sim::default_scenario();
    } else {
      sim::AnyScenario any = load_run_scenario(o);
      if (const auto* canlust = std::get_if<sim::canlust::Scenario>(&any)) return run_canlust(o, *canlust);
      scenario = std::move(std::get<sim::Scenario>(any));
    }
  } catch (const sim::ScenarioError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
  // The test bench's lines (docs/testbench.md) are served while the scenario runs in real time:
  // faster than real time, a user's host on the port would see the drives' minutes pass in seconds.
  if (scenario.serves_lines() && !o.realtime) {
    std::cerr << o.scenario << ": [" << (scenario.lustbus ? "lustbus" : "dfs1")
              << "] serves a line to your own host software, which talks in real time: run it with --realtime\n";
    return kExitBadInput;
  }
  // A live entry needs wall-clock time to land in: without --realtime the simulation runs as
  // fast as it can and is over before anyone could type.
  std::unique_ptr<control::Channel> control;
  if (!o.control.empty()) {
    if (!o.realtime) {
      std::cerr << "--control " << o.control
                << " needs --realtime: without it the simulation runs faster than real time, so a live entry would "
                   "have no time to land in\n";
      return kExitBadInput;
    }
    std::string error;
    control = control::Channel::open(o.control, error);
    if (!control) {
      std::cerr << "--control " << o.control << ": " << error << "\n";
      return kExitBadInput;
    }
  }
  // A plot that cannot be drawn fails before the run.
  std::optional<sim::PlotFormat> format;
  if (!o.plot_file.empty()) {
    format = plot_format(o.plot_file);
    if (!format) {
      std::cerr << o.plot_file << ": --plot draws FILE.svg or FILE.png; say which by the extension\n";
      return kExitBadInput;
    }
    if (!gnuplot_available()) {
      std::cerr << o.plot_file << ": --plot needs gnuplot, which is not installed (Debian package gnuplot-nox); "
                   "nothing was run or written\n";
      return kExitBadInput;
    }
  }
  std::unique_ptr<sim::Simulator> simulator;
  try {
    simulator = std::make_unique<sim::Simulator>(scenario);
  } catch (const std::invalid_argument& e) {
    std::cerr << (o.scenario.empty() ? std::string("default scenario") : o.scenario) << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  // The bench's faces share the simulator's drive cores; its lines open before anything is written.
  std::unique_ptr<Bench> bench;
  if (scenario.serves_lines()) {
    try {
      bench = std::make_unique<Bench>(*simulator, scenario, o.scenario);
    } catch (const std::exception& e) {
      std::cerr << e.what() << "\n";
      return kExitBadInput;
    }
  }
  // Every output is written under a temporary name and renamed into place only when all of them
  // have been written; a path that cannot be created fails before the run.
  OutputFiles outputs;
  std::string error;
  // `--trace -`: the one trace on standard output, for a run that records one; a trace is a
  // device's (docs/replay.md, "Recordings"), so a scenario of several devices has several.
  const bool trace_stdout = o.trace_dir == "-";
  std::ostream* trace_stream = nullptr;
  if (trace_stdout) {
    if (scenario.devices.size() != 1) {
      std::cerr << "--trace -: the scenario has " << scenario.devices.size()
                << " devices and each records its own trace, but standard output holds one; give a directory "
                   "(--trace DIR)\n";
      return kExitBadInput;
    }
    trace_stream = outputs.open("-", error);  // standard output, taken now so no other output takes it
    if (trace_stream == nullptr) {
      std::cerr << error << "\n";
      return kExitBadInput;
    }
  } else if (!o.trace_dir.empty() && !outputs.make_directory(o.trace_dir, error)) {
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
    // $date: when the run was made, as VCD writers put it (IEEE 1364-2005, 18.2.3.1), in UTC.
    const std::time_t started = std::time(nullptr);
    std::tm utc{};
    char date[40] = "";
    if (gmtime_r(&started, &utc) != nullptr) std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", &utc);
    vcd = std::make_unique<sim::VcdRecorder>(*simulator, *vcd_stream, date);
    simulator->add_observer(vcd.get());
  }
  // One wall-clock start for every capture of the run: they merge into one timeline (mergecap).
  const Time epoch = sim::wall_clock_epoch();
  std::unique_ptr<sim::PcapRecorder> pcap;
  if (!o.pcap_file.empty()) {
    if (o.pcap_file == "-" && ::isatty(STDOUT_FILENO) != 0) {
      std::cerr << "--pcap -: standard output is a terminal; pipe the capture on (| tshark -r -) or give a file\n";
      return kExitBadInput;
    }
    std::ostream* pcap_stream = outputs.open(o.pcap_file, error);
    if (pcap_stream == nullptr) {
      std::cerr << error << "\n";
      return kExitBadInput;
    }
    try {
      pcap = std::make_unique<sim::PcapRecorder>(*simulator, scenario, *pcap_stream, epoch);
    } catch (const std::exception& e) {
      std::cerr << o.pcap_file << ": " << e.what() << "\n";
      return kExitBadInput;
    }
    simulator->add_observer(pcap.get());
  }
  // The test bench's served lines as captures (docs/pcap.md, "Serial lines"). Their streams are
  // the outputs': on every way out they are dropped before the outputs go.
  struct DropLineCaptures {
    Bench* bench;
    ~DropLineCaptures() {
      if (bench != nullptr) bench->drop_captures();
    }
  } drop_line_captures{bench.get()};
  std::vector<std::pair<std::string_view, std::string>> line_captures;
  for (const auto& [key, file] : {std::pair<std::string_view, std::string>{"lustbus", o.lustbus_pcap}, {"dfs1", o.dfs1_pcap}}) {
    if (file.empty()) continue;
    if (!bench || !bench->serves_line(key)) {
      std::cerr << "--" << key << "-pcap " << file << ": the scenario serves no [" << key
                << "] line to capture (docs/testbench.md)\n";
      return kExitBadInput;
    }
    std::ostream* stream = outputs.open(file, error);
    if (stream == nullptr) {
      std::cerr << error << "\n";
      return kExitBadInput;
    }
    try {
      bench->capture(key, *stream, epoch);
    } catch (const std::exception& e) {
      std::cerr << file << ": " << e.what() << "\n";
      return kExitBadInput;
    }
    line_captures.emplace_back(key, file);
  }
  std::unique_ptr<sim::PlotRecorder> plot;
  std::ostream* plot_stream = nullptr;
  if (format) {
    plot_stream = outputs.open(o.plot_file, error);
    if (plot_stream == nullptr) {
      std::cerr << error << "\n";
      return kExitBadInput;
    }
    plot = std::make_unique<sim::PlotRecorder>(*simulator, scenario.duration);
    simulator->add_observer(plot.get());
  }

  sim::SimOptions options;
  options.record_traces = !o.trace_dir.empty();
  options.threads = o.threads;
  // A long run shows its progress on standard error (progress.hpp): in place on a terminal, a
  // line every few seconds elsewhere, nothing with -q.
  Progress progress(o.progress, "ibs run");
  if (progress.enabled()) {
    options.progress = [&progress](Time now, Duration total) {
      progress.report(fmt::format("simulated {:.1f} s of {:.1f} s ({:.0f} %)", to_ms(now) / 1000.0,
                                  to_ms(total) / 1000.0, 100.0 * to_ms(now) / to_ms(total)));
    };
  }
  // SIGINT and SIGTERM end the run between two slices of simulated time; then nothing is written
  // (the outputs' temporaries and any directory made for them go) and the command says so.
  StopSignals signals;
  bool interrupted = false;
  if (o.realtime) {
    sim::RealtimeOptions rt{o.rt_priority, [&signals, &interrupted] { return interrupted = signals.raised(); }, {}};
    if (bench) {
      // The words a script waits for, before the first cycle: one line per served line, flushed.
      std::ostream& ready = outputs.uses_stdout() ? std::cerr : std::cout;
      for (const std::string& line : bench->ready_lines()) ready << line << "\n";
      ready << std::flush;
      for (const std::string& note : bench->notes()) std::cerr << "ibs run: " << note << "\n";
    }
    // One hook, on the simulator's thread: the bench's lines turn, then the control lines land.
    std::function<void(Time)> control_turn;
    if (control) control_turn = control_each_cycle(*control, *simulator, scenario, bench.get());
    if (bench || control) {
      rt.each_cycle = [&bench, &control_turn](Time now) {
        if (bench) bench->turn(now);
        if (control_turn) control_turn(now);
      };
    }
    if (stats.every > Duration{0}) {
      rt.interval = stats.every;
      rt.each_interval = [&simulator, &control, &bench](const sim::RealtimeInterval& iv) {
        write_stats_line(iv, *simulator, control.get(), bench.get());
      };
    }
    sim::run_realtime(*simulator, rt, options);
  } else {
    for (Time t = Time{0} + kRunSlice; simulator->run_until(t, options); t += kRunSlice) {
      if (signals.raised()) {
        interrupted = true;
        break;
      }
    }
  }
  progress.finish();
  if (interrupted) {
    std::cerr << "ibs run: interrupted by a signal after " << to_ms(simulator->now()) / 1000.0 << " s of "
              << to_ms(scenario.duration) / 1000.0 << " s simulated; no output was written\n";
    return kExitInterrupted;
  }
  if (vcd) {
    try {
      vcd->finish(scenario.duration);
    } catch (const std::exception& e) {
      std::cerr << o.vcd_file << ": " << e.what() << "\n";
      return kExitBadInput;
    }
    // The state names for gtkwave's translate filter and the save file that opens the dump ready
    // to read (docs/vcd.md), beside the VCD file; the save file names both by absolute path.
    // A dump on standard output has no place beside it: it goes alone.
    const std::string filter_file = o.vcd_file + ".states.txt";
    const std::string save_file = o.vcd_file + ".gtkw";
    const auto absolute = [](const std::string& p) { return std::filesystem::absolute(p).lexically_normal().string(); };
    if (o.vcd_file != "-" &&
        (!outputs.write(filter_file, vcd->state_filter(), error) ||
         !outputs.write(save_file,
                        vcd->save_file(absolute(o.vcd_file), absolute(filter_file), absolute(save_file),
                                       scenario.duration),
                        error))) {
      std::cerr << error << "\n";
      return kExitBadInput;
    }
  }
  if (pcap) {
    try {
      pcap->finish();
    } catch (const std::exception& e) {
      std::cerr << o.pcap_file << ": " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  std::vector<std::uint64_t> line_packets;
  for (const auto& [key, file] : line_captures) {
    try {
      line_packets.push_back(bench->finish_capture(key));
    } catch (const std::exception& e) {
      std::cerr << file << ": " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  if (plot) {
    plot->finish(scenario.duration);
    if (!run_gnuplot(plot->script(simulator->summary(), *format), *plot_stream, error)) {
      std::cerr << o.plot_file << ": " << error << "\n";
      return kExitBadInput;
    }
  }
  std::vector<std::string> written;
  if (trace_stdout) {
    const auto traces = simulator->traces();
    if (traces.size() != 1) {
      // A power cycle ends a recording; the next starts once the device has initialised again.
      std::cerr << "--trace -: the run recorded " << traces.size() << " traces of " << scenario.devices.front().name
                << (traces.empty() ? " (it never showed a freshly started device's words)"
                                   : " (each power cycle starts a new one)")
                << ", but standard output holds one; give a directory (--trace DIR); nothing was written\n";
      return kExitBadInput;
    }
    *trace_stream << trace::write(traces.front().trace);
    written.push_back("standard output");
  } else if (!o.trace_dir.empty()) {
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
  // With an output on standard output (`-`), the summary goes to standard error.
  std::ostream& say = outputs.uses_stdout() ? std::cerr : std::cout;
  const auto written_to = [](const std::string& f) { return f == "-" ? std::string("standard output") : f; };
  const sim::Summary& summary = simulator->summary();
  if (o.json && bench) {
    // The bench's part joins the summary's object (docs/testbench.md), printed as the summary is.
    nlohmann::json json = nlohmann::json::parse(sim::format_json(summary));
    json["bench"] = nlohmann::json::parse(format_bench_json(bench->report()));
    say << json.dump(2) << "\n";
  } else {
    say << (o.json ? sim::format_json(summary) : sim::format_text(summary));
  }
  if (!o.json && bench) say << format_bench_text(bench->report());
  if (!o.json) {
    for (const auto& path : written) say << "trace written: " << path << "\n";
    if (vcd && o.vcd_file == "-") {
      say << "VCD written: standard output\n";
    } else if (vcd) {
      say << "VCD written: " << o.vcd_file << " (open it with: gtkwave " << o.vcd_file
          << ".gtkw; state names for gtkwave: " << o.vcd_file << ".states.txt)\n";
    }
    if (pcap) say << "capture written: " << written_to(o.pcap_file) << " (" << pcap->packets() << " packets)\n";
    for (std::size_t i = 0; i < line_captures.size(); ++i) {
      say << line_captures[i].first << " capture written: " << written_to(line_captures[i].second) << " ("
          << line_packets[i] << " packets)\n";
    }
    if (plot) say << "plot written: " << o.plot_file << "\n";
  }
  return kExitOk;
}

}  // namespace ibs::cli
