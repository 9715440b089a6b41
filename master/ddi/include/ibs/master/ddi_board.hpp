// An INTERBUS controller board brought up and down for ibs's master, through the DDI calls only
// (ibs/ddi.h; docs/board.md, "Bring-up and shutdown"):
//
//   open:  both nodes (NAME_D, NAME_M); plug & play must be off (Read_Value 2240H); the
//          configuration activated (Activate_Configuration) and compared with the master's,
//          device by device (Read_Configuration: a device of another ID code is named and
//          refused); data transfer started; the diagnostics confirmed once the bus runs
//          (RUN | ACTIVE | READY without BUS, PF or USER). Then DdiBus (ddi_bus.hpp) is the
//          master loop's bus, and attach() gives each PCP driver the board's mailbox client.
//   close: Stop_Data_Transfer and both nodes closed -- after stop_drives() has brought the
//          drives to a safe state, also when the application ends on SIGINT or SIGTERM.
//
// Every refusal is an ibs::Error whose message names the call or the service and the code
// ("DDI_DevOpenNode(IBB1N1_D): ERR_NODE_NOT_READY (0087H): ..."), and nothing stays half-started:
// what open() opened it closes again. Configuration time: this allocates and waits (each service
// within a deadline), never on the cycle path.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ibs/base/error.hpp"
#include "ibs/interbus/bus_config.hpp"
#include "ibs/interbus/process_image.hpp"
#include "ibs/master/ddi_bus.hpp"
#include "ibs/master/master_loop.hpp"

namespace ibs::master {

struct DdiBoardOptions {
  // The board without the node suffix: "IBB1N1" (ISA and PCI boards), "IBETH01N1" (Ethernet
  // controllers); open() opens NAME_D and NAME_M.
  std::string board = "IBB1N1";
  // Each firmware service of open() and close() is confirmed within this, or refused as
  // board_no_answer.
  Duration service_deadline = 5s;
  DdiBusOptions bus;
};

class DdiBoard {
 public:
  static Expected<std::unique_ptr<DdiBoard>> open(const interbus::BusConfig& config,
                                                  const DdiBoardOptions& options = {});
  ~DdiBoard();
  DdiBoard(const DdiBoard&) = delete;
  DdiBoard& operator=(const DdiBoard&) = delete;

  DdiBus& bus() { return *bus_; }
  // Every driver of `loop` (on this board's configuration) with a PCP channel gets the board's
  // client of its device: its parameter transactions go through the mailbox from now on.
  void attach(MasterLoop& loop);
  // The board's bus cycle time (Read_Value 2231H); zero when the board does not give it.
  [[nodiscard]] Duration cycle_time() const { return cycle_time_; }
  [[nodiscard]] const std::string& name() const { return name_; }
  // The board's device number (segment << 8 | position) of ring device i.
  [[nodiscard]] std::uint16_t device_number(std::size_t i) const { return bus_->device_number(i); }
  // Stop_Data_Transfer (unless the board has failed) and both nodes closed; the first error.
  // Once; the destructor does it when nobody has.
  Error close();

 private:
  DdiBoard(std::string name, const DdiBoardOptions& options);
  Error bring_up(const interbus::BusConfig& config);
  // A firmware service: the request, then its confirmation within the deadline (other messages
  // are passed over); the confirmation's words -- a negative one too with `negative_too` -- or the
  // error naming `what`.
  Expected<std::vector<Word>> service(const char* what, std::vector<Word> request, bool negative_too = false);
  Error compare(const interbus::BusConfig& config, std::vector<std::uint16_t>& numbers);
  Error running_without_errors();

  std::string name_;
  DdiBoardOptions options_;
  std::int32_t data_ = 0;
  std::int32_t mailbox_ = 0;
  bool started_ = false;  // data transfer started by us
  bool closed_ = false;
  Duration cycle_time_{0};
  std::unique_ptr<DdiBus> bus_;
};

// Brings every drive of `loop` to a safe state, cycling over `bus` (docs/board.md, "Shutdown"):
// references to 0; a drive with its power stage on (ON, ENABLED) is let come to rest (its actual
// within 1 % of the reference it had, at most `ramp`), then sent SHUTDOWN to READY; every other
// drive -- in FAULT, failed, NOT READY, unknown -- gets BLOCK POWER, which resets no fault. Each
// cycle's time comes from `next_cycle`, which waits for it (the caller's clock). True when every
// drive reached its safe state within `ramp` + `settle`.
struct StopOptions {
  Duration ramp = 5s;
  Duration settle = 2s;
};
bool stop_drives(MasterLoop& loop, Bus& bus, interbus::ProcessImage& image, const std::function<Time()>& next_cycle,
                 const StopOptions& options = {});

}  // namespace ibs::master
