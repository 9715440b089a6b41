// The VF1000 drive core's settled shortcut: advance() to the time it was last advanced to, with
// nothing changed since, returns at once (the LUSTBUS face calls it for the telegram and again for
// the ENQUIRY at the same time). Compared with advance_fully(), the general path, on random runs of
// every mutator the drive has -- values (84-SIOT short enough to run out, 5.2; serial control,
// 7.1), writes, faults, starts and resets, both faces attaching and leaving, INTERBUS samples, the
// serial telegrams that feed the watchdog -- at times that often repeat: after every step the two
// drives must look the same in everything they show.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "ibs/devices/vf1000/drive.hpp"

namespace ibs::devices::vf1000 {
namespace {

using namespace std::chrono_literals;

struct Snapshot {
  Word status;
  std::uint8_t siof;
  drivecom::State state;
  double frequency;
  double setpoint;
  Word status_word;
  std::uint32_t starts, software_resets;
  bool starting, serial_fault, e_ibs, ib_tripped, external_fault, powered;
  Time ready_at;
  std::array<Word, Vf1000PdDevice::kWords> out;
  std::vector<Word> ram, eeprom;
  bool operator==(const Snapshot&) const = default;
};

Snapshot snapshot(const Drive& d) {
  Snapshot s{};
  s.status = d.status();
  s.siof = d.siof();
  s.state = d.state();
  s.frequency = d.frequency_hz();
  s.setpoint = d.pd().setpoint_hz();
  s.status_word = d.pd().status_word();
  s.starts = d.starts();
  s.software_resets = d.software_resets();
  s.starting = d.starting();
  s.serial_fault = d.serial_watchdog_fault();
  s.e_ibs = d.e_ibs();
  s.ib_tripped = d.interbus_watchdog_tripped();
  s.external_fault = d.external_fault();
  s.powered = d.powered();
  s.ready_at = d.ready_at();
  d.output(s.out);
  for (std::size_t i = 0; i < d.table().params().size(); ++i) {
    s.ram.push_back(d.store().value(i));
    s.eeprom.push_back(d.store().eeprom_value(i));
  }
  return s;
}

class Twins {
 public:
  Twins(const DriveConfig& c, DeviceStart start) : a_(c, start, Time{0}), b_(c, start, Time{0}) {}
  // The same step on both: `a` through advance(), `b` through advance_fully().
  template <typename F>
  void both(F f) {
    f(a_);
    f(b_);
  }
  void advance(Time t) {
    a_.advance(t);
    b_.advance_fully(t);
  }
  [[nodiscard]] bool same() const { return snapshot(a_) == snapshot(b_); }
  [[nodiscard]] const Drive& a() const { return a_; }

 private:
  Drive a_;
  Drive b_;
};

TEST(Vf1000DriveShortcuts, ASettledAdvanceDoesWhatTheFullOneDoes) {
  std::mt19937 rng(2613);
  auto pick = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); };
  int skipped_chances = 0;
  int trips = 0;
  for (int run = 0; run < 60; ++run) {
    DriveConfig cfg;
    cfg.interbus_software = pick(2) == 0;
    cfg.pd.reset_time = pick(3) == 0 ? Duration{0} : Duration{std::chrono::milliseconds(pick(50))};
    cfg.pd.init_time = Duration{std::chrono::milliseconds(pick(30))};
    const DeviceStart start = std::array{DeviceStart::power_on, DeviceStart::initialised,
                                         DeviceStart::operational, DeviceStart::fault}[static_cast<std::size_t>(pick(4))];
    Twins d(cfg, start);
    d.both([](Drive& x) { x.attach(Face::serial); });
    bool interbus = false;
    Time t{0};
    bool last_was_advance = false;
    for (int step = 0; step < 1500; ++step) {
      switch (pick(4)) {  // the time: often the same again
        case 0: break;
        case 1: t += Duration{pick(1000) + 1}; break;
        case 2: t += std::chrono::microseconds(pick(9000) + 1); break;
        default: t += std::chrono::milliseconds(pick(60) + 1); break;
      }
      const int op = pick(40);
      if (op < 14) {
        d.advance(t);
        if (last_was_advance) ++skipped_chances;
        last_was_advance = true;
      } else if (op < 20) {  // the LUSTBUS face's order: advance, feed the watchdog, advance
        d.advance(t);
        d.both([&](Drive& x) { x.serial_telegram(t); });
        d.advance(t);
        ++skipped_chances;
        last_was_advance = true;
      } else {
        last_was_advance = false;
        switch (op) {
          case 20:  // a telegram at another time (earlier or later) between two advances
            d.advance(t);
            d.both([&, dt = Duration{std::chrono::milliseconds(pick(40)) - 20ms}](Drive& x) {
              x.serial_telegram(t + dt);
            });
            d.advance(t);
            break;
          case 21:
          case 22: {  // 84-SIOT short enough to run out, or off
            const Word v = static_cast<Word>(pick(3) == 0 ? 0 : pick(80) + 1);
            d.both([&](Drive& x) { x.set_value(pnr::kSiot, v); });
            break;
          }
          case 23: {  // serial control (7.1) and its inputs
            const Word m = static_cast<Word>(pick(3) == 0 ? 4 : 0);
            const Word c = static_cast<Word>(pick(2) == 0 ? 3 : pick(6));
            const Word cntl = std::array<Word, 4>{0, 0x80, 0x40, 0xC0}[static_cast<std::size_t>(pick(4))];
            const Word fssio = static_cast<Word>(pick(2000));
            d.both([&](Drive& x) {
              x.set_value(pnr::kMode, m);
              x.set_value(pnr::kCsel, c);
              x.set_value(pnr::kFssel, 8);
              x.set_value(pnr::kCntl, cntl);
              x.set_value(pnr::kFssio, fssio);
            });
            break;
          }
          case 24: {  // a checked write, 11-STAT's reset included
            const auto& params = d.a().table().params();
            const std::size_t slot = static_cast<std::size_t>(pick(static_cast<int>(params.size())));
            const Word raw = pick(2) == 0 ? kStatReset : static_cast<Word>(pick(300));
            d.both([&](Drive& x) {
              const bool powered = x.power_stage_enabled();
              if (x.check_write(&params[slot], raw, powered) == drive::WriteCheck::ok) {
                (void)x.write(slot, raw, powered, t);
              }
            });
            break;
          }
          case 25: {
            const bool on = pick(2) == 0;
            d.both([&](Drive& x) { x.set_fault(on, t); });
            break;
          }
          case 26: d.both([&](Drive& x) { (void)x.read_siof(); }); break;
          case 27: d.both([&](Drive& x) { x.raise_siof(0x10); }); break;
          case 28: d.both([&](Drive& x) { x.clear_siof(0xFF); }); break;
          case 29:
            d.both([&](Drive& x) { x.restart(t); });  // the watchdog's error ends (5.2)
            break;
          case 30:
            if (pick(6) == 0) d.both([&](Drive& x) { x.power_cycle(t); });
            break;
          case 31:  // the INTERBUS face comes or goes
            if (pick(3) == 0) {
              interbus = !interbus;
              d.both([&](Drive& x) { interbus ? x.attach(Face::interbus) : x.detach(Face::interbus); });
            }
            break;
          case 32:
          case 33:
            if (interbus) {  // one INTERBUS sample
              const std::array<Word, Vf1000PdDevice::kWords> m2s{static_cast<Word>(pick(2) ? 0x000F : 0x0006),
                                                                 static_cast<Word>(pick(1000)), 0};
              d.both([&](Drive& x) {
                std::array<Word, Vf1000PdDevice::kWords> s2m{};
                x.interbus_cycle(t);
                x.begin_sample(t);
                x.sample(m2s, s2m, t, std::nullopt);
              });
            }
            break;
          case 34:
            d.both([&, ms = pick(30)](Drive& x) { x.smartcard(std::chrono::milliseconds(ms), t); });
            break;
          case 35: {
            const auto term = static_cast<Terminal>(pick(static_cast<int>(kTerminalCount)));
            const bool high = pick(2) == 0;
            d.both([&](Drive& x) { x.set_terminal(term, high); });
            break;
          }
          case 36:
            if (pick(8) == 0) d.both([&](Drive& x) { x.mains_off(t); });
            break;
          case 37: d.both([&](Drive& x) { x.mains_on(t); }); break;
          case 38:
            d.both([&, slot = static_cast<std::size_t>(pick(5)), raw = static_cast<Word>(pick(10))](Drive& x) {
              x.set(slot, raw);
            });
            break;
          default: d.both([&](Drive& x) { x.interbus_cycle(t); }); break;
        }
      }
      ASSERT_TRUE(d.same()) << "run " << run << " step " << step << " op " << op;
      if (d.a().serial_watchdog_fault()) ++trips;
    }
  }
  EXPECT_GT(skipped_chances, 10000);
  EXPECT_GT(trips, 100);  // the watchdog ran out, in runs
}

}  // namespace
}  // namespace ibs::devices::vf1000
