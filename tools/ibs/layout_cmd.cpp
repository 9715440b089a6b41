// `ibs layout`: a drive's ID code and the meaning of each of its process-data words.
// MC6000: 405-SUPI splits the four bus words between process data and PCP (seed 001 3.2.2),
// 406-IBCNF says how the reference and actual words read (3.2.3, 5.3.3). VF1000: three words,
// 33BH (3.1.2), reference in 0.05 Hz (5.2.3), communication word in word 3 (4.1.2).
#include <array>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bus_commands.hpp"
#include "commands.hpp"
#include "ibs/interbus/bus_config.hpp"
#include "ibs/interbus/cycle_time.hpp"
#include "ibs/interbus/id_code.hpp"
#include "ibs/interbus/mc6000_layout.hpp"

namespace ibs::cli {

namespace {

namespace mc = interbus::mc6000;
using Json = nlohmann::ordered_json;

struct WordMeaning {
  int word;          // 1-based, as the manual counts
  std::string role;  // machine-readable: control_word, reference_q16_high, ...
  std::string meaning;
};

// What one device adds to T_cycle: its bytes to N, 1 to M on the remote bus, and the line time
// of those bits at each baud rate.
struct CycleShare {
  std::size_t data_bytes = 0;
  std::size_t remote_devices = 0;
  double line_bits = 0.0;
  Duration at_500k{0};
  Duration at_2m{0};
};

struct LayoutReport {
  std::string device;  // "mc6000", "vf1000"
  std::string title;
  std::optional<int> supi;
  std::optional<int> ibcnf;
  std::string ibcnf_meaning;
  interbus::Device placed;  // the device as a one-device bus configuration places it
  bool exchanges_data = true;
  std::vector<WordMeaning> out_words;  // master -> device
  std::vector<WordMeaning> in_words;   // device -> master
  std::string pcp;
  CycleShare share;
};

const char* bus_name(interbus::BusKind b) {
  return b == interbus::BusKind::local ? "local" : "remote";
}

CycleShare cycle_share(const interbus::BusConfig& c) {
  CycleShare s;
  const interbus::RingLoad load = interbus::ring_load(c);
  const interbus::CycleTimeParams p500 = interbus::params_for(interbus::BaudRate::kbit500);
  const interbus::CycleTimeParams p2m = interbus::params_for(interbus::BaudRate::mbit2);
  s.data_bytes = load.data_bytes;
  s.remote_devices = load.remote_devices;
  s.line_bits = p500.line_bits_per_byte * static_cast<double>(load.data_bytes) +
                p500.bits_per_remote_device * static_cast<double>(load.remote_devices);
  // The difference to an empty ring: the formula's own rounding, SW and overhead cancel.
  s.at_500k = interbus::cycle_time(load, p500) - interbus::cycle_time(interbus::RingLoad{}, p500);
  s.at_2m = interbus::cycle_time(load, p2m) - interbus::cycle_time(interbus::RingLoad{}, p2m);
  return s;
}

void place(LayoutReport& r, const std::string& name, Word id, interbus::BusKind bus) {
  const std::array<interbus::DeviceSpec, 1> ring{{{name, interbus::IdCode{id}, bus}}};
  const interbus::BusConfig c = interbus::make_bus_config(ring);
  r.placed = c.devices.front();
  r.share = cycle_share(c);
}

const char* ibcnf_meaning(mc::Ibcnf c) {
  switch (c) {
    case mc::Ibcnf::none:
      return "no reference transfer, all actual words 0";
    case mc::Ibcnf::word16:
      return "16-bit reference and actual";
    case mc::Ibcnf::q16:
      return "32-bit Q16 reference and actual, high word first";
    case mc::Ibcnf::speed_torque:
      return "32-bit Q16 speed reference; actual 16-bit speed and 16-bit torque";
    case mc::Ibcnf::lisim:
      return "modified LISIM software";
  }
  return "?";
}

LayoutReport mc6000_report(const mc::Layout& l) {
  LayoutReport r;
  r.device = "mc6000";
  r.supi = l.supi;
  r.ibcnf = static_cast<int>(l.ibcnf);
  r.ibcnf_meaning = ibcnf_meaning(l.ibcnf);
  r.exchanges_data = l.exchanges_data;
  const interbus::BusKind bus =
      l.bus == mc::BusKind::local ? interbus::BusKind::local : interbus::BusKind::remote;
  place(r, "mc6000", l.id_code, bus);
  r.title = "MC6000 servo: 405-SUPI = " + std::to_string(l.supi) +
            ", 406-IBCNF = " + std::to_string(static_cast<int>(l.ibcnf)) + " (" +
            (l.exchanges_data ? r.ibcnf_meaning : std::string("no effect without data exchange")) +
            "), " + bus_name(bus) + " bus";

  if (!l.exchanges_data) {
    const std::string none =
        "no data exchange: 405-SUPI = 0 reports configuration 4 and the INTERBUS card loops "
        "without exchanging data with the servo (seed 001 3.2.2)";
    r.out_words.push_back({1, "no_data", none});
    r.in_words.push_back({1, "no_data", none});
    r.pcp = "none (405-SUPI = 0)";
    return r;
  }

  const std::string unit = "torque, speed or position by the control mode (rpm in speed control)";
  const std::string q16 =
      "as value x 65536, signed 32-bit, high word first (seed 001 5.3.3, 5.3.4)";
  if (l.pd_words >= 1) {
    r.out_words.push_back(
        {1, "control_word", "control word, DRIVECOM Profile 20 (seed 001 5.3.1)"});
    r.in_words.push_back({1, "status_word", "status word, DRIVECOM Profile 20 (seed 001 5.3.2)"});
  }
  switch (l.ibcnf) {
    case mc::Ibcnf::word16:
      r.out_words.push_back({2, "reference",
                             "reference, 16-bit signed, " + unit +
                                 "; integer units (modelling choice: the manual "
                                 "gives no 16-bit scaling)"});
      r.in_words.push_back(
          {2, "actual",
           "actual value, 16-bit signed, " + unit + "; integer units (modelling choice)"});
      break;
    case mc::Ibcnf::q16:
      r.out_words.push_back(
          {2, "reference_q16_high", "reference, Q16 high word: " + unit + ", " + q16});
      r.out_words.push_back({3, "reference_q16_low", "reference, Q16 low word"});
      r.in_words.push_back(
          {2, "actual_q16_high", "actual value, Q16 high word: " + unit + ", " + q16});
      r.in_words.push_back({3, "actual_q16_low", "actual value, Q16 low word"});
      break;
    case mc::Ibcnf::speed_torque:
      r.out_words.push_back({2, "speed_reference_q16_high",
                             "speed reference, Q16 high word: rpm x 65536, signed 32-bit, high "
                             "word first (seed 001 3.2.3, 5.3.4)"});
      r.out_words.push_back({3, "speed_reference_q16_low", "speed reference, Q16 low word"});
      r.in_words.push_back(
          {2, "actual_speed", "actual speed, 16-bit signed, rpm (seed 001 3.2.3)"});
      r.in_words.push_back({3, "actual_torque", "actual torque, 16-bit signed (seed 001 3.2.3)"});
      break;
    case mc::Ibcnf::none:
    case mc::Ibcnf::lisim:
      break;
  }
  // The process-data words 406-IBCNF leaves without a meaning.
  for (int w = 2 + l.reference_words; w <= l.pd_words; ++w) {
    r.out_words.push_back(
        {w, "unused",
         l.ibcnf == mc::Ibcnf::none
             ? "not used (406-IBCNF = 0: no reference transfer)"
             : "not used by 406-IBCNF = " + std::to_string(static_cast<int>(l.ibcnf))});
  }
  for (int w = 2 + l.actual_words; w <= l.pd_words; ++w) {
    r.in_words.push_back(
        {w, l.ibcnf == mc::Ibcnf::none ? "zero" : "unused",
         l.ibcnf == mc::Ibcnf::none
             ? "always 0 (406-IBCNF = 0, seed 001 3.2.3)"
             : "not used by 406-IBCNF = " + std::to_string(static_cast<int>(l.ibcnf))});
  }
  r.pcp = l.pcp_words == 0 ? "none"
                           : std::to_string(l.pcp_words) + (l.pcp_words == 1 ? " word" : " words") +
                                 " each way, PCP 2.0 parameter channel (seed 001 3.2.2)";
  return r;
}

LayoutReport vf1000_report() {
  LayoutReport r;
  r.device = "vf1000";
  r.title = "VF1000 frequency inverter: three words, ID code 33BH (seed 001 3.1.2)";
  place(r, "vf1000", 0x33B, interbus::BusKind::remote);
  r.out_words = {
      {1, "control_word", "control word, DRIVECOM Profile 20 (seed 001 5.2.1)"},
      {2, "frequency_reference",
       "frequency reference, 0.05 Hz per bit, absolute value; the direction comes from control "
       "word bits 14 STL / 15 STR (seed 001 5.2.3)"},
      {3, "communication_word",
       "communication word to the inverter: the parameter channel (seed 001 4.1.2.1)"},
  };
  r.in_words = {
      {1, "status_word", "status word, DRIVECOM Profile 20 (seed 001 5.2.2)"},
      {2, "actual_frequency",
       "actual frequency, 0.05 Hz per bit, signed (modelling choice: the manual does not define "
       "this word)"},
      {3, "communication_word", "communication word from the inverter (seed 001 4.1.2.2)"},
  };
  r.pcp = "none: parameters travel in the communication word (word 3)";
  return r;
}

Json words_json(const std::vector<WordMeaning>& words) {
  Json a = Json::array();
  for (const WordMeaning& w : words) {
    a.push_back(Json{{"word", w.word}, {"role", w.role}, {"meaning", w.meaning}});
  }
  return a;
}

void print_json(const LayoutReport& r, std::ostream& out) {
  Json j;
  j["device"] = r.device;
  if (r.supi) j["supi"] = *r.supi;
  if (r.ibcnf) {
    j["ibcnf"] = *r.ibcnf;
    j["ibcnf_meaning"] = r.ibcnf_meaning;
  }
  j["bus"] = bus_name(r.placed.bus);
  j["id_code"] = interbus::to_hex(r.placed.id);
  j["id_code_value"] = r.placed.id.raw;
  j["id_code_description"] = interbus::describe(r.placed.id);
  j["exchanges_data"] = r.exchanges_data;
  j["ring_words"] = r.placed.ring_words;
  j["pd_words"] = r.placed.ring_words - r.placed.pcp_words;
  j["pcp_words"] = r.placed.pcp_words;
  j["output_words"] = words_json(r.out_words);
  j["input_words"] = words_json(r.in_words);
  j["pcp"] = r.pcp;
  j["cycle_time_contribution"] = Json{
      {"data_bytes", r.share.data_bytes},    {"remote_devices", r.share.remote_devices},
      {"line_bits", r.share.line_bits},      {"time_ns_500k", r.share.at_500k.count()},
      {"time_ns_2m", r.share.at_2m.count()},
  };
  out << j.dump(2) << "\n";
}

void print_words(const std::vector<WordMeaning>& words, std::ostream& out) {
  if (words.empty()) out << "  no process data (every word is PCP)\n";
  for (const WordMeaning& w : words) {
    out << "  word " << w.word << "  " << w.meaning << "\n";
  }
}

void print_text(const LayoutReport& r, std::ostream& out) {
  const interbus::Device& d = r.placed;
  out << r.title << "\n";
  out << "ID code " << interbus::describe(d.id) << "\n";
  out << "on the ring: " << d.ring_words << (d.ring_words == 1 ? " word" : " words") << " ("
      << d.ring_words - d.pcp_words << " process data + " << d.pcp_words << " PCP), "
      << bus_name(d.bus) << " bus\n";
  out << "master -> device (output image):\n";
  print_words(r.out_words, out);
  out << "device -> master (input image):\n";
  print_words(r.in_words, out);
  out << "PCP channel: " << r.pcp << "\n";
  const interbus::CycleTimeParams p;
  out << "cycle time contribution: N += " << r.share.data_bytes
      << " bytes, M += " << r.share.remote_devices << ": " << format_number(p.line_bits_per_byte)
      << " * " << r.share.data_bytes << " + " << format_number(p.bits_per_remote_device) << " * "
      << r.share.remote_devices << " = " << format_number(r.share.line_bits)
      << " bit times = " << format_us(r.share.at_500k) << " us at 500 kbit/s, "
      << format_us(r.share.at_2m) << " us at 2 Mbit/s\n";
}

}  // namespace

int layout_command(const LayoutOptions& o, std::ostream& out, std::ostream& err) {
  try {
    LayoutReport r;
    if (o.device == "mc6000") {
      if (!o.supi || !o.ibcnf) {
        err << "ibs layout: mc6000 needs --supi (405-SUPI, 0..12) and --ibcnf (406-IBCNF, "
               "0..4)\n";
        return kExitBadInput;
      }
      mc::BusKind bus = mc::BusKind::remote;
      if (o.bus) {
        if (*o.bus == "local") {
          bus = mc::BusKind::local;
        } else if (*o.bus != "remote") {
          err << "ibs layout: --bus '" << *o.bus << "' is neither local nor remote\n";
          return kExitBadInput;
        }
      }
      r = mc6000_report(mc::make_layout(*o.supi, *o.ibcnf, bus));
    } else if (o.device == "vf1000") {
      if (o.supi || o.ibcnf || o.bus) {
        err << "ibs layout: --supi, --ibcnf and --bus apply to the mc6000 only; the VF1000 "
               "always reports 33BH on the remote bus (seed 001 3.1.2)\n";
        return kExitBadInput;
      }
      r = vf1000_report();
    } else {
      err << "ibs layout: unknown device '" << o.device << "' (mc6000 or vf1000)\n";
      return kExitBadInput;
    }
    if (o.json) {
      print_json(r, out);
    } else {
      print_text(r, out);
    }
    return kExitOk;
  } catch (const mc::LayoutError& e) {
    err << "ibs layout: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const interbus::ConfigError& e) {
    err << "ibs layout: " << e.what() << "\n";
    return kExitBadInput;
  }
}

int layout_command(const LayoutOptions& options) {
  return layout_command(options, std::cout, std::cerr);
}

}  // namespace ibs::cli
