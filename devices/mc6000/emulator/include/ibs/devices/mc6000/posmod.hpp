// The PosMOD1 positioning option of the MC6000 behind LUSTBUS CODE 49999 (LUSTBUS manual 11.6). The
// seed gives the frame, the status byte (11.6.3) and four example exchanges (11.6.4); "the user
// data is in the command description of the user handbook", which is not among the seeds. So the
// command set below is ours, small and documented (docs/lustbus.md, "PosMOD1", LB-D22):
//
//   data telegrams (status bit 0 = 0; 11.6.4 sends 38H / 3CH, bit 3 set: accepted either way)
//     GOA<pos>[V<vel>]   go to the absolute position <pos> (increments) at <vel> increments/s
//     GOR<dist>[V<vel>]  go relative
//     ST                 stop where the axis is
//     HOME               the current position becomes 0; the axis is referenced
//     %P<n> [comment]    multiblock (bit 2): begin the transfer of program <n> (0..99)
//     <line>             multiblock: one program line (11.6.4: "N10 GO 0")
//     END                single block: end of the transfer; the program is stored
//   request telegrams (bit 0 = 1), answered by the following ENQUIRY 49999
//     ?                  status: "G<enabled><moving>H<referenced><error> P<position>"
//                        (11.6.4: "G10H10 ..." = enabled, standing, referenced, no error)
//     %RDP<n>            program <n>: "%P<n> ..." and its lines as multiblock answers (34H),
//                        then "END" (30H)
//     %RDF               the error of the last NAK: "F<nn> <text>"; reading clears it
//
// A NAK (SELECT or ENQUIRY) records its cause for %RDF. Allocates in its constructor only.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "ibs/base/time.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::devices::mc6000 {

enum class PosmodError : std::uint8_t {
  none = 0,
  syntax = 1,          // unknown command or malformed number
  status_byte = 2,     // the status byte breaks 11.6.3 (bits 1, 6, 7 set, 4 or 5 clear)
  no_program = 3,      // %RDP of a program not stored
  no_request = 4,      // ENQUIRY without a pending request
  memory_full = 5,     // no room for another program or line
  sequence = 6,        // a block out of the transfer's sequence
  not_enabled = 7,     // a motion command while the servo's power stage is off
};
std::string_view to_string(PosmodError e);

struct PosmodConfig {
  std::size_t programs = 16;          // program slots
  std::size_t lines_per_program = 64;
  std::int64_t default_velocity = 1000;  // increments/s when GOA/GOR has no V
};

class PosMod {
 public:
  explicit PosMod(const PosmodConfig& config = {});

  // 11.6.1: the user data of a SELECT 49999 (status byte + data). true: ACK; false: NAK.
  bool select(std::string_view user_data, Time now);
  // 11.6.2: the answer to an ENQUIRY 49999 (status byte + data), or nullopt: NAK.
  std::optional<lustbus::Value> enquiry(Time now);
  // Time passes: the axis moves while `enabled` (the servo's power stage).
  void advance(Time now, bool enabled);
  // A new start of the servo: motion stops, requests and transfers are dropped; programs stay.
  void restart(Time now);

  [[nodiscard]] std::int64_t position() const { return position_; }
  [[nodiscard]] bool moving() const { return moving_; }
  [[nodiscard]] bool referenced() const { return referenced_; }
  [[nodiscard]] PosmodError error() const { return error_; }
  [[nodiscard]] std::size_t stored_programs() const;

 private:
  enum class Pending : std::uint8_t { none, status, program, error };
  struct Program {
    int number = -1;  // -1: free
    lustbus::Value header{};
    std::vector<lustbus::Value> lines;  // reserved at construction
    std::size_t count = 0;
  };
  bool fail(PosmodError e);
  bool data(std::string_view d, bool multiblock, Time now);
  bool request(std::string_view d);
  Program* find(int number);

  PosmodConfig config_;
  std::vector<Program> programs_;
  Program staging_;
  bool transferring_ = false;
  Pending pending_ = Pending::none;
  int read_program_ = -1;
  std::size_t read_line_ = 0;  // 0: the header next; 1..count: lines; count + 1: END
  PosmodError error_ = PosmodError::none;
  bool enabled_ = false;
  bool moving_ = false;
  bool referenced_ = false;
  std::int64_t position_ = 0;
  std::int64_t target_ = 0;
  std::int64_t velocity_ = 0;
  double carry_ = 0.0;  // fraction of an increment
  Time last_{};
};

}  // namespace ibs::devices::mc6000
