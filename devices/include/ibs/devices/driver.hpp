// The master side of one drive: what the master's cycle loop steps for each device. A driver
// composes the DRIVECOM sequencer, the reference/actual conversion to engineering units and the
// device's parameter channel, and offers parameter access through one interface whatever the
// channel (the VF1000's communication word, the MC6000's PCP). Each drive's wing implements it
// (devices/<drive>/driver.hpp); the device side mirrors it (emulator.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "ibs/drivecom/sequencer.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"

namespace ibs::pcp {
class ParameterClient;  // pcp/parameter_client.hpp
}  // namespace ibs::pcp

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

  // The device's PCP channel carried otherwise than in its process-data words -- through a
  // controller board's mailbox (pcp::MailboxClient; master/ddi) -- for every parameter
  // transaction from now on; `client` must outlive the driver's use of it. The words of the
  // channel in DriverIo are then not the driver's. False, and nothing changed, for a driver
  // without a PCP channel. Configuration time, before the first cycle.
  virtual bool use_pcp_client(pcp::ParameterClient& client) {
    static_cast<void>(client);
    return false;
  }

  // The master loop's skip of a holding driver (MasterLoop::cycle, docs/performance.md). A driver
  // points it at its sequencer at the end of a cycle that did nothing but hold: it wrote its
  // words and changed no state but what holding the same input words again leaves as it is
  // (drivecom::Sequencer::step_holding reads no time), and waits for no timer. Until the
  // sequencer's hold code changes (only a step sets it; every request, stop request, restart
  // and change of the application bits clears it), the driver's input words or link flags
  // change, or the driver clears it (a new reference, a restart), its next cycle would be the
  // same again, so the loop may write its words itself instead of calling it. Null: no skip;
  // a driver with a parameter channel or a timer never sets it. A driver that runs in a loop is
  // cycled by that loop only.
  [[nodiscard]] const drivecom::Sequencer* skip_while_holding() const { return skip_; }

 protected:
  const drivecom::Sequencer* skip_ = nullptr;
};

}  // namespace ibs::devices
