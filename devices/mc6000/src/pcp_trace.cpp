#include "ibs/devices/mc6000/pcp_trace.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/pcp_served.hpp"
#include "ibs/devices/mc6000/settings.hpp"
#include "ibs/pcp/client.hpp"
#include "ibs/pcp/explain.hpp"
#include "ibs/pcp/server.hpp"

namespace ibs::devices::mc6000 {

namespace {

using namespace pcp;

constexpr Duration kTraceStep = 1ms;  // without a `step-time` header

Duration step_of(const ibs::trace::Header& h) { return h.step_time.value_or(kTraceStep); }
// DRIVECOM status words for the `init` states, as the device model will report them in
// 408-IBSTA: START-UP INHIBIT 0240H (INTERBUS manual 5.3.4, first row), FAULT 0208H (fault bit 3 and
// remote bit 9 of 5.3.2).
constexpr std::uint32_t kStatusStartUpInhibit = 0x0240;
constexpr std::uint32_t kStatusFault = 0x0208;

void check_header(const ibs::trace::Header& h) {
  if (h.words != ibs::trace::WordsKind::pcp) {
    throw std::invalid_argument("PCP adapters serve `words: pcp`, not `words: " +
                                std::string(ibs::trace::to_string(h.words)) + "`");
  }
}

class PcpDeviceSide final : public ibs::trace::DeviceSide {
 public:
  explicit PcpDeviceSide(const ibs::trace::Header& h)
      : words_(trace_channel_words(h)),
        step_(step_of(h)),
        drive_(drive_parameters_config()),
        served_(drive_),
        server_(config(h), served_) {
    // The trace's power-on start keeps the 85-SERR power-on bit; the others have read it.
    if (h.init != DeviceStart::initialised) drive_.read(now_, kSerr);
    drive_.parameters().set_reading(
        kIbsta, h.init == DeviceStart::fault ? kStatusFault : kStatusStartUpInhibit);
    drive_.set_fault(h.init == DeviceStart::fault);
  }
  PcpDeviceSide(const PcpDeviceSide&) = delete;
  PcpDeviceSide& operator=(const PcpDeviceSide&) = delete;
  [[nodiscard]] std::size_t m2s_words() const override { return static_cast<std::size_t>(words_); }
  [[nodiscard]] std::size_t s2m_words() const override { return static_cast<std::size_t>(words_); }
  void initial(std::span<Word> s2m) override { server_.show(now_, s2m); }
  void step(std::span<const Word> m2s, std::span<Word> s2m) override {
    now_ += step_;
    server_.step(now_, m2s, s2m);
  }

 private:
  static ServerConfig config(const ibs::trace::Header& h) {
    ServerConfig c = server_config(trace_channel_words(h));
    c.latency = LatencyModel::immediate();
    c.start = h.init == DeviceStart::initialised ? StartMode::power_on : StartMode::running;
    return c;
  }
  int words_;
  Duration step_;
  ParametersOnly drive_;
  PcpServed served_;
  Server server_;
  Time now_{};
};

// The raw trace value as the bytes a Write carries: the parameter's type decides the width; a
// value that does not fit it (or an unknown parameter) goes with 2 or 4 bytes, and the servo
// judges it (data length, object does not exist).
std::size_t trace_value_bytes(std::uint16_t pnr, std::int64_t raw, std::span<std::uint8_t, 4> out) {
  if (const ParameterInfo* p = find_parameter(kParameters, pnr)) {
    auto v = value_from_signed_raw(p->type, raw);
    if (!v && raw >= 0 &&
        static_cast<std::uint64_t>(raw) < (std::uint64_t{1} << (8U * size_of(p->type)))) {
      v = Value{p->type, static_cast<std::uint32_t>(raw)};
    }
    if (v) return encode(*v, out);
  }
  const bool word = raw >= -32768 && raw <= 65535;
  const Value v{word ? DataType::usign16 : DataType::int32q16,
                static_cast<std::uint32_t>(static_cast<std::uint64_t>(raw) & 0xFFFFFFFFU)};
  return encode(Value{v.type, word ? (v.raw & 0xFFFFU) : v.raw}, out);
}

class PcpMasterSide final : public ibs::trace::MasterSide {
 public:
  explicit PcpMasterSide(const ibs::trace::Header& h)
      : words_(trace_channel_words(h)), step_(step_of(h)), client_(config(h)) {
    if (h.request) check_request(*h.request);
  }
  [[nodiscard]] std::size_t m2s_words() const override { return static_cast<std::size_t>(words_); }
  [[nodiscard]] std::size_t s2m_words() const override { return static_cast<std::size_t>(words_); }
  void initial(std::span<Word> m2s) override { client_.show(now_, m2s); }

  // A request the channel cannot carry; thrown at construction, where the caller names the line.
  static void check_request(const ibs::trace::Request& request) {
    if (request.kind == ibs::trace::Request::Kind::state) {
      throw std::invalid_argument(
          "a PCP channel trace cannot carry `request: " + ibs::trace::to_string(request) +
          "` (DRIVECOM states travel in `words: pd`)");
    }
  }

  void submit(const ibs::trace::Request& request) override {
    check_request(request);
    request_ = request;
    phase_ = client_.associated() ? Phase::request : Phase::initiate;
    outcome_.reset();
  }

  void step(std::span<const Word> s2m, std::span<const ibs::trace::WordPattern> /*row_m2s*/,
            std::span<Word> m2s) override {
    now_ += step_;
    if (phase_ == Phase::initiate && client_.initiate(now_) == SubmitStatus::accepted) {
      phase_ = Phase::initiating;
    } else if (phase_ == Phase::request && submit_request() == SubmitStatus::accepted) {
      phase_ = Phase::requesting;
    }
    client_.step(now_, s2m, m2s);
    if (const auto r = client_.take_result()) {
      if (phase_ == Phase::initiating && r->ok()) {
        phase_ = Phase::request;
      } else {
        finish(*r);
      }
    }
  }

  [[nodiscard]] std::optional<ibs::trace::Outcome> outcome() const override { return outcome_; }

 private:
  enum class Phase { idle, initiate, initiating, request, requesting, done };

  static ClientConfig config(const ibs::trace::Header& h) {
    ClientConfig c;
    c.channel_words = trace_channel_words(h);
    return c;
  }

  SubmitStatus submit_request() {
    const ParameterRef p = ParameterRef::number(request_.parameter);
    switch (request_.kind) {
      case ibs::trace::Request::Kind::read:
        return client_.read(now_, p);
      case ibs::trace::Request::Kind::describe:
        return client_.get_ov(now_, p);
      case ibs::trace::Request::Kind::write: {
        std::array<std::uint8_t, 4> b{};
        const std::size_t n = trace_value_bytes(request_.parameter, request_.value, b);
        return client_.write_bytes(now_, p, std::span<const std::uint8_t>(b.data(), n));
      }
      case ibs::trace::Request::Kind::state:
        break;
    }
    return SubmitStatus::invalid_argument;
  }

  void finish(const Result& r) {
    phase_ = Phase::done;
    ibs::trace::Outcome o;
    if (r.kind == ResultKind::ok) {
      o.kind = ibs::trace::Outcome::Kind::ok;
      if (r.service == ServiceCode::read) {
        std::int64_t v = 0;
        for (const std::uint8_t b : r.data.view()) v = (v << 8) | b;
        o.value = v;
      }
    } else if (r.kind == ResultKind::timeout) {
      o.kind = ibs::trace::Outcome::Kind::timeout;
    } else {
      o.kind = ibs::trace::Outcome::Kind::nak;
    }
    outcome_ = o;
  }

  int words_;
  Duration step_;
  Client client_;
  Time now_{};
  ibs::trace::Request request_{};
  Phase phase_ = Phase::idle;
  std::optional<ibs::trace::Outcome> outcome_;
};

class PcpExplainer final : public ibs::trace::Explainer {
 public:
  explicit PcpExplainer(int words) : words_(static_cast<std::size_t>(words)) {}
  [[nodiscard]] std::size_t m2s_words() const override { return words_; }
  [[nodiscard]] std::size_t s2m_words() const override { return words_; }
  [[nodiscard]] std::string explain_m2s(std::span<const Word> m2s) const override {
    return "M>S " + explain_frame(m2s, Direction::to_server);
  }
  [[nodiscard]] std::string explain_s2m(std::span<const Word> s2m) const override {
    return "S>M " + explain_frame(s2m, Direction::to_client);
  }

 private:
  std::size_t words_;
};

}  // namespace

int trace_channel_words(const ibs::trace::Header& h) {
  check_header(h);
  const trace::HeaderSetting* given_supi = h.setting(kSupiSetting.name);
  const int supi = given_supi != nullptr ? given_supi->value : static_cast<int>(kSupiSetting.fallback);
  if (supi < 0 || supi > kSupiMax) {
    throw std::invalid_argument("`supi: " + std::to_string(supi) +
                                "` is outside 0..12 (INTERBUS manual 3.2.2)");
  }
  if (const trace::HeaderSetting* ibcnf = h.setting(kIbcnfSetting.name))
    (void)make_layout(supi, ibcnf->value);  // throws LayoutError
  const int words = kSupiTable[static_cast<std::size_t>(supi)].pcp_words;
  if (supi == 0 || words == 0) {
    throw std::invalid_argument(
        "`supi: " + std::to_string(supi) +
        "` gives the MC6000 no PCP channel (INTERBUS manual 3.2.2); use 1, 2, 3, 5, 6, 8, 9 or 11");
  }
  return words;
}

void check_pcp_trace(const ibs::trace::Header& header) {
  (void)trace_channel_words(header);
  if (header.request) PcpMasterSide::check_request(*header.request);
}

std::unique_ptr<ibs::trace::DeviceSide> make_pcp_device_side(const ibs::trace::Header& header) {
  return std::make_unique<PcpDeviceSide>(header);
}

std::unique_ptr<ibs::trace::MasterSide> make_pcp_master_side(const ibs::trace::Header& header) {
  return std::make_unique<PcpMasterSide>(header);
}

std::unique_ptr<ibs::trace::Explainer> make_pcp_explainer(const ibs::trace::Header& header) {
  check_header(header);
  return std::make_unique<PcpExplainer>(trace_channel_words(header));
}

}  // namespace ibs::devices::mc6000
