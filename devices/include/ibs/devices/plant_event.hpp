// The plant and fault events a drive takes from outside its buses (issue 24, item 4): a device
// fault with its cause, mains loss and return, a load torque, a digital input, a power cycle. One
// vocabulary for every face and tool: the simulator's timeline and control channel hand them to
// DeviceEmulator::apply_event, `ibs lustbus emulate --control` to LustbusEmulated::apply_event.
// What a drive kind takes (its error list, its inputs, whether it has a load) is in its
// descriptor's facts (DriveFacts::events); the checks here read those and name no drive.
// Configuration time: checking may allocate. Applying an event to a drive is cycle-path work.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace ibs::devices {

// One of the drive's own error numbers with the name its manual gives it.
struct ErrorCause {
  int number = 0;
  std::string_view name;  // "E-IBS"
};

// The events a drive kind takes and how its manuals name them.
struct EventFacts {
  // Error numbers a device fault may carry: min_error..max_error; the named ones among them.
  int min_error = 0;
  int max_error = -1;  // < min_error: the drive takes no cause
  std::span<const ErrorCause> errors{};
  std::string_view error_source;  // where the list comes from: "INTERBUS manual 4.1.3.3: 00H..0EH"
  // The digital inputs by the manual's names (none: the drive takes no `input`), and why not.
  std::span<const std::string_view> inputs{};
  std::string_view no_inputs;  // the refusal's reason when `inputs` is empty
  // The load torque's unit ("Nm"); empty: the drive takes no load, for `no_load`'s reason.
  std::string_view load_unit;
  std::string_view no_load;
  // A SMARTCARD read into the drive or written from it: the longest such operation in seconds
  // (0: the drive takes no card event, for `no_card`'s reason) and where its manual says so.
  // (Default member initializers: the wings' designated initializers may leave them out.)
  double card_max_s = 0.0;
  std::string_view card_source{};
  std::string_view no_card{};
  // An option card the drive detects at power-on, withdrawn and inserted again: the card as its
  // manual names it (empty: the drive takes no option event, for `no_option`'s reason) and where
  // the manual says what its withdrawal does.
  std::string_view option_card{};
  std::string_view option_source{};
  std::string_view no_option{};
};

struct PlantEvent {
  enum class Kind : std::uint8_t {
    fault,        // a device fault present (cause) ...
    fault_clear,  // ... and its cause gone
    power_cycle,  // switched off and on
    mains_off,    // mains lost
    mains_on,     // mains back
    load,         // load torque, `value` in EventFacts::load_unit
    input,        // digital input `input` (index into EventFacts::inputs) at `level`
    card_read,    // a SMARTCARD is read into the drive for `value` seconds ...
    card_write,   // ... or written from it (EventFacts::card_max_s)
    option_withdrawn,  // the option card (EventFacts::option_card) pulled out ...
    option_inserted,   // ... and put in; the drive detects either at its next power-on
  };
  Kind kind = Kind::fault;
  std::optional<int> cause;  // fault: the error number (nullopt: a generic external fault)
  double value = 0.0;        // load; card_read / card_write: how long, in seconds
  std::size_t input = 0;     // input
  bool level = false;        // input: true = high
};

// A cause as a file or a control line writes it, the number ("12") or the manual's name
// ("E-IBS"), checked against the kind's list: the number, or what is wrong ("... is not an error
// of a VF1000 (...)"). `title` names the drive in the message.
struct CauseCheck {
  std::optional<int> number;
  std::string error;
};
CauseCheck check_cause(const EventFacts& facts, std::string_view title, std::string_view text);
// The error's text for reports: "12 (E-IBS)" or "7".
std::string cause_text(const EventFacts& facts, int number);
// The input's index by its name (as the manual spells it, case-sensitive), or nullopt.
std::optional<std::size_t> find_input(const EventFacts& facts, std::string_view name);
// The names for a message: "IS00 or IS01".
std::string input_names(const EventFacts& facts);

}  // namespace ibs::devices
