// The MC6000's INTERBUS face as the simulator runs it (INTERBUS manual 3.2, 4.2, 5.3, 7.2): the
// process-data layout 405-SUPI / 406-IBCNF read at power-on, the DRIVECOM words decoded into the
// drive core's control word and reference every 1 ms sample, and the PCP channel, whose server
// serves the core's parameters. The servo itself -- parameters, DRIVECOM machine and plant, the
// 409-BUTWD bus watchdog (error 16 E-OP1, location 1), faults -- is the core (drive.hpp), which a
// LUSTBUS face may serve at the same time.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "ibs/devices/descriptor.hpp"
#include "ibs/devices/emulator.hpp"
#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/mc6000/drive.hpp"
#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/devices/mc6000/pcp_served.hpp"
#include "ibs/devices/mc6000/pd_device.hpp"
#include "ibs/interbus/device_start.hpp"
#include "ibs/base/time.hpp"
#include "ibs/pcp/server.hpp"

namespace ibs::devices {

struct Mc6000DeviceConfig {
  int supi = 11;   // 405-SUPI as stored in the servo (read at power-on, 3.2.2)
  int ibcnf = 2;   // 406-IBCNF (3.2.3)
  interbus::BusKind bus = interbus::BusKind::remote;
  Duration bus_watchdog{0};  // 409-BUTWD in ms; 0 = off (3.2.4)
  Mc6000PdConfig pd{};       // plant and limits; its layout is replaced by supi/ibcnf
  // The PCP server's latency model (pcp/server.hpp); empty: calibrated for the channel width.
  std::optional<pcp::LatencyModel> pcp_latency;
  double workload = 0.0;  // processor workload 0..1: PCP answers take longer as it grows (7.2)
  mc6000::DriveTiming timing{};  // the drive's own (EEPROM, 4-PROG, 80-SLOAD), for a core it makes
};

class Mc6000Device final : public DeviceEmulator {
 public:
  // A servo of its own. Throws devices::mc6000::LayoutError for a SUPI/IBCNF pair the servo refuses.
  Mc6000Device(const Mc6000DeviceConfig& config, DeviceStart start, Time now);
  // The INTERBUS face of an existing drive core (shared with other faces): stores 405/406/409 of
  // `config` in it as configured, and from now on samples it every 1 ms (drive.hpp). `start`
  // says only how the PCP link starts (operational: ready).
  Mc6000Device(const Mc6000DeviceConfig& config, std::shared_ptr<mc6000::Drive> drive, DeviceStart start,
               Time now);
  // A copy is an independent servo: its own copy of the core.
  Mc6000Device(const Mc6000Device& other);
  Mc6000Device& operator=(const Mc6000Device&) = delete;
  [[nodiscard]] std::unique_ptr<DeviceEmulator> clone() const override {
    return std::make_unique<Mc6000Device>(*this);
  }

  [[nodiscard]] const devices::mc6000::Layout& layout() const { return layout_; }
  [[nodiscard]] mc6000::Drive& drive() { return *drive_; }
  [[nodiscard]] const mc6000::Drive& drive() const { return *drive_; }
  [[nodiscard]] const std::shared_ptr<mc6000::Drive>& shared_drive() const { return drive_; }

  // One 1 ms sample: the process-data words (control word first) and the PCP channel words
  // (layout().pcp_words each). With the channel words the sample also runs the channel's
  // interface side (a caller whose sample is its bus cycle); with empty spans only the servo
  // processor's share, and pcp_cycle() runs the interface at every bus cycle.
  void sample(std::span<const Word> pd_m2s, std::span<Word> pd_s2m, Time now,
              std::span<const Word> pcp_m2s = {}, std::span<Word> pcp_s2m = {}) {
    step(pd_m2s, now, pcp_m2s, pcp_s2m);
    output(pd_s2m);
  }
  void sample(const EmulatorIo& io, Time now) override { sample(io.pd_in, io.pd_out, now, io.pcp_in, io.pcp_out); }
  // Without PCP words nobody reads the process-data words between two cycle ends.
  [[nodiscard]] bool defers_output() const override { return !pcp_; }
  void sample_deferred(std::span<const Word> pd_m2s, Time now) override { step(pd_m2s, now); }
  void sample_held(std::span<const Word> pd_m2s, Time first, Duration period, std::uint32_t count) override {
    step_held(pd_m2s, first, period, count);
  }
  // The same sample without writing the process-data words; output() writes them as they stand
  // after the last sample. The PCP words are written in every sample.
  void step(std::span<const Word> pd_m2s, Time now, std::span<const Word> pcp_m2s = {},
            std::span<Word> pcp_s2m = {});
  // `count` samples at first, first + period, ... with the same process-data words (between two
  // bus cycles they do not change): exactly what as many calls of step() do. A servo with PCP
  // words steps its channel sample by sample (use step() for those words).
  void step_held(std::span<const Word> pd_m2s, Time first, Duration period, std::uint32_t count);
  void output(std::span<Word> pd_s2m) const override;
  void output_pcp(Time now, std::span<Word> pcp_s2m) override;
  // The INTERBUS CPU's side of the PCP channel, every valid data cycle (INTERBUS manual 3.2.2): the link's
  // fragments move at the bus cycle, independent of the 1 ms control sample (docs/pcp.md).
  void pcp_cycle(Time now, std::span<const Word> pcp_m2s, std::span<Word> pcp_s2m) override;

  // A valid data cycle reached the device: "the watchdog is triggered with every INTERBUS cycle".
  // Not while the face is deaf (a SMARTCARD operation, the card withdrawn): nothing reaches the servo.
  void bus_cycle(Time now) override {
    if (!deaf(now)) drive_->fieldbus_cycle(now);
  }
  void power_cycle(Time now) override;
  void set_fault(bool present) override { drive_->set_external_fault(present); }
  // Plant and fault events (plant_event.hpp): the core's, once for every face.
  bool apply_event(const PlantEvent& e, Time now) override;
  void set_load_torque(double nm) { drive_->set_load_torque(nm); }
  void set_bus_watchdog(Duration d);

  // A servo switched on with other 405-SUPI / 406-IBCNF values than the ring was configured for
  // shows another ID code: the master's configuration no longer fits it and the bus reports a
  // module error until the ring is configured again (a new run).
  // Without mains the INTERBUS card of the servo is off too (MC-D6): a module error. So while a
  // SMARTCARD is read or written (INTERBUS manual 6.1's "bus operation is disabled", MC-D9) and while the
  // card is out of its slot or not yet detected by a power-on (INTERBUS manual 3.2.1, MC-D10).
  [[nodiscard]] bool module_error(Time now) const override {
    return configuration_mismatch_ || !drive_->powered() || deaf(now);
  }
  // The face takes no words and no PCP frames: the servo samples on with the last words it took.
  [[nodiscard]] bool deaf(Time now) const { return drive_->card_busy(now) || !drive_->interbus_card_serving(); }
  [[nodiscard]] bool configuration_mismatch() const { return configuration_mismatch_; }
  [[nodiscard]] drivecom::State state() const override { return drive_->state(); }
  [[nodiscard]] double actual_rpm() const { return drive_->actual_rpm(); }
  [[nodiscard]] double actual() const override { return drive_->actual_rpm(); }
  [[nodiscard]] double reference_rpm() const { return drive_->reference_rpm(); }
  [[nodiscard]] double torque_nm() const { return drive_->torque_nm(); }
  [[nodiscard]] Word status_word() const { return drive_->status_word(); }
  [[nodiscard]] bool watchdog_tripped() const override { return drive_->bus_watchdog_fault(); }
  // The error the servo shows: 16 (E-OP1) at location 1 after the bus watchdog ran out.
  [[nodiscard]] std::optional<int> error_number() const override {
    return watchdog_tripped() ? std::optional<int>(mc6000::kWatchdogError) : std::nullopt;
  }
  // Its error location (3.2.4: "The watchdog error number is 16 ('E-OP1'), with error location 1").
  [[nodiscard]] std::optional<int> error_location() const {
    return watchdog_tripped() ? std::optional<int>(mc6000::kWatchdogLocation) : std::nullopt;
  }
  [[nodiscard]] const drivecom::SampleResult& last_sample() const { return drive_->last_sample(); }
  // A recording's `! write` events: every change a channel made (the process-data words carry no
  // parameter channel: PCP and a LUSTBUS face note theirs); and their replay, as a PCP write.
  void record_changes(bool on) override { drive_->journal().enable(on); }
  std::size_t take_changes(std::span<drive::ParameterChange> out) override { return drive_->journal().take(out); }
  std::string write_parameter(std::uint16_t number, std::int64_t value, Time now) override;
  // The PCP server (nullptr for a layout without PCP words); it serves drive().parameters().
  [[nodiscard]] pcp::Server* pcp() { return pcp_ ? &*pcp_ : nullptr; }
  [[nodiscard]] const pcp::Server* pcp() const { return pcp_ ? &*pcp_ : nullptr; }
  // How many times 15-PLRDY = 1 recalculated the controller (4.2).
  [[nodiscard]] std::uint32_t recalculations() const { return drive_->recalculations(); }
  [[nodiscard]] Notices notices() const override {
    return {recalculations(), "15-PLRDY = 1: controller parameters recalculated"};
  }

 private:
  void attach(const Mc6000DeviceConfig& config, DeviceStart start);
  // Decodes the process-data words and samples the core (INTERBUS manual 5.1.2: a 0->1 edge of control
  // word bit 7 is the fault reset, the same core call as 416-SCTL1 bit 7 over LUSTBUS).
  void sample_core(std::span<const Word> pd_m2s, Time first, Duration period, std::uint32_t count);

  mc6000::Layout layout_;
  std::shared_ptr<mc6000::Drive> drive_;
  mc6000::PcpServed served_;
  std::optional<pcp::Server> pcp_;
  Word last_control_ = 0;
  std::array<Word, 4> held_{};  // the process-data words taken last (the servo holds them)
  std::uint32_t reboots_seen_ = 0;  // the core's reaction-5 boots this face has followed
  bool configuration_mismatch_ = false;
};

namespace mc6000 {
// The servo its configuration describes (descriptor.hpp), started as `start` at `now`.
std::unique_ptr<DeviceEmulator> make_emulator(const Configuration& config, DeviceStart start, Time now);
}  // namespace mc6000

}  // namespace ibs::devices
