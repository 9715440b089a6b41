#include "ibs/vf1000_channel/trace_adapters.hpp"

#include <stdexcept>
#include <string>

#include "ibs/vf1000_channel/comm_word.hpp"

namespace ibs::vf1000_channel {

namespace {

namespace tr = ibs::trace;

// Which drive the trace is for is the registry's business (devices/registry.hpp): it hands
// `words: comm` traces of the drives that have this channel here.
void check_header(const tr::Header& h, const char* who) {
  if (h.words != tr::WordsKind::comm) {
    throw std::invalid_argument(std::string(who) + ": serves `words: comm`, not `words: " +
                                std::string(tr::to_string(h.words)) + "`");
  }
}

ServerStart start_of(DeviceStart s) {
  switch (s) {
    case DeviceStart::operational:
    case DeviceStart::fault:
      return ServerStart::operational;
    case DeviceStart::power_on:
      return ServerStart::power_on;
    case DeviceStart::initialised:
      return ServerStart::initialised;
  }
  return ServerStart::operational;
}

class CommDeviceSide final : public tr::DeviceSide {
 public:
  CommDeviceSide(const tr::Header& h, std::span<const drive::ParameterInfo> params, const ServerConfig& config)
      : server_(config, start_of(h.init), Time{0}, params), step_(h.step_time.value_or(kTraceStepPeriod)) {}

  [[nodiscard]] std::size_t m2s_words() const override { return 1; }
  [[nodiscard]] std::size_t s2m_words() const override { return 1; }
  void initial(std::span<Word> s2m) override { s2m[0] = server_.output(); }
  void step(std::span<const Word> m2s, std::span<Word> s2m) override {
    ++steps_;
    s2m[0] = server_.step(m2s[0], step_ * steps_, false);
  }

 private:
  Server server_;
  Duration step_;
  std::int64_t steps_ = 0;
};

ClientConfig trace_client_config() {
  ClientConfig c;
  c.start_synchronised = true;
  return c;
}

class CommMasterSide final : public tr::MasterSide {
 public:
  explicit CommMasterSide(Duration step) : client_(trace_client_config()), step_(step) {}

  [[nodiscard]] std::size_t m2s_words() const override { return 1; }
  [[nodiscard]] std::size_t s2m_words() const override { return 1; }
  void initial(std::span<Word> m2s) override { m2s[0] = Client::initial_word(); }
  void submit(const tr::Request& request) override {
    const Submitted s = client_.submit(to_channel_request(request));
    if (!s) {
      throw std::invalid_argument("vf1000 comm master: request `" + tr::to_string(request) +
                                  "` refused: " + std::string(to_string(s.error)));
    }
    id_ = s.id;
  }
  void step(std::span<const Word> s2m, std::span<const tr::WordPattern> /*row_m2s*/,
            std::span<Word> m2s) override {
    // The communication word is protocol through and through: nothing is taken from the row.
    ++steps_;
    m2s[0] = client_.step(s2m[0], step_ * steps_);
  }
  [[nodiscard]] std::optional<tr::Outcome> outcome() const override {
    if (id_ == 0) return std::nullopt;
    const Poll p = client_.poll(id_);
    if (p.state != RequestState::done) return std::nullopt;
    return to_trace_outcome(p.outcome);
  }

 private:
  Client client_;
  Duration step_;
  RequestId id_ = 0;
  std::int64_t steps_ = 0;
};

class CommExplainer final : public tr::Explainer {
 public:
  [[nodiscard]] std::size_t m2s_words() const override { return 1; }
  [[nodiscard]] std::size_t s2m_words() const override { return 1; }
  [[nodiscard]] std::string explain_m2s(std::span<const Word> m2s) const override {
    if (m2s.size() != 1) return "expected 1 communication word, got " + std::to_string(m2s.size());
    return explain_master_word(m2s[0]);
  }
  [[nodiscard]] std::string explain_s2m(std::span<const Word> s2m) const override {
    if (s2m.size() != 1) return "expected 1 communication word, got " + std::to_string(s2m.size());
    return explain_inverter_word(s2m[0]);
  }
};

}  // namespace

Request to_channel_request(const tr::Request& r) {
  if (r.parameter > kMaxParameterNumber) {
    throw std::invalid_argument("vf1000 comm: parameter " + std::to_string(r.parameter) +
                                " above 3FFH (1023), the channel's range (INTERBUS manual 4.1.3)");
  }
  switch (r.kind) {
    case tr::Request::Kind::read:
      return value_inquiry(r.parameter);
    case tr::Request::Kind::describe:
      return description_scan(r.parameter);
    case tr::Request::Kind::write:
      if (r.value < -32768 || r.value > 0xFFFF) {
        throw std::invalid_argument("vf1000 comm: value " + std::to_string(r.value) +
                                    " does not fit a 16-bit parameter word");
      }
      return value_transfer(r.parameter,
                            static_cast<Word>(static_cast<std::uint64_t>(r.value) & 0xFFFFU));
    case tr::Request::Kind::state:
      break;
  }
  throw std::invalid_argument("vf1000 comm: `" + tr::to_string(r) +
                              "` is a DRIVECOM request; the communication word carries "
                              "read, write and describe");
}

tr::Outcome to_trace_outcome(const Outcome& o) {
  tr::Outcome t;
  switch (o.kind) {
    case OutcomeKind::value:
      t.kind = tr::Outcome::Kind::ok;
      t.value = o.value;
      break;
    case OutcomeKind::written:
    case OutcomeKind::description:
      t.kind = tr::Outcome::Kind::ok;
      break;
    case OutcomeKind::nak:
      t.kind = tr::Outcome::Kind::nak;
      break;
    case OutcomeKind::timeout:
    case OutcomeKind::inverter_restarted:
    case OutcomeKind::aborted:
    case OutcomeKind::protocol_error:
      t.kind = tr::Outcome::Kind::timeout;
      break;
  }
  return t;
}

std::unique_ptr<tr::DeviceSide> make_comm_device_side(const tr::Header& header,
                                                      std::span<const drive::ParameterInfo> params,
                                                      const ServerConfig& config) {
  check_header(header, "vf1000 comm device");
  return std::make_unique<CommDeviceSide>(header, params, config);
}

std::unique_ptr<tr::MasterSide> make_comm_master_side(const tr::Header& header) {
  check_comm_trace(header);
  return std::make_unique<CommMasterSide>(header.step_time.value_or(kTraceStepPeriod));
}

void check_comm_trace(const tr::Header& header) {
  check_header(header, "vf1000 comm");
  if (header.request) (void)to_channel_request(*header.request);
}

std::unique_ptr<tr::Explainer> make_comm_explainer() {
  return std::make_unique<CommExplainer>();
}

}  // namespace ibs::vf1000_channel
