// The scenario's timeline and the faults: injected by the timeline or the campaign, and random ones.
#include "simulator_internal.hpp"

namespace ibs::sim {

using detail::fmt_value;
using detail::next_random;

void Simulator::inject_fault(Action kind, std::size_t i, Duration duration, int count) {
  const bool bus_wide = kind == Action::fault_corrupt || kind == Action::master_restart;
  if (!bus_wide && i >= devices_.size()) return;
  fault(now_, bus_wide ? devices_.size() : i, kind, duration, count);
}

void Simulator::apply_timeline(Time t) {
  // Entries of a device that waits for a state stay deferred until the wait ends.
  auto waiting = [&](const TimelineEntry& e) {
    if (e.device.empty()) return false;
    const auto i = index_of(e.device);
    return i && master_side_->waiting(*i);
  };
  for (auto it = deferred_.begin(); it != deferred_.end();) {
    if (!waiting(**it)) {
      apply(**it, t);
      record_control(**it, t);
      it = deferred_.erase(it);
    } else {
      ++it;
    }
  }
  while (timeline_next_ < scenario_.timeline.size() && scenario_.timeline[timeline_next_].at <= t) {
    const TimelineEntry& e = scenario_.timeline[timeline_next_++];
    if (waiting(e)) {
      deferred_.push_back(&e);
    } else {
      apply(e, t);
    }
  }
}

void Simulator::control(const TimelineEntry& e) {
  control_entries_.push_back(e);
  const TimelineEntry& kept = control_entries_.back();
  if (!kept.device.empty()) {
    const auto i = index_of(kept.device);
    if (i && master_side_->waiting(*i)) {
      deferred_.push_back(&kept);
      return;
    }
  }
  apply(kept, now_);
  record_control(kept, now_);
}

void Simulator::record_control(const TimelineEntry& e, Time t) {
  for (const TimelineEntry& c : control_entries_) {
    if (&c == &e) {
      summary_.control.push_back({t, e.source_line, e.source_client, write_control_line(e), e.device});
      return;
    }
  }
}

void Simulator::apply(const TimelineEntry& e, Time t) {
  std::optional<std::size_t> idx;
  if (!e.device.empty()) {
    idx = index_of(e.device);
    if (!idx) return;  // checked when the scenario was read
  }
  switch (e.action) {
    case Action::state:
    case Action::emergency_stop:
    case Action::block_power:
    case Action::speed:
    case Action::frequency:
    case Action::read:
    case Action::write:
    case Action::describe:
    case Action::wait_state:
      if (idx) master_side_->apply(e, *idx, t);  // the master's (master_timeline.hpp)
      break;
    case Action::fault_corrupt:
    case Action::fault_power_cycle:
    case Action::fault_device:
    case Action::fault_lost:
    case Action::master_restart:
    case Action::mains:
    case Action::load:
    case Action::input:
    case Action::smartcard:
    case Action::option_card:
      fault(t, idx.value_or(devices_.size()), e.action, e.duration, e.count, &e);
      break;
  }
}

void Simulator::plant(Time t, std::size_t i, const TimelineEntry& e, FaultRecord& f) {
  // The drive's own events (devices/plant_event.hpp), as its descriptor's EventFacts allow them
  // (the validator checked the entry against them).
  Device& d = *devices_[i];
  const devices::EventFacts& facts = (*d.kind)->facts().events;
  devices::PlantEvent ev;
  switch (e.action) {
    case Action::mains:
      ev.kind = e.value == "off" ? devices::PlantEvent::Kind::mains_off : devices::PlantEvent::Kind::mains_on;
      f.kind = e.value == "off" ? "mains-off" : "mains-on";
      f.detail = e.value == "off" ? "mains lost: the drive is off" : "mains back: the drive starts as at power-on";
      break;
    case Action::load:
      ev.kind = devices::PlantEvent::Kind::load;
      ev.value = e.number;
      f.kind = "load";
      f.detail = "load torque " + fmt_value(e.number) + " " + std::string(facts.load_unit);
      break;
    case Action::input:
      ev.kind = devices::PlantEvent::Kind::input;
      ev.input = devices::find_input(facts, e.value).value_or(0);
      ev.level = e.level;
      f.kind = "input";
      f.detail = "input " + e.value + (e.level ? " high" : " low");
      break;
    case Action::smartcard:
      ev.kind = e.value == "write" ? devices::PlantEvent::Kind::card_write : devices::PlantEvent::Kind::card_read;
      ev.value = std::chrono::duration<double>(e.duration).count();
      f.kind = "smartcard";
      f.detail = "SMARTCARD " + std::string(e.value == "write" ? "written" : "read") + " for " +
                 fmt_value(to_ms(e.duration)) + " ms";
      break;
    case Action::option_card:
      ev.kind = e.value == "withdrawn" ? devices::PlantEvent::Kind::option_withdrawn
                                       : devices::PlantEvent::Kind::option_inserted;
      f.kind = "option-card";
      f.detail = std::string(facts.option_card) + " " + e.value + ": detected at the next power-on (" +
                 std::string(facts.option_source) + ")";
      break;
    default:
      return;
  }
  if (!d.emu->apply_event(ev, t)) f.detail += " (not taken by the drive)";
}

void Simulator::fault(Time t, std::size_t i, Action kind, Duration duration, int count,
                      const TimelineEntry* entry) {
  FaultRecord f;
  f.at = t;
  if (i < devices_.size()) f.device = devices_[i]->cfg.name;
  auto note = [&](Device& d, const std::string& what) {
    if (!d.recordings.empty() && d.recording) {
      auto& r = d.recordings.back().remark;
      r += (r.empty() ? "" : "; ") + what;
    }
  };
  auto event = [&](Device& d, trace::Event::Kind what, const std::string& text) {
    if (!d.recordings.empty() && d.recording) d.recordings.back().events_pending.push_back({what, text, 0, 0});
  };
  switch (kind) {
    case Action::fault_corrupt:
      f.kind = "corrupt";
      f.detail = std::to_string(count) + " corrupted cycle(s), then " +
                 std::to_string(scenario_.bus.recovery_cycles) + " recovery cycles";
      corrupt_left_ += std::max(count, 1);
      break;
    case Action::fault_power_cycle: {
      Device& d = *devices_[i];
      f.kind = "power-cycle";
      f.detail = "switched off and on: initialising again";
      d.emu->power_cycle(t);
      if (d.recording) {
        // A power cycle is not in the trace format: this recording ends, a new one starts once the
        // device has initialised again.
        d.recordings.back().trace.trailing_comments.push_back("# recording ends: power cycle at " +
                                                              fmt_value(to_ms(t)) + " ms");
        Recording next;
        next.trace.file = d.cfg.name;
        next.trace.header = d.recordings.back().trace.header;
        next.file_name = d.cfg.name + "." + std::to_string(d.recordings.size() + 1) + ".trace";
        d.recordings.push_back(std::move(next));
        d.recording = false;
      }
      d.power_cycled = true;
      break;
    }
    case Action::fault_device: {
      Device& d = *devices_[i];
      f.kind = "device-fault";
      f.detail = "fault present for " + fmt_value(to_ms(duration)) + " ms";
      d.fault_until = t + std::max(duration, d.period);
      const devices::EventFacts& facts = (*d.kind)->facts().events;
      const std::optional<int> cause =
          entry != nullptr && !entry->cause.empty()
              ? devices::check_cause(facts, (*d.kind)->facts().title, entry->cause).number
              : std::nullopt;
      if (cause) {
        // The drive shows its own error (LUSTBUS manual 8; docs/errata.md VF-E17, MC-D6).
        devices::PlantEvent ev;
        ev.cause = cause;
        d.emu->apply_event(ev, t);
        const std::string error = "error " + devices::cause_text(facts, *cause);
        f.detail += ", " + error;
        summary_.devices[d.index].errors.push_back(fmt_value(to_ms(t)) + " ms: " + error + ": device fault injected");
      } else {
        d.emu->set_fault(true);
      }
      note(d, "device fault injected");
      event(d, trace::Event::Kind::fault, "injected at " + fmt_value(to_ms(t)) + " ms");
      break;
    }
    case Action::fault_lost: {
      Device& d = *devices_[i];
      f.kind = "lost";
      f.detail = duration > Duration{0} ? "off the bus for " + fmt_value(to_ms(duration)) + " ms"
                                        : "off the bus until the end";
      d.lost_until = duration > Duration{0} ? t + duration : Time::max();
      note(d, "device lost from the bus");
      break;
    }
    case Action::master_restart:
      f.kind = "master-restart";
      f.detail = "drivers and channels start over";
      if (external_ != nullptr) {
        external_->restart(t);
      } else {
        loop_->restart(t);
      }
      break;
    case Action::mains:
    case Action::load:
    case Action::input:
    case Action::smartcard:
    case Action::option_card:
      if (entry == nullptr || i >= devices_.size()) return;
      plant(t, i, *entry, f);
      if (kind == Action::mains || kind == Action::smartcard || kind == Action::option_card) {
        note(*devices_[i], f.detail);
      }
      break;
    default: return;
  }
  summary_.faults.push_back(std::move(f));
}

void Simulator::apply_random_faults(Time t) {
  const auto& r = scenario_.random;
  auto pick = [&]() {
    std::uniform_int_distribution<std::size_t> u(0, devices_.size() - 1);
    return u(rng_);
  };
  if (t >= random_next_.corrupt) {
    fault(t, devices_.size(), Action::fault_corrupt, Duration{0}, 1);
    random_next_.corrupt = next_random(rng_, t, r.corrupt_per_s);
  }
  if (t >= random_next_.power_cycle) {
    fault(t, pick(), Action::fault_power_cycle, Duration{0}, 1);
    random_next_.power_cycle = next_random(rng_, t, r.power_cycle_per_s);
  }
  if (t >= random_next_.device_fault) {
    fault(t, pick(), Action::fault_device, 50ms, 1);
    random_next_.device_fault = next_random(rng_, t, r.device_fault_per_s);
  }
  if (t >= random_next_.lost) {
    fault(t, pick(), Action::fault_lost, 100ms, 1);
    random_next_.lost = next_random(rng_, t, r.lost_per_s);
  }
  if (t >= random_next_.master_restart) {
    fault(t, devices_.size(), Action::master_restart, Duration{0}, 1);
    random_next_.master_restart = next_random(rng_, t, r.master_restart_per_s);
  }
}

}  // namespace ibs::sim
