// The PCP server: the drive side of the parameter channel (seed 001, 4.2, as the MC6000 has it).
// The device model steps it once per sample (the MC6000: 1 ms, seed 001, 7.2) with the channel
// words and the time; the server answers Initiate, Read, Write, Get-OV long, Identify and Status
// from the drive's parameter table (its wing's, devices/mc6000/parameters.hpp) and may send
// Information Reports (the KBL of 4.2.2). The parameters with behaviour beyond storing a value
// (85-SERR, a PROG command, a controller-recalculation request, the SLOAD download handshake) are
// named by the drive in ServerConfig::roles.
//
// Latency model (docs/pcp.md, "Latency model"): a complete request is executed
// `processing(workload)` after it arrived, processing = min + workload * (max - min), then the
// confirmation is segmented back. EEPROM writes are acknowledged once in RAM and saved in the
// background, 15 ms per byte (seed 000, 3 and 10.2.2); another EEPROM write in that time is
// refused with "not executable now" and sets the EEPROM-busy bit of 85-SERR.
//
// The cycle path (step, the setters) allocates nothing, throws nothing, reads no clock.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "ibs/drive/parameters.hpp"
#include "ibs/drive/siof.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/pcp/link.hpp"
#include "ibs/pcp/parameters.hpp"
#include "ibs/pcp/parameter_store.hpp"
#include "ibs/pcp/pdu.hpp"

namespace ibs::pcp {

struct LatencyModel {
  // Time from a complete request to its execution: the servo's background task, slower as the
  // control loop takes more of the processor. processing = min + workload * (max - min).
  Duration processing_min = 7ms;
  Duration processing_max = 27ms;
  // Seed 000, 3: "To save a byte in EEPROM, the servocontroller needs 15 ms".
  Duration eeprom_byte_time = 15ms;
  // Seed 000, 10, exception 1: 4-PROG = 1 answers once all parameters are reset, "up to 10 s".
  Duration factory_defaults_time = 10s;
  // 80-SLOAD = -2: the dataset check and save before SLOAD reads 0 (seed 000, 11.4; chosen).
  Duration dataset_check_time = 500ms;

  [[nodiscard]] Duration processing(double workload) const;

  // The defaults per channel width, calibrated so that a Read or Write, end to end at the master,
  // spans seed 001 7.2's 10..35 ms as the workload goes 0..1 (bus cycle 0.567 ms of one MC6000 on
  // the ring, 1 ms samples): 4 words 7..27 ms, 2 words 0..21 ms. One word cannot: its
  // segmentation alone takes 33..36 ms, so processing gets 0..2 ms (docs/pcp.md, errata).
  static LatencyModel for_channel(int channel_words);
  // Replay (one trace step = one device step): a request is executed in the step it completes.
  static LatencyModel immediate();
};

enum class StartMode : std::uint8_t {
  power_on,  // as after switching on: SERR power-on bit set, the link announces the restart
  running,   // running for a while: SERR read and clear, link ready (trace `init: operational`)
};

// The drive's parameters the server acts on (0: the drive has none).
struct ParameterRoles {
  // The serial-interface error flags (seed 000, 9.2): every refused write sets its bit, any bit
  // refuses further writes, reading it clears it.
  std::uint16_t serr = drive::kSiofNumber;
  // Writing drive::kLoadDefaults loads every factory default, confirmed after
  // LatencyModel::factory_defaults_time (seed 000, 10); reads back 0 (a command).
  std::uint16_t prog = 0;
  // Writing 1 asks the drive to recalculate its controller (counted: plrdy_requests()).
  std::uint16_t plrdy = 0;
  // The download handshake (seed 000, 11.4): drive::kDownloadBegin / kDownloadEnd.
  std::uint16_t sload = 0;
};

struct ServerConfig {
  int channel_words = 1;  // 1, 2 or 4 (405-SUPI)
  Kbl kbl = kDefaultServerKbl;
  std::uint16_t password = 0;           // an Initiate must carry it
  std::optional<LatencyModel> latency;  // empty: LatencyModel::for_channel(channel_words)
  double workload = 0.0;                // 0..1
  Duration link_ack_timeout = 100ms;
  IdentifyInfo identity{Name::from("Lust"), Name{}, Name::from("PCP 2.0")};  // model: the drive's
  StartMode start = StartMode::power_on;
  ParameterRoles roles{};
};

struct ServerStats {
  std::uint32_t requests = 0;
  std::uint32_t positive = 0;
  std::uint32_t negative = 0;
  std::uint32_t aborts_sent = 0;
  std::uint32_t aborts_received = 0;
  std::uint32_t link_resets = 0;
  std::uint32_t eeprom_saves = 0;
};

class Server {
 public:
  // Refuses a workload outside 0..1 (ErrorCode::channel_workload_out_of_range), a latency with
  // processing_min below 0 or above processing_max (ErrorCode::channel_latency_invalid), then what
  // ParameterStore::validate refuses of the table and Link::validate of the channel.
  [[nodiscard]] static Error validate(const ServerConfig& cfg,
                                      std::span<const ParameterInfo> table);
  // Serves the drive's table, with a configuration validate() accepts: otherwise it throws
  // std::invalid_argument with validate()'s message (configuration time), or, in the embedded
  // build, aborts.
  Server(const ServerConfig& cfg, std::span<const ParameterInfo> table);

  // Switches the servo off and on: RAM from EEPROM, an EEPROM save in progress is lost, SERR
  // power-on bit, association gone, the link announces the restart with ABORT.
  void power_on(Time now);

  // One device sample: reads the master's channel words, writes the servo's.
  void step(Time now, std::span<const Word> m2s, std::span<Word> s2m);
  // The frame the servo shows before its first sample (a trace's s2m[0]).
  void show(Time now, std::span<Word> s2m) { link_.transmit(now, s2m); }

  [[nodiscard]] ParameterStore& parameters() { return store_; }
  [[nodiscard]] const ParameterStore& parameters() const { return store_; }

  // Inputs from the device model.
  void set_workload(double workload);                           // clamped to 0..1
  void set_drive_running(bool running) { running_ = running; }  // 80-SLOAD only at standstill
  // Seed 000, 11.4: from 80-SLOAD = -1 until the dataset check has ended, "the servocontroller
  // will be secured against being engaged".
  [[nodiscard]] bool engage_locked() const { return download_active_ || dataset_checking_; }
  void set_fault(bool fault) { fault_ = fault; }                // Status: physical status 1

  // Queues an Information Report with the parameter's value; false without an association,
  // while the server is busy, or for an unknown parameter.
  bool information_report(std::uint16_t number);

  // How many times 15-PLRDY = 1 was written since construction (the device model recalculates).
  [[nodiscard]] std::uint32_t plrdy_requests() const { return plrdy_requests_; }
  [[nodiscard]] bool associated() const { return associated_; }
  [[nodiscard]] bool busy() const { return job_active_ || out_pending_; }
  [[nodiscard]] bool eeprom_busy(Time now) const { return now < eeprom_busy_until_; }
  [[nodiscard]] const Link& link() const { return link_; }
  [[nodiscard]] const ServerStats& stats() const { return stats_; }
  [[nodiscard]] const ServerConfig& config() const { return cfg_; }

 private:
  void advance(Time now);
  void handle_message(Time now, std::span<const std::uint8_t> msg);
  void execute(Time now);
  void queue_abort(AbortReason reason, std::uint8_t cr);
  void drop_association();
  [[nodiscard]] std::uint8_t serr() const;
  void set_serr_bits(std::uint8_t bits);
  PcpError do_read(ResponsePdu& r);
  PcpError do_write(Time now, Duration& extra_delay);

  ServerConfig cfg_;
  LatencyModel latency_;
  ParameterStore store_;
  Link link_;
  double workload_ = 0.0;
  bool running_ = false;
  bool fault_ = false;

  bool associated_ = false;
  std::uint8_t cr_ = 0;

  bool job_active_ = false;
  RequestPdu job_{};
  Time job_at_{};

  bool out_pending_ = false;
  bool out_is_report_ = false;
  Pdu out_{};
  Time out_at_{};

  bool eeprom_pending_ = false;
  std::uint16_t eeprom_number_ = 0;
  std::uint32_t eeprom_value_ = 0;
  Time eeprom_busy_until_{};

  bool download_active_ = false;  // 80-SLOAD = -1 seen
  bool dataset_checking_ = false;
  Time dataset_done_at_{};

  std::uint32_t plrdy_requests_ = 0;
  ServerStats stats_{};
};

}  // namespace ibs::pcp
