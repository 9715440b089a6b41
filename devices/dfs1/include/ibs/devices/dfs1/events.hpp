// Plant and fault events of an emulated DFS-1 controller, the same from a scenario's timeline and
// from the live control channel (`ibs dfs1 emulate --control`, docs/dfs1.md, "Faults on demand"):
// a controller fault with its cause (the fault bits of status 81 that a host reads, by the names
// the seed gives them), mains loss and return, a digital input's level, the motor's load and a
// power cycle. Controller::apply(event, now) carries one out; to_string() of what it returns is
// the one line a program prints about it.
//
// The events and their application allocate nothing and throw nothing; parse_event() and
// to_string() are configuration-time work (they allocate).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibs/base/time.hpp"

namespace ibs::devices::dfs1 {

// The causes of a controller fault: the eight ST1 bits and ST2's "uP fault" (public notes,
// "Status (81)"; docs/dfs1.md, "Faults on demand").
enum class FaultCause : std::uint8_t {
  bus_not_charged,
  ioc,
  stall,
  i2t,
  heatsink_overtemp,
  commutation,
  overvolt,
  undervolt,
  micro_fault,
};

struct FaultCauseInfo {
  FaultCause cause;
  std::string_view seed_name;  // as the status list writes it: "Heatsink OT"
  std::string_view flag_name;  // as `ibs dfs1 status` prints the bit: "heatsink-overtemp"
  std::uint8_t st1_bit;        // 0 for the uP fault
  std::uint8_t st2_bit;        // kSt2MicroFault for the uP fault, else 0
};

inline constexpr std::size_t kFaultCauses = 9;
const std::array<FaultCauseInfo, kFaultCauses>& fault_causes();
const FaultCauseInfo& info(FaultCause cause);
// Either name, letters in any case; nullopt when it names no cause.
std::optional<FaultCause> find_fault_cause(std::string_view name);

// The largest load (% of the drive's rating) an event may set: the load % of status 81 is
// reported up to this (decision D18).
inline constexpr std::uint32_t kMaxLoadPercent = 200;

struct Event {
  enum class Kind : std::uint8_t { fault, power_cycle, mains, input, load };
  Kind kind = Kind::fault;
  FaultCause cause = FaultCause::ioc;  // fault
  Duration duration{};                 // fault: how long the cause lasts (0: it is gone at once)
  bool on = false;                     // mains: on; input: high (the terminal closed)
  std::uint8_t input = 0;              // input: 1..7 (1 is the E-stop)
  std::uint32_t load_percent = 0;      // load: 0..kMaxLoadPercent

  static Event fault(FaultCause c, Duration d = {}) { return {Kind::fault, c, d, false, 0, 0}; }
  static Event power_cycle() { return {Kind::power_cycle, FaultCause::ioc, {}, false, 0, 0}; }
  static Event mains(bool on) { return {Kind::mains, FaultCause::ioc, {}, on, 0, 0}; }
  static Event input_level(std::uint8_t channel, bool high) {
    return {Kind::input, FaultCause::ioc, {}, high, channel, 0};
  }
  static Event load(std::uint32_t percent) { return {Kind::load, FaultCause::ioc, {}, false, 0, percent}; }
};

// What Controller::apply() did: the event, when, and the status a host reads right after it.
struct EventReport {
  Time at{};
  Event event;
  std::uint8_t st2 = 0;
  std::uint8_t st1 = 0;
  std::uint32_t load_percent = 0;
  bool latched = false;  // a fault is latched now (it stays until reset, D16)
};

// One line, e.g. `fault IOC for 500 ms: latched until the E-stop input opens; status ST2 18H
// forward fault, ST1 40H IOC`.
std::string to_string(const EventReport& r);
// The event alone: `fault IOC for 500 ms`, `mains off`, `input 3 high`, `load 40 %`, `power cycle`.
std::string to_string(const Event& e);

// A control line's keys and values, as the JSON of the channel gives them (the decoding of JSON
// is the program's; this wing takes strings and numbers).
struct ControlValue {
  enum class Type : std::uint8_t { string, number, other };
  Type type = Type::other;
  std::string text;   // string: the value; other: what it is ("a boolean", "an array", ...)
  double number = 0;  // number
  static ControlValue string(std::string s) { return {Type::string, std::move(s), 0}; }
  static ControlValue of_number(double v) { return {Type::number, {}, v}; }
  static ControlValue other(std::string what) { return {Type::other, std::move(what), 0}; }
};
using ControlFields = std::vector<std::pair<std::string, ControlValue>>;

struct ControlEvent {
  std::optional<std::uint8_t> uid;  // `device`; nullopt: the only controller served
  Event event;
};

// The keys: `device` (a UID 1..255, or "dfs1@UID"), `fault` ("device" with `cause` and optional
// `duration`, or "power-cycle"), `mains` ("off", "on"), `input` (1..7, "DI1".."DI7" or "E-stop")
// with `level` ("high", "low"), `load` (0..200, % of the rating). One event per line. Either the
// event or `error`, which says which key and value is wrong and what is allowed.
struct ParsedControl {
  std::optional<ControlEvent> event;
  std::string error;
};
ParsedControl parse_event(const ControlFields& fields);

}  // namespace ibs::devices::dfs1
