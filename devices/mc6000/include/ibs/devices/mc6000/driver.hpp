// The MC6000's master driver: the DRIVECOM sequencer, the reference and actual in the words of
// its 405-SUPI / 406-IBCNF layout, and parameter access through PCP (INTERBUS manual 4.2): over the
// channel words of its layout (pcp/client.hpp), or, on a controller board, through the board's
// mailbox (use_pcp_client, pcp/mailbox_client.hpp) -- the same transactions over either.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "ibs/devices/driver.hpp"
#include "ibs/base/bounded_queue.hpp"
#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/devices/mc6000/pd_master.hpp"
#include "ibs/pcp/client.hpp"

namespace ibs::devices {

// The MC6000's parameters go through PCP (pcp/client.hpp): the driver queues requests, opens the
// association with Initiate when it has none, and works the queue one request at a time, since
// PCP allows one outstanding request per communication reference.
class Mc6000Driver final : public DeviceDriver, private ParameterAccess {
 public:
  static constexpr std::size_t kQueueCapacity = 16;
  static constexpr std::size_t kCompletedCapacity = 16;
  // A write of 4-PROG = 1 (factory defaults) is confirmed after up to 10 s (LUSTBUS manual 10).
  static constexpr Duration kFactoryDefaultsTimeout = 10500ms;
  // A request's confirmation time grows with the bus cycle: a Read or Write over a one-word
  // channel is 24..28 fragments, each a bus cycle or more (PCP-E7). The timeout is the client's
  // (500 ms) or this many bus cycles, whichever is longer: on the full ring of 13.86 ms, 3.3 s.
  static constexpr std::uint32_t kTimeoutCycles = 240;

  explicit Mc6000Driver(const mc6000::Layout& layout,
                        const drivecom::SequencerConfig& config = drivecom::SequencerConfig::defaults());
  void cycle(const DriverIo& io, Time now) override;
  void initial(const DriverIo& io) override;
  void restart(Time now) override;
  drivecom::Sequencer& sequencer() override { return master_.sequencer(); }
  ParameterAccess& parameters() override { return *this; }
  void set_reference(double rpm) override {
    skip_ = nullptr;  // new reference words: the next cycle writes them
    master_.set_reference_rpm(rpm);
  }
  [[nodiscard]] double reference() const override { return master_.reference_rpm(); }
  [[nodiscard]] double actual() const override { return master_.actual_rpm(); }
  [[nodiscard]] std::string_view unit() const override { return "rpm"; }
  // A layout with a PCP channel: the transactions go through `client` from now on.
  bool use_pcp_client(pcp::ParameterClient& client) override;
  // The client over the channel words; nullptr without a channel or with another client.
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

  // cycle() of a driver with a PCP channel: the bus period, the process data, then the channel
  // (when the cycle hands the driver the channel's words).
  // Never inline: cycle() would then save registers for its calls on every driver's path.
  [[gnu::noinline]] void cycle_with_pcp(const DriverIo& io, Time now);
  // The channel's part of a cycle, written once for either client: `Channel` is pcp::Client
  // (the words', called directly) or pcp::ParameterClient (another carrier's, through the
  // interface).
  template <typename Channel>
  void run_channel(Channel& c, Time now, std::span<const Word> s2m, std::span<Word> m2s);
  template <typename Channel>
  void take_results(Channel& c);
  // The timeout for the next request: kTimeoutCycles of the cycle time seen, at least the
  // client's own.
  [[nodiscard]] Duration request_timeout(Duration at_least) const;
  template <typename Channel>
  void start_next(Channel& c, Time now);
  void complete(const Pending& p, ParamKind kind, std::int64_t value, const pcp::Result& r);
  [[nodiscard]] const Completed* find_completed(ParamId id) const;

  Mc6000PdMaster master_;
  pcp::ClientConfig pcp_config_{};
  bool channel_ = false;                    // the layout has a PCP channel
  std::optional<pcp::Client> client_;        // over the channel words, unless...
  pcp::ParameterClient* carrier_ = nullptr;  // ...another carrier's client is used (use_pcp_client)
  BoundedQueue<Pending> queue_{kQueueCapacity};  // the active request stays at the front until it completes
  bool active_ = false;      // the queue head has been sent
  bool initiating_ = false;  // an Initiate is outstanding for the queue head
  std::array<Completed, kCompletedCapacity> completed_{};
  std::size_t completed_next_ = 0;
  ParamId next_id_ = 1;
  Refusal refusal_ = Refusal::none;
  Time last_cycle_{};
  bool cycled_ = false;
  Duration period_{};  // the bus cycle, from the times cycle() is called with (PCP drivers only)
};

}  // namespace ibs::devices
