#include "ibs/devices/trace_adapters.hpp"

#include <cstdio>
#include <string>

#include "ibs/devices/drive_pd.hpp"
#include "ibs/devices/mc6000_device.hpp"
#include "ibs/devices/vf1000_device.hpp"
#include "ibs/pcp/trace_adapters.hpp"
#include "ibs/vf1000_channel/trace_adapters.hpp"

namespace ibs::devices {

namespace {

using trace::DeviceType;
using trace::Header;
using trace::Outcome;
using trace::Request;
using trace::TraceError;
using trace::WordPattern;
using trace::WordsKind;

// `init: power-on` is a device that has initialised with the power-on bit still set.
DeviceStart start_of(const Header& h) {
  switch (h.init) {
    case trace::InitState::operational: return DeviceStart::operational;
    case trace::InitState::power_on: return DeviceStart::initialised;
    case trace::InitState::fault: return DeviceStart::fault;
  }
  return DeviceStart::operational;
}

drivecom::Target target_of(trace::StateTarget t) {
  switch (t) {
    case trace::StateTarget::start_up_inhibit: return drivecom::Target::start_up_inhibit;
    case trace::StateTarget::ready: return drivecom::Target::ready;
    case trace::StateTarget::on: return drivecom::Target::on;
    case trace::StateTarget::enabled: return drivecom::Target::enabled;
  }
  return drivecom::Target::start_up_inhibit;
}

std::optional<Outcome> outcome_of(const drivecom::Report& r) {
  switch (r.phase) {
    case drivecom::Phase::idle:
    case drivecom::Phase::moving: return std::nullopt;
    case drivecom::Phase::reached: return Outcome{Outcome::Kind::ok, std::nullopt};
    case drivecom::Phase::failed:
      return Outcome{r.failure == drivecom::Failure::timeout ? Outcome::Kind::timeout
                                                             : Outcome::Kind::nak,
                     std::nullopt};
  }
  return std::nullopt;
}

interbus::mc6000::Layout layout_of(const trace::Trace& t) {
  const Header& h = t.header;
  try {
    return interbus::mc6000::make_layout(h.supi, h.ibcnf);
  } catch (const interbus::mc6000::LayoutError& e) {
    // The offending header's line: a message about 405-SUPI on the supi line, any other (IBCNF,
    // the pair) on the ibcnf line, each falling back to the other and then to the device line.
    const std::string msg = e.what();
    const bool about_supi = msg.rfind("405-SUPI", 0) == 0;
    const std::size_t first = about_supi ? h.lines.supi : h.lines.ibcnf;
    const std::size_t second = about_supi ? h.lines.ibcnf : h.lines.supi;
    const std::size_t line = first != 0 ? first : (second != 0 ? second : h.lines.device);
    throw TraceError(t.file, line, msg);
  }
}

void require_state_request(const trace::Trace& t) {
  const Header& h = t.header;
  if (h.request && h.request->kind != Request::Kind::state) {
    throw TraceError(t.file, h.lines.request,
                     "request: '" + to_string(*h.request) +
                         "' is a parameter request; a words: pd trace takes 'state TARGET' "
                         "(parameter requests go in words: comm or words: pcp traces)");
  }
}

// Up to `digits` significant digits, as %g would.
std::string num(double v, int digits = 7) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}
std::string hz(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

// --- MC6000 pd --------------------------------------------------------------------------------

// A device as the simulator runs it (mc6000_device.hpp, vf1000_device.hpp), one sample of its
// period per row and every row a valid bus cycle: recorded simulator traces replay unchanged.
template <typename Device>
class SimulatedDeviceSide final : public trace::DeviceSide {
 public:
  template <typename Config>
  SimulatedDeviceSide(std::size_t words, Duration period, const Config& config, DeviceStart start)
      : words_(words), period_(period), device_(config, start, Time{0}) {}
  std::size_t m2s_words() const override { return words_; }
  std::size_t s2m_words() const override { return words_; }
  void initial(std::span<Word> s2m) override { device_.output(s2m); }
  void step(std::span<const Word> m2s, std::span<Word> s2m) override {
    now_ += period_;
    device_.bus_cycle(now_);
    device_.sample(m2s, s2m, now_);
  }
  // The device faults a recording injects (trace-format.md, "Events").
  bool supports(trace::Event::Kind) const override { return true; }
  void apply(const trace::Event& e) override { device_.set_fault(e.kind == trace::Event::Kind::fault); }

 private:
  std::size_t words_;
  Duration period_;
  Device device_;
  Time now_{0};
};

Mc6000DeviceConfig mc6000_config(const interbus::mc6000::Layout& l) {
  Mc6000DeviceConfig c;
  c.supi = l.supi;
  c.ibcnf = static_cast<int>(l.ibcnf);
  c.bus = l.bus;
  return c;
}

class Mc6000Master final : public trace::MasterSide {
 public:
  explicit Mc6000Master(const interbus::mc6000::Layout& l) : master_(l) {}
  std::size_t m2s_words() const override { return static_cast<std::size_t>(master_.layout().pd_words); }
  std::size_t s2m_words() const override { return m2s_words(); }
  void initial(std::span<Word> m2s) override { master_.initial(m2s); }
  void submit(const Request& r) override { master_.sequencer().request(target_of(r.target), now_); }
  void step(std::span<const Word> s2m, std::span<const WordPattern> row_m2s,
            std::span<Word> m2s) override {
    now_ += kMc6000SamplePeriod;
    // The reference and the device bits of the control word are the application's: taken from
    // the file. The DRIVECOM bits 0-3 and 7 are the sequencer's and are computed.
    const auto& l = master_.layout();
    if (!row_m2s.empty() && row_m2s[0].is_exact()) master_.sequencer().set_application_bits(row_m2s[0].value);
    const auto n = static_cast<std::size_t>(l.reference_words);
    if (row_m2s.size() > n) {
      Word ref[2] = {0, 0};
      bool exact = true;
      for (std::size_t i = 0; i < n; ++i) {
        exact = exact && row_m2s[1 + i].is_exact();
        ref[i] = row_m2s[1 + i].value;
      }
      if (exact) master_.set_reference_rpm(interbus::mc6000::decode_reference(l, std::span<const Word>(ref, n)));
    }
    master_.cycle(s2m, m2s, now_);
  }
  std::optional<Outcome> outcome() const override { return outcome_of(master_.sequencer().report()); }

 private:
  Mc6000PdMaster master_;
  Time now_{0};
};

class Mc6000Explainer final : public trace::Explainer {
 public:
  explicit Mc6000Explainer(const interbus::mc6000::Layout& l) : layout_(l) {}
  std::size_t m2s_words() const override { return static_cast<std::size_t>(layout_.pd_words); }
  std::size_t s2m_words() const override { return static_cast<std::size_t>(layout_.pd_words); }
  std::string explain_m2s(std::span<const Word> w) const override {
    if (w.empty()) return "no process data";
    std::string s = "control " + drivecom::explain_control_word(drivecom::DeviceType::mc6000, w[0], prev_control_);
    prev_control_ = w[0];
    const auto n = static_cast<std::size_t>(layout_.reference_words);
    if (n > 0 && w.size() > n) {
      s += "; reference " + num(interbus::mc6000::decode_reference(layout_, w.subspan(1, n))) +
           " rpm";
    }
    return s;
  }
  std::string explain_s2m(std::span<const Word> w) const override {
    if (w.empty()) return "no process data";
    std::string s = "status " + drivecom::explain_status_word(drivecom::DeviceType::mc6000, w[0]);
    const auto n = static_cast<std::size_t>(layout_.actual_words);
    if (n > 0 && w.size() > n) {
      const auto a = interbus::mc6000::decode_actual(layout_, w.subspan(1, n));
      s += "; actual " + num(a.value) + " rpm";
      if (layout_.ibcnf == interbus::mc6000::Ibcnf::speed_torque) s += ", torque " + num(a.torque);
    }
    return s;
  }

 private:
  interbus::mc6000::Layout layout_;
  mutable Word prev_control_ = 0;  // explains the reset-fault edge row by row
};

// --- VF1000 pd --------------------------------------------------------------------------------

class Vf1000Master final : public trace::MasterSide {
 public:
  std::size_t m2s_words() const override { return Vf1000PdDevice::kWords; }
  std::size_t s2m_words() const override { return Vf1000PdDevice::kWords; }
  void initial(std::span<Word> m2s) override { master_.initial(m2s); }
  void submit(const Request& r) override { master_.sequencer().request(target_of(r.target), now_); }
  void step(std::span<const Word> s2m, std::span<const WordPattern> row_m2s,
            std::span<Word> m2s) override {
    now_ += kVf1000SamplePeriod;
    // Application data from the file: the ramp and direction bits of the control word and the
    // reference word; the DRIVECOM bits are computed by the sequencer.
    if (row_m2s[1].is_exact()) {
      const auto b = row_m2s[0].is_exact() ? drivecom::decode_vf1000_bits(row_m2s[0].value)
                                            : drivecom::Vf1000ControlBits{};
      const double hz = vf1000_reference_hz(row_m2s[1].value);
      master_.set_frequency_hz(b.stl && !b.str ? -hz : hz);
    }
    if (row_m2s[0].is_exact()) master_.sequencer().set_application_bits(row_m2s[0].value);
    master_.cycle(s2m, m2s, now_, 0);
  }
  std::optional<Outcome> outcome() const override { return outcome_of(master_.sequencer().report()); }

 private:
  Vf1000PdMaster master_;
  Time now_{0};
};

class Vf1000Explainer final : public trace::Explainer {
 public:
  std::size_t m2s_words() const override { return Vf1000PdDevice::kWords; }
  std::size_t s2m_words() const override { return Vf1000PdDevice::kWords; }
  std::string explain_m2s(std::span<const Word> w) const override {
    std::string s = "control " + drivecom::explain_control_word(drivecom::DeviceType::vf1000, w[0], prev_control_);
    prev_control_ = w[0];
    s += "; reference " + hz(vf1000_reference_hz(w[1])) + " Hz";
    char buf[16];
    std::snprintf(buf, sizeof buf, "%04X", static_cast<unsigned>(w[2]));
    s += "; comm " + std::string(buf);
    return s;
  }
  std::string explain_s2m(std::span<const Word> w) const override {
    std::string s = "status " + drivecom::explain_status_word(drivecom::DeviceType::vf1000, w[0]);
    s += "; actual " + hz(vf1000_actual_hz(w[1])) + " Hz";
    char buf[16];
    std::snprintf(buf, sizeof buf, "%04X", static_cast<unsigned>(w[2]));
    s += "; comm " + std::string(buf);
    return s;
  }

 private:
  mutable Word prev_control_ = 0;
};

[[noreturn]] void unsupported(const trace::Trace& t) {
  const Header& h = t.header;
  std::string why;
  if (h.words == WordsKind::comm && h.device != DeviceType::vf1000) why = " (the communication word is the VF1000's)";
  if (h.words == WordsKind::pcp && h.device != DeviceType::mc6000) why = " (PCP is the MC6000's)";
  throw TraceError(t.file, h.lines.words,
                   "words: " + std::string(to_string(h.words)) + " is not served for device " +
                       std::string(to_string(h.device)) + why);
}

// The channel adapters report a header they cannot serve with std::invalid_argument; the user
// gets it as FILE:LINE naming the request (or the words header).
template <typename F>
auto channel_adapter(const trace::Trace& t, F make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    const auto& l = t.header.lines;
    throw TraceError(t.file, l.request != 0 ? l.request : l.words, e.what());
  }
}

bool is_comm(const Header& h) { return h.words == WordsKind::comm && h.device == DeviceType::vf1000; }
bool is_pcp(const Header& h) { return h.words == WordsKind::pcp && h.device == DeviceType::mc6000; }

}  // namespace

Duration pd_step_period(DeviceType d) {
  return d == DeviceType::vf1000 ? kVf1000SamplePeriod : kMc6000SamplePeriod;
}

std::unique_ptr<trace::DeviceSide> make_device_side(const trace::Trace& t) {
  const Header& h = t.header;
  if (h.words == WordsKind::pd) {
    if (h.device == DeviceType::mc6000) {
      const auto l = layout_of(t);
      return std::make_unique<SimulatedDeviceSide<Mc6000Device>>(static_cast<std::size_t>(l.pd_words),
                                                                  kMc6000SamplePeriod, mc6000_config(l), start_of(h));
    }
    return std::make_unique<SimulatedDeviceSide<Vf1000Device>>(Vf1000Device::kWords, kVf1000SamplePeriod,
                                                               Vf1000DeviceConfig{}, start_of(h));
  }
  if (is_comm(h)) return channel_adapter(t, [&] { return vf1000_channel::make_comm_device_side(h); });
  if (is_pcp(h)) return channel_adapter(t, [&] { return pcp::make_pcp_device_side(h); });
  unsupported(t);
}

std::unique_ptr<trace::MasterSide> make_master_side(const trace::Trace& t) {
  const Header& h = t.header;
  if (h.words == WordsKind::pd) {
    require_state_request(t);
    if (h.device == DeviceType::mc6000) return std::make_unique<Mc6000Master>(layout_of(t));
    return std::make_unique<Vf1000Master>();
  }
  if (is_comm(h)) return channel_adapter(t, [&] { return vf1000_channel::make_comm_master_side(h); });
  if (is_pcp(h)) return channel_adapter(t, [&] { return pcp::make_pcp_master_side(h); });
  unsupported(t);
}

std::unique_ptr<trace::Explainer> make_explainer(const trace::Trace& t) {
  const Header& h = t.header;
  if (h.words == WordsKind::pd) {
    if (h.device == DeviceType::mc6000) return std::make_unique<Mc6000Explainer>(layout_of(t));
    return std::make_unique<Vf1000Explainer>();
  }
  if (is_comm(h)) return vf1000_channel::make_comm_explainer();
  if (is_pcp(h)) return channel_adapter(t, [&] { return pcp::make_pcp_explainer(h); });
  unsupported(t);
}

}  // namespace ibs::devices
