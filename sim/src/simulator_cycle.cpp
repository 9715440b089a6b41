// The cycle end: the bus exchange with the emulated devices (the far side of the master's bus seam,
// master/bus.hpp), then the master's half of the cycle and what the summary takes from it.
#include "simulator_internal.hpp"

namespace ibs::sim {

using detail::fmt_value;
using detail::copy_words;

void Simulator::handle_cycle(Time t) {
  cycle_exchange(t);
  cycle_master(t);
}

void Simulator::cycle_exchange(Time t) {
  merge_device_records();
  apply_timeline(t);
  apply_random_faults(t);
  for (auto& d : devices_) {
    if (d->fault_until >= Time{0} && t >= d->fault_until) {
      d->fault_until = Time{-1};
      d->emu->set_fault(false);
      summary_.faults.push_back({t, d->cfg.name, "fault-cleared", "the fault's cause has gone"});
      if (!d->recordings.empty() && d->recording) {
        d->recordings.back().events_pending.push_back(
            {trace::Event::Kind::fault_cleared, "at " + fmt_value(to_ms(t)) + " ms", 0, 0});
      }
    }
    if (d->lost_until >= Time{0} && d->lost_until != Time::max() && t >= d->lost_until) {
      d->lost_until = Time{-1};
      summary_.faults.push_back({t, d->cfg.name, "back", "back on the bus"});
    }
  }
  // The cycle just ended: a corrupted one and the recovery cycles after it deliver nothing.
  bool valid = bus_running_;
  if (!bus_running_) {
    // A stopped bus: no cycle, nothing delivered; faults of the timeline still take their course.
  } else if (corrupt_left_ > 0) {
    --corrupt_left_;
    valid = false;
    if (corrupt_left_ == 0) recovery_left_ = scenario_.bus.recovery_cycles;
  } else if (recovery_left_ > 0) {
    --recovery_left_;
    valid = false;
  }
  ++summary_.cycles;
  if (valid) ++summary_.valid_cycles;
  for (auto& d : devices_) {
    master::LinkState& link = links_[d->index];
    link.data_valid = valid && !d->switched_off;
    link.module_error = d->module_error(t) && !d->switched_off;
    if (!valid) continue;
    if (d->switched_off) {
      std::fill(d->in_slot.begin(), d->in_slot.end(), Word{0});
      continue;
    }
    if (link.module_error) {
      std::fill(d->in_slot.begin(), d->in_slot.end(), Word{0});  // no data from a device with a module error
      // A device that is on the ring but initialising (6.1) still takes the master's words into
      // its bus interface: it acts on the newest ones once it is ready, not on words from before.
      if (!d->lost(t) && d->emu->takes_words_in_module_error()) {
        copy_words(d->out, d->m2s.data());
        // A recording cannot tell words taken without the watchdog fed from a valid cycle: the
        // words matter once the device is ready, so the sample counts as one with data.
        d->delivered = d->ever_delivered = true;
      }
      continue;
    }
    copy_words(d->out, d->m2s.data());
    d->delivered = d->ever_delivered = true;
    copy_words({d->s2m.data(), d->in.size()}, d->in.data());
    copy_words(d->pcp_out, d->pcp_m2s.data());
    copy_words({d->pcp_s2m.data(), d->pcp_in.size()}, d->pcp_in.data());
    // The device's PCP interface takes this cycle's frame and prepares its next one at the bus
    // cycle (INTERBUS manual 3.2.2, the servo's INTERBUS CPU), not at its 1 ms sample (docs/pcp.md).
    if (d->pcp_words > 0) d->emu->pcp_cycle(t, {d->pcp_m2s.data(), d->pcp_words}, {d->pcp_s2m.data(), d->pcp_words});
    d->emu->bus_cycle(t);
  }
  // What the master's side reports of the devices, as they are at this cycle end (the devices
  // may be sampling again while the master's cycle runs).
  for (auto& d : devices_) d->error_at_cycle = d->emu->error_number();
  last_cycle_valid_ = valid;
}

void Simulator::cycle_master(Time t) {
  const auto t0 = options_.measure_master_time ? std::chrono::steady_clock::now()
                                               : std::chrono::steady_clock::time_point{};
  if (external_ != nullptr) {
    external_->cycle(image_, t, master::Exchange{last_cycle_valid_, links_});
  } else {
    loop_->cycle(image_, t, master::Exchange{last_cycle_valid_, links_});
  }
  if (options_.measure_master_time) {
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0);
    master_ns_.push_back(static_cast<std::uint32_t>(std::min<std::int64_t>(ns.count(), 0xFFFFFFFF)));
  }
  for (Observer* o : observers_) o->on_cycle(t, last_cycle_valid_, image_);
  observe_master(t);
}

void Simulator::observe_master(Time t) {
  for (auto& d : devices_) {
    // Under another master (ExternalMaster) what ibs's drivers saw is not there; the devices'
    // watchdog errors are.
    if (external_ == nullptr) master_side_->observe_device(d->index, t);
    const auto err = d->error_at_cycle;
    if (err && err != d->reported_error) {
      const std::string what((*d->kind)->facts().watchdog_error);
      summary_.faults.push_back({t, d->cfg.name, "watchdog", what});
      summary_.devices[d->index].errors.push_back(fmt_value(to_ms(t)) + " ms: " + what);
    }
    d->reported_error = err;
  }
  master_side_->observe_transactions(t);
}

void Simulator::merge_device_records() {
  for (auto& d : devices_) {
    if (d->records.empty()) continue;
    auto& states = summary_.devices[d->index].states;
    states.insert(states.end(), d->records.begin(), d->records.end());
    d->records.clear();
  }
}

}  // namespace ibs::sim
