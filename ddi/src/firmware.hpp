// The virtual board's firmware (docs/ddi.md): what an INTERBUS controller board does between the
// DDI and the ring. It is the simulator's master (sim::ExternalMaster): at every cycle end it
// hands the application's output bytes to the bus, takes the inputs, steps one PCP client per
// PCP device and keeps the diagnostic registers. Mailbox requests come in as DDI messages
// ([code][parameter count][parameters], big-endian words) and are answered with confirmations
// (code | 8000H, result first) and indications in the board's outgoing mailbox.
//
// Not thread-safe by itself: the board (board.hpp) calls it under its lock.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "ibs/interbus/bus_config.hpp"
#include "ibs/interbus/process_image.hpp"
#include "ibs/pcp/client.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::ddi {

// One message of the board's outgoing mailbox.
struct Message {
  std::uint16_t type = 0;     // DDI_MSG_CONFIRMATION / DDI_MSG_INDICATION
  std::uint16_t user_id = 0;  // the request's DDIUserID (0: indication)
  std::vector<std::uint8_t> bytes;
};

// What a mailbox request did, for the DDI's return code.
enum class Accept : std::uint8_t { ok, mailbox_full };

class Firmware final : public sim::ExternalMaster {
 public:
  // The outgoing mailbox holds at most this many messages before a send is refused.
  static constexpr std::size_t kMailboxCapacity = 32;

  Firmware(sim::Simulator& sim, const interbus::BusConfig& config, Duration cycle_time);

  // sim::ExternalMaster
  void cycle(interbus::ProcessImage& image, Time now, const master::Exchange& exchange) override;
  void restart(Time now) override;

  // Process data, by byte address of the image (checked by the caller).
  void read_inputs(std::size_t address, std::span<std::uint8_t> dst) const;
  void write_outputs(std::size_t address, std::span<const std::uint8_t> src);

  // A mailbox request of `words` (code, count, parameters; the count already checked).
  Accept request(std::span<const std::uint16_t> words, std::uint16_t user_id, Time now);
  [[nodiscard]] const Message* front() const { return outbox_.empty() ? nullptr : &outbox_.front(); }
  void pop() { outbox_.pop_front(); }

  [[nodiscard]] bool running() const { return running_; }
  [[nodiscard]] bool sysfail() const { return sysfail_; }
  [[nodiscard]] std::uint16_t diag_status() const;
  [[nodiscard]] std::uint16_t diag_parameter() const { return diag_parameter_; }
  // The INTERBUS device number (segment << 8 | position) of ring position i.
  [[nodiscard]] std::uint16_t device_number(std::size_t i) const { return numbers_[i]; }
  [[nodiscard]] std::uint64_t cycles() const { return cycles_; }

 private:
  struct Cr {  // one communication reference: a PCP device and its client
    std::size_t device = 0;
    std::uint8_t cr = 0;
    std::optional<pcp::Client> client;
    bool pending = false;  // a confirmed request is outstanding
    std::uint16_t code = 0;
    std::uint8_t invoke_id = 0;
    std::uint16_t user_id = 0;
  };

  void service(std::span<const std::uint16_t> words, std::uint16_t user_id);
  void pcp_service(std::span<const std::uint16_t> words, std::uint16_t user_id, Time now);
  void confirm(std::uint16_t code, std::uint16_t user_id, std::uint16_t result,
               std::span<const std::uint16_t> more = {});
  void indicate(std::uint16_t code, std::span<const std::uint16_t> params);
  void post(std::uint16_t type, std::uint16_t user_id, std::span<const std::uint16_t> words);
  void pcp_negative(const Cr& c, std::uint16_t code, const pcp::PcpError& e);
  void pcp_results(Cr& c);
  void stop_transfer(std::uint16_t abort_reason);
  void reset_clients(std::uint16_t abort_reason);
  [[nodiscard]] Duration pcp_timeout() const;
  [[nodiscard]] std::optional<std::size_t> segment_head(std::uint16_t number) const;
  void set_segment(std::size_t head, bool off);
  [[nodiscard]] bool any_switched_off() const;

  sim::Simulator& sim_;
  const interbus::BusConfig& config_;
  Duration cycle_time_;
  interbus::ProcessImage user_{};  // in: what the board delivered; out: what the application wrote
  std::vector<std::uint16_t> numbers_;
  std::vector<Cr> crs_;
  std::deque<Message> outbox_;

  bool active_ = false;
  bool running_ = false;
  bool sysfail_ = false;
  bool user_error_ = false;
  bool bus_error_ = false;             // latched: cycles without valid data while running
  bool bus_error_now_ = false;         // the last cycle delivered nothing
  std::vector<bool> pf_latched_;       // per device: a module error seen since the last confirmation
  std::vector<bool> pf_now_;           // per device: the module error of the last cycle
  std::uint16_t diag_parameter_ = 0;
  std::uint64_t cycles_ = 0;
  // Start_Data_Transfer is confirmed once the first data cycle has run (its user ID till then).
  std::optional<std::uint16_t> start_confirmation_;
};

}  // namespace ibs::ddi
