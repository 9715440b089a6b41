// The PCP server: the drive side of the parameter channel (INTERBUS manual 4.2, as the MC6000 has it).
// Two processors share it, as on the servo (INTERBUS manual 3.2.2: the servo's INTERBUS CPU): the
// interface side runs the link at the bus cycle (cycle(): the channel words of every cycle), the
// servo's processor takes complete requests and answers them in its samples (sample(): the
// MC6000: every 1 ms, INTERBUS manual 7.2). step() does both in one call, for a caller whose cycle is its
// sample (trace replay, lock-step tests). The server answers Initiate, Read, Write, Get-OV long, Identify and Status
// and may send Information Reports (the KBL of 4.2.2). It serves the parameters it is given
// (ServedParameters, served.hpp) and owns none: the values, their checks, 85-SERR and the drive's
// own timing (EEPROM, PROG, a download) are the drive's, which other buses reach as well.
//
// Latency model (docs/pcp.md, "Latency model"): a complete request is executed
// `processing(workload)` after it arrived, processing = min + workload * (max - min), then the
// confirmation is segmented back (later still when the drive says so, WriteAnswer::confirm_after).
//
// The cycle path (step, the setters) allocates nothing, throws nothing, reads no clock.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/pcp/link.hpp"
#include "ibs/pcp/parameters.hpp"
#include "ibs/pcp/parameter_store.hpp"
#include "ibs/pcp/pdu.hpp"
#include "ibs/pcp/served.hpp"

namespace ibs::pcp {

struct LatencyModel {
  // Time from a complete request to its execution: the device's background task, slower as its
  // control loop takes more of the processor. processing = min + workload * (max - min). The
  // default is neutral -- none: a request is executed in the step it completes; a drive's wing
  // calibrates its own (the MC6000's: mc6000::pcp_latency, devices/mc6000/channel.hpp).
  Duration processing_min{0};
  Duration processing_max{0};
  [[nodiscard]] Duration processing(double workload) const;

  // Replay (one trace step = one device step): a request is executed in the step it completes.
  static LatencyModel immediate();
};

enum class StartMode : std::uint8_t {
  power_on,  // as after switching on: the link announces the restart
  running,   // running for a while: link ready (trace `init: operational`)
};

struct ServerConfig {
  int channel_words = 1;  // 1, 2 or 4 (405-SUPI)
  Kbl kbl = kDefaultServerKbl;
  std::uint16_t password = 0;           // an Initiate must carry it
  // The processing time: `latency` when given; otherwise `latency_for(channel_words)`, the drive's
  // calibration by channel width, when given; otherwise the neutral LatencyModel{}.
  std::optional<LatencyModel> latency;
  LatencyModel (*latency_for)(int channel_words) = nullptr;
  double workload = 0.0;                // 0..1
  Duration link_ack_timeout = 100ms;
  IdentifyInfo identity{Name::from("Lust"), Name{}, Name::from("PCP 2.0")};  // model: the drive's
  StartMode start = StartMode::power_on;
};

struct ServerStats {
  std::uint32_t requests = 0;
  std::uint32_t positive = 0;
  std::uint32_t negative = 0;
  std::uint32_t aborts_sent = 0;
  std::uint32_t aborts_received = 0;
  std::uint32_t link_resets = 0;
};

class Server {
 public:
  // Refuses a workload outside 0..1 (ErrorCode::channel_workload_out_of_range), a latency with
  // processing_min below 0 or above processing_max (ErrorCode::channel_latency_invalid), then what
  // ParameterStore::validate refuses of the table and Link::validate of the channel.
  [[nodiscard]] static Error validate(const ServerConfig& cfg,
                                      std::span<const ParameterInfo> table);
  // Serves `served` (which must outlive the server), with a configuration validate() accepts for
  // its table: otherwise it throws std::invalid_argument with validate()'s message (configuration
  // time), or, in the embedded build, aborts.
  Server(const ServerConfig& cfg, ServedParameters& served);

  // The servo was switched off and on: association gone, the link announces the restart with
  // ABORT. (The drive's own power-on -- RAM from EEPROM, 85-SERR -- is the drive's.)
  void power_on(Time now);

  // The interface side, once per bus cycle: reads the master's frame of this cycle and writes the
  // servo's frame for the next.
  void cycle(Time now, std::span<const Word> m2s, std::span<Word> s2m);
  // The servo processor's share, once per device sample: takes a complete request from the
  // interface, executes it after the latency model's processing time, hands the answer back.
  void sample(Time now);
  // Both in one call (cycle == sample): receive, sample, transmit.
  void step(Time now, std::span<const Word> m2s, std::span<Word> s2m);
  // The frame the servo shows before its first sample (a trace's s2m[0]).
  void show(Time now, std::span<Word> s2m) { link_.transmit(now, s2m); }

  // After a copy of the object that owns both the server and what it serves: serve the copy's.
  void serve(ServedParameters& served) { served_ = &served; }
  [[nodiscard]] ServedParameters& served() { return *served_; }
  [[nodiscard]] const ServedParameters& served() const { return *served_; }

  // Inputs from the device model.
  void set_workload(double workload);  // clamped to 0..1

  // Queues an Information Report with the parameter's value; false without an association,
  // while the server is busy, or for an unknown parameter.
  bool information_report(std::uint16_t number);

  [[nodiscard]] bool associated() const { return associated_; }
  [[nodiscard]] bool busy() const { return job_active_ || out_pending_; }
  [[nodiscard]] const Link& link() const { return link_; }
  [[nodiscard]] const ServerStats& stats() const { return stats_; }
  [[nodiscard]] const ServerConfig& config() const { return cfg_; }

 private:
  void receive(Time now, std::span<const Word> m2s);
  void serve(Time now);  // the servo processor's work of a sample, after the drive's advance()
  void handle_message(Time now, std::span<const std::uint8_t> msg);
  void execute(Time now);
  void queue_abort(AbortReason reason, std::uint8_t cr);
  void drop_association();
  PcpError do_read(Time now, ResponsePdu& r);
  // A confirmation with its result `err`: counted, encoded into out_, to be sent from `at`.
  void answer(ResponsePdu& r, PcpError err, Time at);

  ServerConfig cfg_;
  LatencyModel latency_;
  ServedParameters* served_;
  Link link_;
  double workload_ = 0.0;
  // latency_.processing(workload_), formed when the workload is set rather than per request.
  Duration processing_{};

  bool associated_ = false;
  std::uint8_t cr_ = 0;

  bool job_active_ = false;
  RequestPdu job_{};
  Time job_at_{};

  ResponsePdu read_answer_{};  // Read confirmations' (execute)

  bool out_pending_ = false;
  bool out_is_report_ = false;
  Pdu out_{};
  Time out_at_{};

  ServerStats stats_{};
};

}  // namespace ibs::pcp
