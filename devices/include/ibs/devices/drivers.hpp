// Master-side device drivers: what the master's cycle loop steps for each device. A driver
// composes the DRIVECOM sequencer, the reference/actual conversion to engineering units and the
// device's parameter channel, and offers parameter access through one interface for both device
// types (the VF1000 through its communication word, the MC6000 through PCP).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "ibs/devices/drive_pd.hpp"
#include "ibs/interbus/mc6000_layout.hpp"
#include "ibs/interbus/time.hpp"
#include "ibs/pcp/client.hpp"
#include "ibs/vf1000_channel/client.hpp"

namespace ibs::devices {

enum class ParamOp : std::uint8_t { read, write, describe };
std::string_view to_string(ParamOp op);

enum class ParamKind : std::uint8_t {
  pending,      // queued or running
  value,        // read: `value` holds the raw value
  written,      // write took effect
  description,  // describe: the description is available through describe()
  nak,          // the device refused (reason in describe())
  timeout,      // no complete answer in time
  aborted,      // the device or the master restarted during the transaction
  refused,      // never sent: queue full, number out of range, no parameter channel
};
std::string_view to_string(ParamKind k);

struct ParamStatus {
  ParamKind kind = ParamKind::pending;
  std::int64_t value = 0;
  [[nodiscard]] bool done() const { return kind != ParamKind::pending; }
};

using ParamId = std::uint32_t;  // 0 is never valid

// Parameter access of one device. submit() and status() are cycle-path safe (no allocation);
// describe() is for reports.
class ParameterAccess {
 public:
  virtual ~ParameterAccess() = default;
  // Queues a request; returns its id, or 0 with status refused (see describe(0)) when it cannot
  // be queued.
  virtual ParamId submit(ParamOp op, std::uint16_t number, std::int64_t value) = 0;
  [[nodiscard]] virtual ParamStatus status(ParamId id) const = 0;
  // "value 1000 (03E8H)", "NAK: 85-SIOF 80H: invalid value", "VB2 [%] EEPROM, decimal, 0..25.00,
  // default 8.00" ...
  [[nodiscard]] virtual std::string describe(ParamId id) const = 0;
  // True while the channel still closes a transaction whose outcome is known (the VF1000 master
  // returns to the starting position and waits for the inverter's wait mode, 4.1.3): the end of
  // a transfer as the manual's transfer times (7.1) count it.
  [[nodiscard]] virtual bool closing() const { return false; }
};

// What the master's loop hands a driver each cycle.
struct DriverIo {
  std::span<const Word> pd_in;   // the device's process-data words (status word first)
  std::span<Word> pd_out;        // the words to the device (control word first)
  std::span<const Word> pcp_in;  // PCP channel words from the device (MC6000)
  std::span<Word> pcp_out;       // PCP channel words to the device
  bool data_valid = true;        // false: this cycle delivered no valid data (corrupted, recovery)
  bool module_error = false;     // the bus reports a module error for the device
};

class DeviceDriver {
 public:
  virtual ~DeviceDriver() = default;
  // One master cycle. No allocation, no exceptions.
  virtual void cycle(const DriverIo& io, Time now) = 0;
  // The words before the first cycle.
  virtual void initial(const DriverIo& io) = 0;
  // The master restarted: sequencer idle (BLOCK POWER), parameter channel starts over.
  virtual void restart(Time now) = 0;

  virtual drivecom::Sequencer& sequencer() = 0;
  virtual ParameterAccess& parameters() = 0;
  // The reference in engineering units: rpm (MC6000), Hz signed by direction (VF1000).
  virtual void set_reference(double value) = 0;
  [[nodiscard]] virtual double reference() const = 0;
  [[nodiscard]] virtual double actual() const = 0;
  [[nodiscard]] virtual std::string_view unit() const = 0;
};

class Vf1000Driver final : public DeviceDriver, private ParameterAccess {
 public:
  explicit Vf1000Driver(const vf1000_channel::ClientConfig& channel = {},
                        const drivecom::SequencerConfig& config = drivecom::SequencerConfig::defaults());
  void cycle(const DriverIo& io, Time now) override;
  void initial(const DriverIo& io) override;
  void restart(Time now) override;
  drivecom::Sequencer& sequencer() override { return master_.sequencer(); }
  ParameterAccess& parameters() override { return *this; }
  void set_reference(double hz) override { master_.set_frequency_hz(hz); }
  [[nodiscard]] double reference() const override { return master_.frequency_setpoint_hz(); }
  [[nodiscard]] double actual() const override { return master_.actual_hz(); }
  [[nodiscard]] std::string_view unit() const override { return "Hz"; }
  [[nodiscard]] const vf1000_channel::Client& channel() const { return client_; }

 private:
  ParamId submit(ParamOp op, std::uint16_t number, std::int64_t value) override;
  [[nodiscard]] ParamStatus status(ParamId id) const override;
  [[nodiscard]] std::string describe(ParamId id) const override;
  [[nodiscard]] bool closing() const override {
    return client_.state() == vf1000_channel::ClientState::closing;
  }

  Vf1000PdMaster master_;
  vf1000_channel::Client client_;
  vf1000_channel::SubmitError last_refusal_ = vf1000_channel::SubmitError::none;
};

// The MC6000's parameters go through PCP (pcp/client.hpp): the driver queues requests, opens the
// association with Initiate when it has none, and works the queue one request at a time, since
// PCP allows one outstanding request per communication reference.
class Mc6000Driver final : public DeviceDriver, private ParameterAccess {
 public:
  static constexpr std::size_t kQueueCapacity = 16;
  static constexpr std::size_t kCompletedCapacity = 16;
  // A write of 4-PROG = 1 (factory defaults) is confirmed after up to 10 s (seed 000, 10).
  static constexpr Duration kFactoryDefaultsTimeout = 10500ms;

  explicit Mc6000Driver(const interbus::mc6000::Layout& layout,
                        const drivecom::SequencerConfig& config = drivecom::SequencerConfig::defaults());
  void cycle(const DriverIo& io, Time now) override;
  void initial(const DriverIo& io) override;
  void restart(Time now) override;
  drivecom::Sequencer& sequencer() override { return master_.sequencer(); }
  ParameterAccess& parameters() override { return *this; }
  void set_reference(double rpm) override { master_.set_reference_rpm(rpm); }
  [[nodiscard]] double reference() const override { return master_.reference_rpm(); }
  [[nodiscard]] double actual() const override { return master_.actual_rpm(); }
  [[nodiscard]] std::string_view unit() const override { return "rpm"; }
  [[nodiscard]] const pcp::Client* pcp() const { return client_ ? &*client_ : nullptr; }

 private:
  struct Pending {
    ParamId id = 0;
    ParamOp op = ParamOp::read;
    std::uint16_t number = 0;
    std::int64_t value = 0;
  };
  struct Completed {
    ParamId id = 0;
    ParamKind kind = ParamKind::pending;
    std::int64_t value = 0;
    pcp::Result result{};
  };
  enum class Refusal : std::uint8_t { none, no_channel, queue_full, bad_value };

  ParamId submit(ParamOp op, std::uint16_t number, std::int64_t value) override;
  [[nodiscard]] ParamStatus status(ParamId id) const override;
  [[nodiscard]] std::string describe(ParamId id) const override;

  void take_results(Time now);
  void start_next(Time now);
  void complete(const Pending& p, ParamKind kind, std::int64_t value, const pcp::Result& r);
  [[nodiscard]] const Completed* find_completed(ParamId id) const;

  Mc6000PdMaster master_;
  pcp::ClientConfig pcp_config_{};
  std::optional<pcp::Client> client_;
  std::array<Pending, kQueueCapacity> queue_{};
  std::size_t queue_head_ = 0;
  std::size_t queue_count_ = 0;
  bool active_ = false;      // the queue head has been sent
  bool initiating_ = false;  // an Initiate is outstanding for the queue head
  std::array<Completed, kCompletedCapacity> completed_{};
  std::size_t completed_next_ = 0;
  ParamId next_id_ = 1;
  Refusal refusal_ = Refusal::none;
};

}  // namespace ibs::devices
