// The master's side of a scenario (master_timeline.hpp): what the simulator's cycle end did for
// ibs's master, moved here so that a run against a controller board does the very same.
#include "ibs/sim/master_timeline.hpp"

#include "ibs/base/number_text.hpp"
#include "simulator_internal.hpp"

namespace ibs::sim {

using detail::fmt_value;

MasterTimeline::MasterTimeline(master::MasterLoop& loop, const interbus::ProcessImage& image, Summary& summary)
    : loop_(loop), summary_(summary), devices_(loop.size()) {
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    devices_[i].in = interbus::in_slice(image, loop.config().devices[i]);
  }
}

bool MasterTimeline::is_master_command(Action a) {
  switch (a) {
    case Action::state:
    case Action::emergency_stop:
    case Action::block_power:
    case Action::speed:
    case Action::frequency:
    case Action::read:
    case Action::write:
    case Action::describe:
    case Action::wait_state:
      return true;
    default:
      return false;
  }
}

void MasterTimeline::apply(const TimelineEntry& e, std::size_t i, Time t) {
  devices::DeviceDriver& driver = loop_.driver(i);
  Device& d = devices_[i];
  switch (e.action) {
    case Action::state:
      if (const auto target = drivecom::target_named(e.value)) driver.sequencer().request(*target, t);
      break;
    case Action::emergency_stop:
      driver.sequencer().request_emergency_stop(t);
      break;
    case Action::block_power:
      driver.sequencer().request_block_power(t);
      break;
    case Action::speed:
    case Action::frequency:
      driver.set_reference(e.number);
      d.reached_reported = false;
      d.reached_for = e.number;
      break;
    case Action::read:
    case Action::write:
    case Action::describe: {
      const devices::ParamOp op = e.action == Action::read    ? devices::ParamOp::read
                                  : e.action == Action::write ? devices::ParamOp::write
                                                              : devices::ParamOp::describe;
      TransactionRecord r;
      r.device = e.device;
      r.op = op;
      r.number = e.parameter;
      r.value = static_cast<std::int64_t>(e.number);
      r.submitted = t;
      r.source_line = e.source_line;
      r.id = driver.parameters().submit(op, e.parameter, r.value);
      if (r.id == 0) {
        r.answered = r.finished = t;
        r.kind = devices::ParamKind::refused;
        r.result = driver.parameters().describe(0);
      }
      summary_.transactions.push_back(std::move(r));
      transaction_device_.push_back(i);
      break;
    }
    case Action::wait_state:
      d.waiting_for = drivecom::state_named(e.value);
      d.wait_deadline = e.duration > Duration{0} ? t + e.duration : Time::max();
      break;
    default:
      break;
  }
}

void MasterTimeline::observe_device(std::size_t i, Time t) {
  Device& d = devices_[i];
  devices::DeviceDriver& drv = loop_.driver(i);
  const auto seen = drv.sequencer().report().state_seen;
  auto& states = summary_.devices[i].states;
  if (seen && seen != d.last_seen) {
    states.push_back({t, std::string(drivecom::to_string(*seen))});
    d.last_seen = seen;
  }
  // A reference the master sees reached (status bit 10 while ENABLED, the actual at it).
  const std::span<const Word> in = d.in;
  // (the actual must be at the new reference too: the status word may still show the old one)
  const bool at_reference = std::fabs(drv.actual() - d.reached_for) <= 0.01 * std::fabs(d.reached_for) + 0.1;
  if (!d.reached_reported && !in.empty() && seen == State::enabled &&
      bit(in[0], drivecom::sw::kReferenceReached) && at_reference) {
    d.reached_reported = true;
    // Numbers a person reads (base/number_text.hpp): "reference 1000 rpm reached (actual 994.60)".
    states.push_back({t, "reference " + fmt_value(d.reached_for) + " " + std::string(drv.unit()) +
                             " reached (actual " + quantity_text(drv.actual(), drv.unit()) + ")"});
  }
  if (d.waiting_for && (seen == d.waiting_for || t >= d.wait_deadline)) {
    if (seen != d.waiting_for) {
      states.push_back({t, "wait for " + std::string(drivecom::to_string(*d.waiting_for)) + " timed out"});
    }
    d.waiting_for.reset();
  }
  const drivecom::Report& rep = drv.sequencer().report();
  if (rep.phase != drivecom::Phase::failed) {
    d.failure_reported = false;
  } else if (!d.failure_reported) {
    d.failure_reported = true;
    const std::string why = drivecom::describe(rep);
    states.push_back({t, "master: request failed (" + std::string(drivecom::to_string(rep.failure)) + ")"});
    summary_.devices[i].failures.push_back({t, std::string(drivecom::to_string(rep.failure)), why});
  }
}

void MasterTimeline::observe_transactions(Time t) {
  for (std::size_t k = 0; k < summary_.transactions.size(); ++k) {
    TransactionRecord& r = summary_.transactions[k];
    if (r.finished) continue;
    const devices::ParameterAccess& pa = loop_.driver(transaction_device_[k]).parameters();
    if (!r.answered) {
      const devices::ParamStatus s = pa.status(r.id);
      if (!s.done()) continue;
      r.answered = t;
      r.kind = s.kind;
      r.result_value = s.value;
      r.result = pa.describe(r.id);
    }
    if (!pa.closing()) r.finished = t;
  }
}

void MasterTimeline::finish() {
  for (auto& r : summary_.transactions) {
    if (!r.finished) r.result = "still pending at the end of the run";
  }
}

}  // namespace ibs::sim
