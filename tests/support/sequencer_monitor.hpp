// A monitor of the master sequencer's safety promises (docs/drivecom.md, "Master side"), written
// from the promises alone, not from the sequencer's code: BLOCK POWER with bit 7 low after a
// failure, SHUTDOWN never skipped, no POWER-ON/ENABLE out of FAULT without a reset edge, never a
// reset the request did not cover, stop requests in the next cycle. Told what the user asked for,
// it checks each control word the sequencer sent against the status word it answered.
// Used by tests/drivecom/sequencer_safety_test.cpp and fuzz/drivecom_fuzz.cpp.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "ibs/drivecom/control_word.hpp"
#include "ibs/drivecom/sequencer.hpp"
#include "ibs/drivecom/status_word.hpp"

namespace ibs::drivecom::test_support {

inline bool is_fault(State s) { return s == State::fault || s == State::fault_response_active; }

// What the user asked for, and what the status words showed; checks each word the sequencer sent.
class Monitor {
 public:
  enum class Ask : std::uint8_t { none, target, emergency_stop, block_power };

  void on_request(Target t) {
    ask_ = Ask::target;
    target_ = t;
    covered_ = !known_ || is_fault(*known_);
    target_seen_ = false;
    up_seen_ = false;
    reset_sent_ = false;
    must_block_ = false;
  }
  void on_emergency_stop() { ask_ = Ask::emergency_stop; must_block_ = false; }
  void on_block_power() { ask_ = Ask::block_power; must_block_ = false; }
  void on_restart() {
    ask_ = Ask::none;
    known_.reset();
    edge_out_ = false;
    must_block_ = false;
    prev_word_ = 0;
  }

  // The sequencer answered `status` with `word`; returns what is wrong ("" if nothing).
  std::string check(Word status, Word word, const Report& report) {
    const std::optional<State> st = decode_state(status);
    if (ask_ == Ask::target && st) {
      if (is_fault(*st) && !covered_) must_block_ = true;  // a fault nobody asked to reset
      if (!is_fault(*st)) covered_ = false;
      if (target_seen_ && *st != target_state(target_)) must_block_ = true;  // left the target
      if (*st == target_state(target_)) target_seen_ = true;
      // NOT READY after any other state since the request: the drive restarted -- unless the
      // request's own reset edge, sent in FAULT, made it boot (the VF1000's software reset, seed
      // 001 5.2.1); then it comes up again as after power-on.
      const bool booting = known_ == State::fault && reset_sent_;
      if (*st == State::not_ready && up_seen_ && !booting) must_block_ = true;
      if (*st == State::not_ready) up_seen_ = false;
      if (*st != State::not_ready) up_seen_ = true;
      if (*st != State::fault) reset_sent_ = false;
      // Out of a fault state into a healthy one with no reset edge since the drive showed FAULT
      // (sent by this request or an earlier one): FAULT is left by transition 15 alone (5.1.2),
      // so the drive restarted, its NOT READY unseen (errata DC-D1).
      if (*st != State::not_ready && !is_fault(*st) && known_ && is_fault(*known_) && !edge_out_) must_block_ = true;
    }
    if (st && *st != State::fault) edge_out_ = false;
    if (st) known_ = st;
    std::string why = judge(word, report);
    if (ask_ == Ask::target && known_ == State::fault && covered_ && (word & 0x0080U) != 0 &&
        (prev_word_ & 0x0080U) == 0) {
      reset_sent_ = true;
    }
    if (known_ == State::fault && (word & 0x0080U) != 0 && (prev_word_ & 0x0080U) == 0) edge_out_ = true;
    prev_word_ = word;
    return why;
  }

 private:
  std::string judge(Word word, const Report& report) const {
    const Command c = decode_command(word);
    const bool bit7 = (word & 0x0080U) != 0;
    const bool rising = bit7 && (prev_word_ & 0x0080U) == 0;
    if ((word & cw::kReservedMask) != 0) return "reserved bits 8-10 set";
    if (report.phase == Phase::failed || must_block_) {
      if (c != Command::block_power || bit7) return "not BLOCK POWER with bit 7 low after a failure";
      if (must_block_ && report.phase != Phase::failed) return "the failure is not reported";
      return "";
    }
    switch (ask_) {
      case Ask::none:
        if (c != Command::block_power || bit7) return "not BLOCK POWER without a request";
        return "";
      case Ask::emergency_stop:
        if (c != Command::emergency_stop || bit7) return "EMERGENCY STOP requested but not sent";
        return "";
      case Ask::block_power:
        if (c != Command::block_power || bit7) return "BLOCK POWER requested but not sent";
        return "";
      case Ask::target: break;
    }
    if (c == Command::enable && target_ != Target::enabled) return "ENABLE that nobody asked for";
    if (c == Command::disable && target_ != Target::on && target_ != Target::enabled) {
      return "POWER-ON that nobody asked for";
    }
    if ((c == Command::enable || c == Command::disable) &&
        !(known_ == State::ready || known_ == State::on || known_ == State::enabled)) {
      return "POWER-ON while the drive was last seen in " +
             (known_ ? std::string(to_string(*known_)) : std::string("no state")) + " (SHUTDOWN skipped)";
    }
    if (rising && !(covered_ && known_ == State::fault)) return "a reset edge the request did not cover";
    return "";
  }

  Ask ask_ = Ask::none;
  Target target_ = Target::start_up_inhibit;
  std::optional<State> known_;
  bool covered_ = false;
  bool target_seen_ = false;
  bool up_seen_ = false;
  bool reset_sent_ = false;  // the request's reset edge was sent while the drive showed FAULT
  bool edge_out_ = false;    // a reset edge (any request's) went out since the drive showed FAULT
  bool must_block_ = false;
  Word prev_word_ = 0;
};

}  // namespace ibs::drivecom::test_support
