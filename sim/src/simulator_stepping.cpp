// The devices' samples between cycle ends: device by device on one or several threads (a held stretch
// in one call), or time-ordered when an observer watches every sample.
#include "simulator_internal.hpp"

namespace ibs::sim {

using detail::usable_cores;

Time Simulator::next_sample_time(Device& d) {
  // Nominal phase + k * period, moved by up to +-jitter, never before the previous sample. Each
  // device draws its jitter from its own generator, so the order in which devices are stepped
  // does not change the run.
  Time t = d.cfg.phase + static_cast<std::int64_t>(d.k) * d.period;
  if (d.cfg.jitter > Duration{0}) {
    const auto span = static_cast<std::uint64_t>(2 * d.cfg.jitter.count() + 1);
    t += Duration{static_cast<std::int64_t>(d.jitter_rng() % span) - d.cfg.jitter.count()};
  }
  return std::max(t, d.last_sample);
}

void Simulator::run_device_major(Time end) {
  // Devices interact only through the bus exchange: between two cycle ends every device can take
  // all its samples on its own, in its own time order, with exactly the result of the globally
  // time-ordered loop (a sample at the instant of a cycle end comes after the exchange).
  // The master's cycle after a cycle end and the devices' samples up to the next one do not meet
  // either (the master's new words reach the devices only at that next cycle end), so they run
  // side by side: the master's on the calling thread, ahead of its part of the devices.
  Time last_progress = now_;
  while (true) {
    const Time limit = std::min(next_cycle_, end + Duration{1});
    step_devices(limit);
    master_due_.reset();
    if (next_cycle_ > end) break;
    now_ = next_cycle_;
    cycle_exchange(next_cycle_);
    master_due_ = next_cycle_;
    next_cycle_ += cycle_time_;
    if (options_.progress && now_ - last_progress >= 100ms) {
      options_.progress(now_, scenario_.duration);
      last_progress = now_;
    }
  }
}

void Simulator::step_devices(Time limit) {
  window_limit_ = limit;
  if (!workers_) {
    step_part(0);
    return;
  }
  workers_->run();
}

void Simulator::step_part(unsigned part) {
  if (part == 0 && master_due_) cycle_master(*master_due_);
  const Part p = parts_.empty() ? Part{0, devices_.size()} : parts_[part];
  for (std::size_t k = p.first; k < p.end; ++k) step_device(*devices_[k], window_limit_);
}

void Simulator::start_threads(unsigned requested) {
  // Work of a device: its samples per simulated millisecond (an MC6000 1, a VF1000 0.12).
  std::vector<double> work;
  double total = 0.0;
  for (const auto& d : devices_) {
    work.push_back(1e6 / static_cast<double>(d->period.count()));
    total += work.back();
  }
  // Automatic: a thread only for at least this much work (servo samples per millisecond); less
  // cannot pay for the hand-over each cycle. (On the 2-vCPU machine of docs/performance.md even
  // 32 per thread did not, hence one thread by default.)
  constexpr double kWorkPerThread = 16.0;
  // The master's cycle and the summary, on the first part's thread: about three servo samples
  // per device and cycle (measured with callgrind on the full bus).
  const double master = 3.0 * static_cast<double>(devices_.size()) * 1e6 / static_cast<double>(cycle_time_.count());
  unsigned n = requested;
  if (n == 0) {
    const unsigned cores = usable_cores();
    n = std::min(cores, static_cast<unsigned>(std::max(1.0, total / kWorkPerThread)));
  }
  n = std::min<unsigned>(n, static_cast<unsigned>(devices_.size()));
  if (n <= 1) return;
  // Contiguous parts of about (total + master) / n each, the first with the master's work.
  parts_.assign(n, Part{});
  std::size_t i = 0;
  double done = master;
  for (unsigned p = 0; p < n; ++p) {
    parts_[p].first = i;
    const double target = (total + master) * (p + 1) / n;
    const std::size_t keep = n - p - 1;  // devices left for the parts after this one
    while (i < devices_.size() - keep && (i == parts_[p].first || done + 0.5 * work[i] <= target)) {
      done += work[i++];
    }
    parts_[p].end = p + 1 == n ? devices_.size() : i;
  }
  workers_ = std::make_unique<ForkJoin>(n, [this](unsigned part) { step_part(part); });
}

void Simulator::step_device(Device& d, Time limit) {
  if (d.next_sample >= limit) return;
  if (!d.emu->defers_output() || !d.recordings.empty()) {
    while (d.next_sample < limit) handle_sample(d.index, d.next_sample);
    return;
  }
  // An MC6000 without PCP words, not recorded: nobody reads its process-data words before the
  // cycle end, so they are formed once, after its last sample before it. Without jitter its
  // samples up to the cycle end are known at once and it takes them in one go.
  if (d.cfg.jitter == Duration{0}) {
    const auto count = static_cast<std::uint64_t>((limit - d.next_sample + d.period - Duration{1}) / d.period);
    d.emu->sample_held(d.pd_m2s(), d.next_sample, d.period, static_cast<std::uint32_t>(count));
    d.k += count;
    d.last_sample = d.next_sample + static_cast<std::int64_t>(count - 1) * d.period;
    d.next_sample = next_sample_time(d);
  } else {
    do {
      d.last_sample = d.next_sample;
      d.emu->sample_deferred(d.pd_m2s(), d.next_sample);
      ++d.k;
      d.next_sample = next_sample_time(d);
    } while (d.next_sample < limit);
  }
  d.emu->output(d.pd_s2m());
}

void Simulator::run_time_ordered(Time end) {
  // With observers (a VCD file) the events go strictly in time order across devices.
  samples_.clear();
  for (const auto& d : devices_) samples_.push_back({d->next_sample, d->index});
  std::make_heap(samples_.begin(), samples_.end(), std::greater<>{});
  Time last_progress = now_;
  while (true) {
    const SampleEvent next = samples_.front();  // the earliest sample of any device
    const Time t = std::min(next_cycle_, next.at);
    if (t > end) break;
    now_ = t;
    // At the same instant the bus exchange comes first: a device sampling then sees its new words.
    if (next_cycle_ <= next.at) {
      handle_cycle(t);
      next_cycle_ += cycle_time_;
    } else {
      handle_sample(next.device, t);
      reschedule_front(devices_[next.device]->next_sample);
    }
    if (options_.progress && t - last_progress >= 100ms) {
      options_.progress(t, scenario_.duration);
      last_progress = t;
    }
  }
}

void Simulator::reschedule_front(Time at) {
  // The device at the top of the min-heap sampled: give it its next time and sift it down (one
  // pass instead of a pop and a push).
  const std::size_t n = samples_.size();
  SampleEvent moving{at, samples_[0].device};
  std::size_t i = 0;
  while (true) {
    const std::size_t l = 2 * i + 1;
    if (l >= n) break;
    std::size_t c = l;
    if (l + 1 < n && samples_[l + 1] < samples_[l]) c = l + 1;
    if (!(samples_[c] < moving)) break;
    samples_[i] = samples_[c];
    i = c;
  }
  samples_[i] = moving;
}

void Simulator::handle_sample(std::size_t i, Time t) {
  Device& d = *devices_[i];
  d.last_sample = t;
  const bool recording = !d.recordings.empty();  // only with SimOptions::record_traces
  std::array<Word, 4> before{};
  if (recording) {
    before = d.s2m;
    record_changes(d);  // made by other channels before this sample: they act before it
  }
  // The PCP words move at the cycle end (pcp_cycle): the sample gets none.
  d.emu->sample({d.pd_m2s(), d.pd_s2m(), {}, {}}, t);
  ++d.k;
  d.next_sample = next_sample_time(d);
  if (const devices::Notices n = d.emu->notices(); n.count != d.notices) {
    // E.g. 15-PLRDY = 1 makes the servo recalculate its controller parameters (INTERBUS manual 4.2).
    d.notices = n.count;
    d.records.push_back({t, std::string(n.what)});
  }
  if (recording) record_sample(d, before, t);
  for (Observer* o : observers_) o->on_sample(t, i, d.pd_m2s(), d.pd_s2m());
}

}  // namespace ibs::sim
