// `words: pd` traces of the MC6000 (../shared/specs/trace-format.md): the master side and the
// explainer. The device side is the emulator itself (the registry's trace adapters run it).
#include "ibs/devices/mc6000/pd_trace.hpp"

#include <cstdio>
#include <string>

#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/pd_master.hpp"
#include "ibs/devices/trace_support.hpp"

namespace ibs::devices::mc6000 {

namespace {

// Up to `digits` significant digits, as %g would.
std::string num(double v, int digits = 7) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

class Master final : public trace::MasterSide {
 public:
  Master(const Layout& l, Duration step) : step_(step), master_(l) {}
  std::size_t m2s_words() const override { return static_cast<std::size_t>(master_.layout().pd_words); }
  std::size_t s2m_words() const override { return m2s_words(); }
  void initial(std::span<Word> m2s) override { master_.initial(m2s); }
  void submit(const trace::Request& r) override {
    if (const auto t = drivecom::target_named(r.target)) master_.sequencer().request(*t, now_);
  }
  void step(std::span<const Word> s2m, std::span<const trace::WordPattern> row_m2s,
            std::span<Word> m2s) override {
    now_ += step_;
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
      if (exact) master_.set_reference_rpm(decode_reference(l, std::span<const Word>(ref, n)));
    }
    master_.cycle(s2m, m2s, now_);
  }
  std::optional<trace::Outcome> outcome() const override { return trace_outcome(master_.sequencer().report()); }

 private:
  Duration step_;
  Mc6000PdMaster master_;
  Time now_{0};
};

class Explainer final : public trace::Explainer {
 public:
  explicit Explainer(const Layout& l) : layout_(l) {}
  std::size_t m2s_words() const override { return static_cast<std::size_t>(layout_.pd_words); }
  std::size_t s2m_words() const override { return static_cast<std::size_t>(layout_.pd_words); }
  // `! write PNR VALUE` (another channel's write): the parameter's name from the drive's table.
  std::string explain_write(std::uint16_t parameter, std::int64_t value) const override {
    for (const auto& p : parameters()) {
      if (p.number == parameter) return std::to_string(parameter) + "-" + std::string(p.name) + " = " + std::to_string(value);
    }
    return "parameter " + std::to_string(parameter) + " = " + std::to_string(value);
  }
  std::string explain_m2s(std::span<const Word> w) const override {
    if (w.empty()) return "no process data";
    std::string s = "control " + explain_control_word(w[0], prev_control_);
    prev_control_ = w[0];
    const auto n = static_cast<std::size_t>(layout_.reference_words);
    if (n > 0 && w.size() > n) s += "; reference " + num(decode_reference(layout_, w.subspan(1, n))) + " rpm";
    return s;
  }
  std::string explain_s2m(std::span<const Word> w) const override {
    if (w.empty()) return "no process data";
    std::string s = "status " + explain_status_word(w[0]);
    const auto n = static_cast<std::size_t>(layout_.actual_words);
    if (n > 0 && w.size() > n) {
      const auto a = decode_actual(layout_, w.subspan(1, n));
      s += "; actual " + num(a.value) + " rpm";
      if (layout_.ibcnf == Ibcnf::speed_torque) s += ", torque " + num(a.torque);
    }
    return s;
  }

 private:
  Layout layout_;
  mutable Word prev_control_ = 0;  // explains the reset-fault edge row by row
};

}  // namespace

std::unique_ptr<trace::MasterSide> make_pd_master(const Layout& l, Duration step) { return std::make_unique<Master>(l, step); }
std::unique_ptr<trace::Explainer> make_pd_explainer(const Layout& l) { return std::make_unique<Explainer>(l); }

}  // namespace ibs::devices::mc6000
