// `words: pd` traces of the VF1000 (../shared/specs/trace-format.md): the master side and the
// explainer. The device side is the emulator itself (the registry's trace adapters run it).
#include "ibs/devices/vf1000/pd_trace.hpp"

#include <cstdio>
#include <string>

#include "ibs/base/number_text.hpp"
#include "ibs/devices/trace_support.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/devices/vf1000/pd_master.hpp"

namespace ibs::devices::vf1000 {

namespace {

std::string hz(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string hex4(Word w) { return hex_text(w, 4); }

class Master final : public trace::MasterSide {
 public:
  explicit Master(Duration step) : step_(step) {}
  std::size_t m2s_words() const override { return kWords; }
  std::size_t s2m_words() const override { return kWords; }
  void initial(std::span<Word> m2s) override { master_.initial(m2s); }
  void submit(const trace::Request& r) override {
    if (const auto t = drivecom::target_named(r.target)) master_.sequencer().request(*t, now_);
  }
  void step(std::span<const Word> s2m, std::span<const trace::WordPattern> row_m2s,
            std::span<Word> m2s) override {
    now_ += step_;
    // Application data from the file: the ramp and direction bits of the control word and the
    // reference word; the DRIVECOM bits are computed by the sequencer.
    if (row_m2s[1].is_exact()) {
      const auto b = row_m2s[0].is_exact() ? decode_control_bits(row_m2s[0].value) : ControlBits{};
      const double f = reference_hz(row_m2s[1].value);
      master_.set_frequency_hz(b.stl && !b.str ? -f : f);
    }
    if (row_m2s[0].is_exact()) master_.sequencer().set_application_bits(row_m2s[0].value);
    master_.cycle(s2m, m2s, now_, 0);
  }
  std::optional<trace::Outcome> outcome() const override { return trace_outcome(master_.sequencer().report()); }

 private:
  Duration step_;
  Vf1000PdMaster master_;
  Time now_{0};
};

class Explainer final : public trace::Explainer {
 public:
  std::size_t m2s_words() const override { return kWords; }
  std::size_t s2m_words() const override { return kWords; }
  // `! write PNR VALUE` (another channel's write): the parameter's name from the drive's table.
  std::string explain_write(std::uint16_t parameter, std::int64_t value) const override {
    for (const auto& p : parameters()) {
      if (p.number == parameter) return std::to_string(parameter) + "-" + std::string(p.name) + " = " + std::to_string(value);
    }
    return "parameter " + std::to_string(parameter) + " = " + std::to_string(value);
  }
  std::string explain_m2s(std::span<const Word> w) const override {
    std::string s = "control " + explain_control_word(w[0], prev_control_);
    prev_control_ = w[0];
    s += "; reference " + hz(reference_hz(w[1])) + " Hz";
    s += "; comm " + hex4(w[2]);
    return s;
  }
  std::string explain_s2m(std::span<const Word> w) const override {
    std::string s = "status " + explain_status_word(w[0]);
    s += "; actual " + hz(actual_hz(w[1])) + " Hz";
    s += "; comm " + hex4(w[2]);
    return s;
  }

 private:
  mutable Word prev_control_ = 0;  // explains the reset-fault edge row by row
};

}  // namespace

std::unique_ptr<trace::MasterSide> make_pd_master(Duration step) { return std::make_unique<Master>(step); }
std::unique_ptr<trace::Explainer> make_pd_explainer() { return std::make_unique<Explainer>(); }

}  // namespace ibs::devices::vf1000
