#include "board.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "ibs/sim/realtime.hpp"

namespace ibs::ddi {

namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr ? std::string(v) : std::string();
}

// A board runs as long as it is open: a simulated time no run reaches.
constexpr Duration kForever = std::chrono::hours(24 * 365 * 100);

}  // namespace

BoardOptions options_from_environment() {
  BoardOptions o;
  const std::string mode = env("IBS_DDI_MODE");
  if (mode == "stepped") {
    o.mode = Mode::stepped;
  } else if (!mode.empty() && mode != "realtime") {
    throw std::invalid_argument("IBS_DDI_MODE = '" + mode + "': expected realtime or stepped");
  }
  o.scenario = env("IBS_DDI_SCENARIO");
  const std::string commands = env("IBS_DDI_MASTER_COMMANDS");
  if (commands == "ibs-master") {
    o.master_commands = MasterCommands::ibs_master;
  } else if (!commands.empty() && commands != "ignore") {
    throw std::invalid_argument("IBS_DDI_MASTER_COMMANDS = '" + commands + "': expected ignore or ibs-master");
  }
  const std::string prio = env("IBS_DDI_RT_PRIORITY");
  if (!prio.empty()) {
    char* end = nullptr;
    const long p = std::strtol(prio.c_str(), &end, 10);
    if (*end != '\0' || p < 0 || p > 99) {
      throw std::invalid_argument("IBS_DDI_RT_PRIORITY = '" + prio + "': expected 0..99");
    }
    o.rt_priority = static_cast<int>(p);
  }
  return o;
}

sim::Scenario board_scenario(const std::string& path, MasterCommands commands, std::string* note) {
  sim::Scenario s;
  if (path.empty()) {
    s = sim::default_scenario();
    s.timeline.clear();  // its commands are for ibs's master; the ring is what the board takes
  } else {
    s = sim::load_scenario(path);
  }
  // The board runs the ring's faults and the drives' events; what commands a master is the
  // application's. A master restart is the board's controller failing (SysFail) unless ibs's
  // master runs the file's master side, whose restart it is then.
  std::vector<sim::TimelineEntry> kept;
  std::vector<const sim::TimelineEntry*> left;
  for (const sim::TimelineEntry& e : s.timeline) {
    switch (e.action) {
      case sim::Action::fault_corrupt:
      case sim::Action::fault_power_cycle:
      case sim::Action::fault_device:
      case sim::Action::fault_lost:
      case sim::Action::mains:
      case sim::Action::load:
      case sim::Action::input:
      case sim::Action::smartcard:
      case sim::Action::option_card:
        kept.push_back(e);
        break;
      case sim::Action::master_restart:
        if (commands == MasterCommands::ibs_master) continue;
        kept.push_back(e);
        break;
      default:
        left.push_back(&e);
        break;
    }
  }
  if (!left.empty() && commands == MasterCommands::ignore && note != nullptr) {
    *note = path + ":" + std::to_string(left.front()->source_line) + ": " + std::to_string(left.size()) +
            " timeline entr" + (left.size() == 1 ? "y commands" : "ies command") +
            " a master (the first: '" + std::string(sim::to_string(left.front()->action)) +
            "'); the board runs the ring and its faults and ignores them: behind the DDI the application is the "
            "master (IBS_DDI_MASTER_COMMANDS=ibs-master leaves them to `ibs master --board` without this note)";
  }
  s.timeline = std::move(kept);
  s.duration = kForever;
  return s;
}

Board::Board(const BoardOptions& options) : options_(options) {
  std::string note;
  scenario_ = board_scenario(options.scenario, options.master_commands, &note);
  if (!note.empty()) std::fprintf(stderr, "ibs-ddi: %s\n", note.c_str());
  sim_ = std::make_unique<sim::Simulator>(scenario_);
  firmware_ = std::make_unique<Firmware>(*sim_, sim_->bus(), sim_->cycle_time());
  sim_->set_external_master(firmware_.get());
  if (options_.mode == Mode::realtime) thread_ = std::thread([this] { run_realtime(); });
}

Board::~Board() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void Board::step() {
  ++cycle_;
  sim::SimOptions o;
  o.measure_master_time = false;
  sim_->run_until(Time{0} + sim_->cycle_time() * static_cast<std::int64_t>(cycle_), o);
}

void Board::run_realtime() {
  if (options_.rt_priority > 0) {
    if (const std::string refused = sim::set_fifo_priority(options_.rt_priority); !refused.empty()) {
      std::fprintf(stderr, "ibs-ddi: %s\n", refused.c_str());
    }
  }
  const std::int64_t start = sim::monotonic_ns();
  const std::int64_t cycle_ns = sim_->cycle_time().count();
  while (!stop_) {
    sim::sleep_until_ns(start + cycle_ns * static_cast<std::int64_t>(cycle_ + 1));
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stop_) break;
    try {
      step();
    } catch (const std::exception& e) {
      // Nothing in a cycle throws; should it, the board fails as a board does: SysFail.
      std::fprintf(stderr, "ibs-ddi: the board's cycle failed: %s\n", e.what());
      firmware_->restart(sim_->now());
      return;
    }
  }
}

}  // namespace ibs::ddi
