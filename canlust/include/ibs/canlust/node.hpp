// A drive's CANLust node (CANLust manual 5.2 CAN system states, 5.5 identifiers; 4.3.1 574-CAWDG and
// 575-CASCY): the system-state machine, the stored command of System Stop, the cyclic logon and
// status telegrams, the control-telegram watchdog, and the parameter channel's drive side. It
// serves a drive through two interfaces and knows no concrete drive:
//   DriveProcess     - executes control telegrams, gives the status telegram, reacts to errors
//   ParameterAccess  - the drive's parameters (parameter_channel.hpp)
//
//   node.power_on(now);
//   node.receive(frame, now);   // every frame from the bus
//   node.step(now);             // cyclic telegrams, watchdog, delayed parameter replies
//   while (auto f = node.take_frame()) bus.send(*f);   // or take_frame(CanFrame&)
//   node.next_deadline();       // when step() next has something to do
// All of them allocate nothing and throw nothing after construction.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "ibs/canlust/errors.hpp"
#include "ibs/canlust/frame.hpp"
#include "ibs/canlust/identifiers.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/canlust/telegrams.hpp"
#include "ibs/base/bounded_queue.hpp"
#include "ibs/base/time.hpp"

namespace ibs::canlust {

// 5.2 "CAN system states".
enum class SystemState : std::uint8_t {
  logon,  // System Logon: System Stop after power-on, logon telegram every 100 ms
  stop,   // System Stop after a System Start: commands stored, not executed
  start,  // System Start: commands executed, status cyclic, watchdog armed
};
std::string_view to_string(SystemState s);

enum class SystemEvent : std::uint8_t { start_broadcast, stop_broadcast };

// One row of the transition table (5.2, 5.5.4).
struct SystemTransition {
  SystemState from;
  SystemEvent event;
  SystemState to;
  bool execute_stored;  // run the command stored during Stop (5.2 "System Start")
  std::string_view source;
};
inline constexpr std::array<SystemTransition, 6> kSystemTransitions = {{
    {SystemState::logon, SystemEvent::start_broadcast, SystemState::start, true,
     "5.2 System Start: stored commands executed, all drives together (1 ms jitter)"},
    {SystemState::logon, SystemEvent::stop_broadcast, SystemState::logon, false,
     "5.2: already in System Stop; keeps logging on (decision D14)"},
    {SystemState::start, SystemEvent::stop_broadcast, SystemState::stop, false,
     "5.2 System Stop: commands are only stored"},
    {SystemState::start, SystemEvent::start_broadcast, SystemState::start, false,
     "5.2: already started; nothing stored to execute (decision D14)"},
    {SystemState::stop, SystemEvent::start_broadcast, SystemState::start, true,
     "5.2 System Start: stored commands executed"},
    {SystemState::stop, SystemEvent::stop_broadcast, SystemState::stop, false,
     "5.2: already stopped"},
}};
constexpr const SystemTransition& system_transition(SystemState from, SystemEvent e) {
  for (const auto& t : kSystemTransitions) {
    if (t.from == from && t.event == e) return t;
  }
  return kSystemTransitions[0];  // unreachable: the table is complete (pinned by a test)
}

// What the watchdog hands the drive: the reaction set for it and the error telegram the node
// proposes to send (6.1, 6.2).
struct WatchdogEvent {
  ErrorReaction reaction = ErrorReaction::disable_power;
  ErrorTelegram error{};
  Time last_control{};  // the last control telegram (or the System Start) before it ran out
  Time now{};
};

// What a drive implements for the node (floor 3 wings). Called on the frame path: must not
// allocate or throw.
class DriveProcess {
 public:
  virtual ~DriveProcess() = default;
  // 5.2: a control telegram to act on now: in System Start at once, or the one stored during
  // System Stop at the System Start.
  virtual void execute(const ControlTelegram& t, Time now) = 0;
  // 5.5.6: the status telegram to send now (sent every 575-CASCY ms in System Start and Stop).
  virtual StatusTelegram status(Time now) = 0;
  // 574-CAWDG ran out. The drive applies `e.reaction` (its programmable error reaction) and
  // returns the error telegram to send, or nullopt for none. Default: send the proposal.
  virtual std::optional<ErrorTelegram> watchdog_expired(const WatchdogEvent& e) { return e.error; }
  // System state changes (the EasyDrive status bit 8 "CAN status", 5.4.1). Default: nothing.
  virtual void system_state_changed(SystemState s, Time now) {
    (void)s;
    (void)now;
  }
};

struct NodeConfig {
  Address address = 0;                      // 571-CLADR
  IdentifierMap ids{};
  ProcessLayout layout{};                   // from 492-CACNF
  Duration logon_period = 100ms;            // 5.2: every 100 ms
  Duration status_period = 80ms;            // 575-CASCY, 1..32000 ms, factory 80
  Duration watchdog = 0ms;                  // 574-CAWDG, 0..255 ms, 0 = off
  ErrorReaction watchdog_reaction = ErrorReaction::disable_power;
  // The error telegram proposed when the watchdog runs out: E-OP2 at location 172 (decision
  // D15: the seed does not say which location the bus watchdog reports).
  std::uint8_t watchdog_error_number = kErrorOp2;
  std::uint8_t watchdog_error_location = kLocationOp2_172;
  std::size_t outbox_capacity = 16;
};

struct NodeCounters {
  std::uint32_t logons = 0;
  std::uint32_t statuses = 0;
  std::uint32_t controls = 0;           // control telegrams received
  std::uint32_t stored = 0;             // of them, stored during System Stop
  std::uint32_t watchdog_trips = 0;
  std::uint32_t bad_frames = 0;         // own identifiers with a too-short DLC or RTR
  std::uint32_t dropped_frames = 0;     // outbox full
};

class Node {
 public:
  Node(const NodeConfig& config, DriveProcess& drive, ParameterAccess& parameters);

  // Power-on: System Logon, the first logon telegram at once.
  void power_on(Time now);
  void receive(const CanFrame& f, Time now);
  void step(Time now);
  // The next frame into `out`; false when there is none. Inline: asked until it has nothing
  // (issue 26: twice a parameter read at least; the frame is not carried out in an optional).
  bool take_frame(CanFrame& out) {
    if (outbox_.empty()) return false;
    out = outbox_.front();
    outbox_.pop();
    return true;
  }
  std::optional<CanFrame> take_frame() {
    CanFrame f;
    if (!take_frame(f)) return std::nullopt;
    return f;
  }
  [[nodiscard]] Time next_deadline() const;

  // An error of the drive (6.2): sends the error telegram (441 + address).
  void report_error(const ErrorTelegram& e, Time now);

  [[nodiscard]] SystemState state() const { return state_; }
  [[nodiscard]] bool powered() const { return powered_; }
  [[nodiscard]] std::optional<ControlTelegram> stored_command() const { return stored_; }
  [[nodiscard]] bool watchdog_tripped() const { return tripped_; }
  [[nodiscard]] const NodeConfig& config() const { return config_; }
  [[nodiscard]] const NodeCounters& counters() const { return counters_; }
  [[nodiscard]] const ParameterServer& parameter_server() const { return server_; }
  // 574-CAWDG and 575-CASCY may be written through the parameter channel: the wing calls these.
  void set_watchdog(Duration d, Time now);
  void set_status_period(Duration d);

 private:
  void push(const std::optional<CanFrame>& f);
  void push_frame(const CanFrame& f);
  // Inlined into receive and step (issue 26: one call fewer per reply).
  [[gnu::always_inline]] inline void push_reply(const ParameterTelegram& t);
  void apply(SystemEvent e, Time now);
  void send_status(Time now);

  NodeConfig config_;
  // config_.ids.own_id of this node's control and parameter request telegrams, -1 for none: the
  // frames receive() acts on besides the broadcast (issue 26: no classify for every frame).
  std::int32_t control_id_ = -1;
  std::int32_t request_id_ = -1;
  std::int32_t reply_id_ = -1;  // config_.ids.id of its parameter replies, -1 for none
  DriveProcess* drive_;
  ParameterServer server_;
  bool powered_ = false;
  SystemState state_ = SystemState::logon;
  std::optional<ControlTelegram> stored_;
  Time next_logon_ = Time::max();
  Time next_status_ = Time::max();
  Time last_control_{};
  bool tripped_ = false;
  BoundedQueue<CanFrame> outbox_;
  NodeCounters counters_{};
};

}  // namespace ibs::canlust
