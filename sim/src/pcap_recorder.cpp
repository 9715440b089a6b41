#include "ibs/sim/pcap_recorder.hpp"

#include <limits>

#include "ibs/devices/registry.hpp"


namespace ibs::sim {

namespace capture {

namespace {

void put8(std::vector<std::uint8_t>& b, std::size_t v) { b.push_back(static_cast<std::uint8_t>(v)); }
void put16(std::vector<std::uint8_t>& b, std::size_t v) {
  b.push_back(static_cast<std::uint8_t>(v >> 8U));
  b.push_back(static_cast<std::uint8_t>(v));
}
void put32(std::vector<std::uint8_t>& b, std::uint64_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) b.push_back(static_cast<std::uint8_t>(v >> static_cast<unsigned>(shift)));
}
void put_words(std::vector<std::uint8_t>& b, std::span<const Word> words) {
  for (const Word w : words) {
    b.push_back(high_byte(w));
    b.push_back(low_byte(w));
  }
}
void put_text(std::vector<std::uint8_t>& b, const std::string& text, const char* what, const std::string& device) {
  if (text.size() > 255) {
    throw std::invalid_argument("capture: device '" + device + "': " + what + " longer than 255 bytes");
  }
  put8(b, text.size());
  b.insert(b.end(), text.begin(), text.end());
}
void check16(std::size_t v, const std::string& what) {
  if (v > 0xFFFF) throw std::invalid_argument("capture: " + what + " = " + std::to_string(v) + " exceeds 65535");
}
void check_slice(const interbus::Slice& s, std::size_t area, const std::string& device, const char* name) {
  if (s.end() > area) {
    throw std::invalid_argument("capture: device '" + device + "': " + name + " slice " + std::to_string(s.offset) +
                                "+" + std::to_string(s.length) + " lies outside the area of " +
                                std::to_string(area) + " words");
  }
}

void put_header(std::vector<std::uint8_t>& b, std::uint8_t type) {
  b.push_back(kMagic0);
  b.push_back(kMagic1);
  b.push_back(kVersion);
  b.push_back(type);
}

}  // namespace

std::vector<std::uint8_t> encode_configuration(const Configuration& c) {
  check16(c.devices.size(), "devices");
  check16(c.in_words, "IN words");
  check16(c.out_words, "OUT words");
  check16(c.pcp_words, "PCP words");
  std::vector<std::uint8_t> b;
  put_header(b, kTypeConfiguration);
  put16(b, c.devices.size());
  put16(b, c.in_words);
  put16(b, c.out_words);
  put16(b, c.pcp_words);
  const auto ns = c.cycle_time.count();
  put32(b, ns < 0 ? 0U : static_cast<std::uint64_t>(std::min<std::int64_t>(ns, 0xFFFFFFFF)));
  put8(b, static_cast<std::size_t>(c.source));
  put8(b, 0);
  put16(b, 0);
  for (const Device& d : c.devices) {
    check_slice(d.in, c.in_words, d.name, "IN");
    check_slice(d.out, c.out_words, d.name, "OUT");
    check_slice(d.pcp, c.pcp_words, d.name, "PCP");
    put8(b, static_cast<std::size_t>(d.kind));
    put8(b, d.first_word);
    put16(b, d.id_code);
    put16(b, d.in.offset);
    put16(b, d.in.length);
    put16(b, d.out.offset);
    put16(b, d.out.length);
    put16(b, d.pcp.offset);
    put16(b, d.pcp.length);
    put8(b, static_cast<std::size_t>(d.values));
    put8(b, d.layout[0]);
    put8(b, d.layout[1]);
    put_text(b, d.name, "the name is", d.name);
    put_text(b, d.unit, "the unit is", d.name);
  }
  return b;
}

void encode_cycle(const Configuration& c, std::uint32_t cycle, bool valid, const interbus::ProcessImage& image,
                  std::vector<std::uint8_t>& out) {
  out.clear();
  put_header(out, kTypeCycle);
  put32(out, cycle);
  put8(out, valid ? 1U : 0U);
  put8(out, 0);
  put16(out, c.out_words);
  put16(out, c.in_words);
  put16(out, c.pcp_words);
  put_words(out, std::span<const Word>(image.out).first(c.out_words));
  put_words(out, std::span<const Word>(image.in).first(c.in_words));
  put_words(out, std::span<const Word>(image.pcp_out).first(c.pcp_words));
  put_words(out, std::span<const Word>(image.pcp_in).first(c.pcp_words));
}

Device describe(const std::string& name, const std::string& kind_name, const devices::DeviceSettings& settings) {
  Device d;
  d.name = name;
  const devices::DriveKind* kind = devices::find_drive_kind(kind_name);
  if (kind == nullptr) return d;
  const devices::Configuration c = (*kind)->configure(settings);
  d.id_code = c.id_code.raw;
  d.unit = std::string((*kind)->facts().unit);
  // The kind number and value format the drive declares for the format (docs/pcap.md,
  // "Configuration"); a drive without them is "other" to the dissector.
  if (const devices::CaptureFace* capture = kind->capture; capture != nullptr) {
    d.kind = capture->kind;
    const devices::CaptureFormat f = capture->format(settings);
    d.values = f.values;
    d.layout = f.layout;
  }
  return d;
}

Configuration configuration_of(const Simulator& sim, const Scenario& scenario) {
  const interbus::BusConfig& bus = sim.bus();
  if (bus.devices.size() != scenario.devices.size()) {
    throw std::invalid_argument("capture: the scenario does not describe the simulator's ring");
  }
  Configuration c;
  c.source = Source::run;
  c.cycle_time = sim.cycle_time();
  c.in_words = bus.in_words;
  c.out_words = bus.out_words;
  c.pcp_words = bus.pcp_words;
  for (std::size_t i = 0; i < bus.devices.size(); ++i) {
    const interbus::Device& placed = bus.devices[i];
    const DeviceConfig& dc = scenario.devices[i];
    Device d = describe(placed.name, dc.kind, device_settings(dc));
    d.id_code = placed.id.raw;
    d.in = placed.in;
    d.out = placed.out;
    d.pcp = placed.pcp;
    c.devices.push_back(std::move(d));
  }
  return c;
}

}  // namespace capture

PcapRecorder::PcapRecorder(Simulator& sim, const Scenario& scenario, std::ostream& out, Time epoch)
    : config_(capture::configuration_of(sim, scenario)), file_(out, kLinktypeInterbus, epoch) {
  file_.write(Time{0}, capture::encode_configuration(config_));
}

void PcapRecorder::on_cycle(Time at, bool valid, const interbus::ProcessImage& image) {
  ++cycle_;
  capture::encode_cycle(config_, cycle_, valid, image, buffer_);
  file_.write(at, buffer_);
}

void PcapRecorder::finish() { file_.close(); }

}  // namespace ibs::sim
