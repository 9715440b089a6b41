// The bus seam (bus.hpp) over an INTERBUS controller board, through the calls of Phoenix
// Contact's Device Driver Interface only (ibs/ddi.h, docs/board.md): what the master's cycle
// loop runs on a real board, and on ibs's virtual one (libibs-ddi), unchanged.
//
// Per exchange, one consistent access (DDI_DTI_ReadWriteData, word consistency) writes the
// process data the drivers wrote and reads what the devices sent; the diagnostic status register
// (GetIBSDiagnostic) gives the cycle's validity; the devices the board names with a peripheral
// fault (its parameter register, Get_Diag_Info) get a module error; and the mailbox carries the
// PCP devices' parameter messages (pcp::MailboxClient, one per PCP device: CR 2, 3, ... in ring
// order) and the diagnostic services. The board's image holds process data only: the PCP areas of
// the master's image are not carried (the channel is the board's firmware's).
//
// Cycle path: exchange() allocates nothing, throws nothing, takes no lock and reads no clock
// (`now` is the caller's); what the board's library does inside its calls is the board's. Built
// by DdiBoard (ddi_board.hpp), which brings the board up and down.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/interbus/bus_config.hpp"
#include "ibs/master/bus.hpp"
#include "ibs/pcp/mailbox_client.hpp"

namespace ibs::master {

// The DDI calls and firmware services the adapter makes, for reports.
enum class DdiCall : std::uint8_t {
  open_node,         // DDI_DevOpenNode
  close_node,        // DDI_DevCloseNode
  read_write_data,   // DDI_DTI_ReadWriteData
  read_data,         // DDI_DTI_ReadData
  write_data,        // DDI_DTI_WriteData
  send_message,      // DDI_MXI_SndMessage
  receive_message,   // DDI_MXI_RcvMessage
  get_diagnostic,    // GetIBSDiagnostic
  get_info,          // DDI_GetInfo
};
std::string_view to_string(DdiCall c);
// A return code's name: "ERR_NODE_NOT_READY"; "unknown return code" for one ibs/ddi.h lacks.
std::string_view ddi_return_name(std::int32_t code);
// "DDI_DevOpenNode(IBB1N1_D): ERR_NODE_NOT_READY (0087H)": the call, what it was made on, the code.
std::string ddi_call_text(DdiCall call, std::string_view on, std::int32_t code);

// What the board reported in a cycle, one entry per change, for the application's report
// (`ibs master --board` turns them into the summary's faults). Plain data: logged on the cycle
// path without allocation.
struct BoardEvent {
  enum class Kind : std::uint8_t {
    bus_error,         // BUS: cycles without valid data (the cycles are invalid while it lasts)
    bus_ok,            // BUS cleared (after Confirm_Diagnostics)
    peripheral_fault,  // a device reports a module error (PF; `device`, `number`)
    peripheral_ok,     // that device no longer
    segment_off,       // BSA: a segment switched off (by switch_segment or another application)
    segment_on,        // BSA gone
    sysfail,           // the board's controller failed (CTRL, ERR_IBS_SYSFAIL): every device lost
    call_failed,       // a DDI call of the cycle failed (`call`, `code`): every device lost
    service_refused,   // a diagnostic or segment service was confirmed negatively (`code`: result)
    user_error,        // USER: a service of someone's was refused (`code`: the parameter register)
  };
  Kind kind = Kind::bus_error;
  Time at{0};
  std::size_t device = 0;    // ring position (peripheral faults, segments)
  std::uint16_t number = 0;  // the board's device number (segment << 8 | position)
  std::int32_t code = 0;     // call_failed: the return code; service_refused: the result word
  DdiCall call = DdiCall::read_write_data;
};
std::string_view to_string(BoardEvent::Kind k);

struct DdiBusOptions {
  // A firmware service of the cycle (Get_Diag_Info, Confirm_Diagnostics, a segment switch) not
  // confirmed in this much of the caller's time is given up and sent again.
  Duration service_timeout = 1s;
  // The PCP clients' request timeout unless a request says otherwise (the drivers pass theirs).
  Duration pcp_timeout = 500ms;
};

class DdiBus final : public Bus {
 public:
  // At most this many messages are received per exchange (the board's mailbox holds 32).
  static constexpr std::size_t kMaxReceivesPerCycle = 64;
  static constexpr std::size_t kEventCapacity = 256;

  // On open nodes of a board whose active configuration is `config` (DdiBoard checks it), with
  // the board's device numbers in ring order.
  DdiBus(std::int32_t data_node, std::int32_t mailbox_node, interbus::BusConfig config,
         std::vector<std::uint16_t> device_numbers, const DdiBusOptions& options = {});

  Exchange exchange(interbus::ProcessImage& image, Time now) noexcept override;

  // The board's PCP client of ring device i; nullptr for a device without a PCP channel.
  pcp::MailboxClient* pcp_client(std::size_t i) noexcept;
  // Switches the segment that ring device i starts off or on (Control_Active_Configuration, sent
  // with the next exchange). Its devices' data is then not valid and reads 0, as the simulator's
  // bypassed devices; the board shows BSA. False for a device that starts no segment.
  bool switch_segment(std::size_t i, bool on) noexcept;

  // The events since the last clear_events(), oldest first; `lost_events` counts those that did
  // not fit.
  [[nodiscard]] std::span<const BoardEvent> events() const noexcept { return {events_.data(), event_count_}; }
  void clear_events() noexcept;
  [[nodiscard]] std::uint64_t lost_events() const noexcept { return lost_events_; }

  // The diagnostic status and parameter registers as last read.
  [[nodiscard]] std::uint16_t diagnostic_status() const noexcept { return diag_status_; }
  [[nodiscard]] std::uint16_t diagnostic_parameter() const noexcept { return diag_parameter_; }
  // True once the board has failed or a call of the cycle has: the bus is gone until the nodes
  // are closed.
  [[nodiscard]] bool failed() const noexcept { return failed_; }
  [[nodiscard]] const interbus::BusConfig& config() const noexcept { return config_; }
  [[nodiscard]] std::uint16_t device_number(std::size_t i) const noexcept {
    return i < numbers_.size() ? numbers_[i] : 0;
  }
  [[nodiscard]] std::uint64_t exchanges() const noexcept { return exchanges_; }
  [[nodiscard]] std::uint64_t valid_exchanges() const noexcept { return valid_exchanges_; }

 private:
  enum class Service : std::uint8_t { none, get_diag_info, confirm, segment };
  void log(BoardEvent e) noexcept;
  void lose_every_device(interbus::ProcessImage& image, Time now, DdiCall call, std::int32_t code) noexcept;
  void read_diagnostics(Time now) noexcept;
  void pump_mailbox(Time now) noexcept;
  bool send(std::span<const Word> words, std::uint16_t user_id, Time now) noexcept;
  void dispatch(std::span<const Word> m, Time now) noexcept;
  void service_confirmed(std::span<const Word> m, Time now) noexcept;
  void set_peripheral_fault(std::size_t i, bool on, Time now) noexcept;
  [[nodiscard]] std::optional<std::size_t> position_of(std::uint16_t number) const noexcept;

  std::int32_t data_;
  std::int32_t mailbox_;
  interbus::BusConfig config_;
  std::vector<std::uint16_t> numbers_;
  DdiBusOptions options_;
  std::size_t in_bytes_ = 0;
  std::size_t out_bytes_ = 0;
  std::array<std::uint8_t, 512> out_buffer_{};
  std::array<std::uint8_t, 512> in_buffer_{};
  std::array<std::uint8_t, 1024> message_{};
  std::array<Word, 512> words_{};

  std::vector<LinkState> links_;
  std::vector<bool> pf_;             // per device: the board names a module error
  std::vector<bool> switched_off_;   // per device: its segment is off
  std::vector<std::unique_ptr<pcp::MailboxClient>> clients_;  // per device (null: no PCP)
  std::array<std::int16_t, 256> client_of_cr_{};              // CR -> device, -1: none

  std::uint16_t diag_status_ = 0;
  std::uint16_t diag_parameter_ = 0;
  bool bus_error_ = false;  // as last reported (events)
  bool bsa_ = false;
  bool user_ = false;
  bool failed_ = false;
  Service service_ = Service::none;  // the cycle's firmware service outstanding
  Time service_sent_{0};
  bool confirm_due_ = false;  // Confirm_Diagnostics after the Get_Diag_Info just confirmed
  // A segment switch asked for and not yet sent: the segment's first device, and on or off.
  std::optional<std::pair<std::size_t, bool>> segment_request_;

  std::array<BoardEvent, kEventCapacity> events_{};
  std::size_t event_count_ = 0;
  std::uint64_t lost_events_ = 0;
  std::uint64_t exchanges_ = 0;
  std::uint64_t valid_exchanges_ = 0;
};

}  // namespace ibs::master
