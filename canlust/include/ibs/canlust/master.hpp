// The master's side of CANLust (CANLust manual 5.2, 5.5): the logon list, System Start / Stop
// broadcasts, control telegrams to each drive, the drives' last status and error telegrams, and
// the parameter client. Frames in, frames out, time passed in; it knows no concrete drive (what
// the control and status words mean is the driver's, a floor above).
//
//   master.receive(frame, now);        // every frame from the bus
//   master.system_start();             // queues the broadcast 221 / 01H
//   master.send_control(1, {0x000F, q16});
//   master.step(now);                  // parameter client timeouts and starts
//   while (auto f = master.take_frame()) bus.send(*f);
// Everything after construction allocates nothing and throws nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "ibs/canlust/frame.hpp"
#include "ibs/canlust/identifiers.hpp"
#include "ibs/canlust/parameter_client.hpp"
#include "ibs/canlust/telegrams.hpp"
#include "ibs/base/bounded_queue.hpp"
#include "ibs/base/time.hpp"

namespace ibs::canlust {

struct MasterConfig {
  IdentifierMap ids{};
  ProcessLayout layout{};  // every drive's, unless set_layout() says otherwise
  ClientConfig client{};   // its `ids` is replaced by the master's
  std::size_t outbox_capacity = 128;
  std::size_t error_capacity = 32;
};

// What the master knows of one address.
struct DriveView {
  bool logged_on = false;           // a logon telegram was seen (5.5.4)
  Time first_logon{};
  Time last_logon{};
  std::uint32_t logons = 0;
  bool has_status = false;
  StatusTelegram status{};
  Time status_time{};
  std::uint32_t statuses = 0;
  std::uint32_t errors = 0;
  ProcessLayout layout{};
};

struct ErrorEvent {
  Address address = 0;
  ErrorTelegram error{};
  Time time{};
};

struct MasterCounters {
  std::uint32_t frames_in = 0;
  std::uint32_t foreign_frames = 0;   // identifiers outside the map
  std::uint32_t bad_frames = 0;       // CANLust identifiers with a bad length / RTR
  std::uint32_t dropped_frames = 0;   // outbox full
  std::uint32_t lost_errors = 0;      // error ring full
};

class Master {
 public:
  explicit Master(const MasterConfig& config = {});

  void receive(const CanFrame& f, Time now);
  void step(Time now);
  // The next frame into `out`, false when there is none; the same frames as the optional form,
  // without carrying one out through the stack (docs/canlust.md, "Parameter channel").
  bool take_frame(CanFrame& out);
  std::optional<CanFrame> take_frame();
  // Time::min() while frames wait in the outbox (take them now).
  [[nodiscard]] Time next_deadline() const {
    return !outbox_.empty() ? Time::min() : client_.next_deadline();
  }

  // 5.5.4: the broadcasts; every drive takes them together.
  void system_start();
  void system_stop();
  // 5.5.5: false when the address is out of the map or the outbox is full.
  bool send_control(Address a, const ControlTelegram& t);
  void set_layout(Address a, const ProcessLayout& l);

  ParameterClient& parameters() { return client_; }
  [[nodiscard]] const ParameterClient& parameters() const { return client_; }
  [[nodiscard]] const DriveView& drive(Address a) const { return drives_[a]; }
  // Addresses in the order of their first logon.
  [[nodiscard]] std::span<const Address> logon_order() const { return {logon_order_.data(), logon_count_}; }
  std::optional<ErrorEvent> take_error();
  [[nodiscard]] const MasterCounters& counters() const { return counters_; }
  [[nodiscard]] const IdentifierMap& ids() const { return config_.ids; }

 private:
  bool push(const std::optional<CanFrame>& f);

  MasterConfig config_;
  ParameterClient client_;
  std::vector<DriveView> drives_;
  std::vector<Address> logon_order_;
  std::size_t logon_count_ = 0;
  BoundedQueue<CanFrame> outbox_;
  std::vector<ErrorEvent> errors_;
  std::size_t err_head_ = 0;
  std::size_t err_size_ = 0;
  MasterCounters counters_{};
};

}  // namespace ibs::canlust
