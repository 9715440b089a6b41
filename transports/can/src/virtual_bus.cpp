#include "ibs/can/virtual_bus.hpp"

#include <stdexcept>

namespace ibs::can {

double BusStats::load() const {
  const auto span = (until - since).count();
  if (span <= 0) return 0.0;
  return static_cast<double>(busy.count()) / static_cast<double>(span);
}

VirtualBus::VirtualBus(const VirtualBusConfig& config) : config_(config) {
  if (!valid_bitrate(config_.bitrate)) {
    throw std::invalid_argument("virtual CAN bus: bit rate " + std::to_string(config_.bitrate) +
                                " bit/s is outside 25000..500000 (489-CLBDR)");
  }
  bit_ = can::bit_time(config_.bitrate);
}

NodeId VirtualBus::attach(std::string_view name) {
  Node n;
  n.name = std::string(name);
  n.tx.resize(config_.tx_capacity == 0 ? 1 : config_.tx_capacity);
  n.rx.resize(config_.rx_capacity == 0 ? 1 : config_.rx_capacity);
  nodes_.push_back(std::move(n));
  return static_cast<NodeId>(nodes_.size() - 1);
}

bool VirtualBus::send(NodeId node, const CanFrame& f, Time now) {
  if (node >= nodes_.size() || !f.valid()) return false;
  Node& n = nodes_[node];
  if (n.tx_size == n.tx.size()) {
    ++stats_.tx_overflows;
    return false;
  }
  n.tx[(n.tx_head + n.tx_size) % n.tx.size()] = {f, now};
  ++n.tx_size;
  return true;
}

std::optional<Time> VirtualBus::next_start() const {
  std::optional<Time> earliest;
  for (const auto& n : nodes_) {
    if (n.tx_size == 0) continue;
    const Time r = n.tx[n.tx_head].ready;
    if (!earliest || r < *earliest) earliest = r;
  }
  if (!earliest) return std::nullopt;
  return *earliest > free_at_ ? *earliest : free_at_;
}

void VirtualBus::advance(Time now) {
  for (;;) {
    if (current_.active) {
      if (current_.end > now) break;
      // End of frame: every other node receives it (the sender does not see its own frame).
      for (std::size_t i = 0; i < nodes_.size(); ++i) {
        if (i == current_.sender) continue;
        Node& n = nodes_[i];
        if (n.rx_size == n.rx.size()) {
          ++stats_.rx_overflows;
          continue;
        }
        n.rx[(n.rx_head + n.rx_size) % n.rx.size()] = {current_.frame, current_.end, current_.start,
                                                       current_.sender};
        ++n.rx_size;
      }
      free_at_ = current_.end + bit_ * kIntermissionBits;
      current_.active = false;
      continue;
    }
    const auto start = next_start();
    if (!start || *start > now) break;
    // Arbitration among the nodes whose oldest frame is ready at `start`: the lowest identifier
    // wins, then a data frame over a remote frame (RTR recessive).
    int winner = -1;
    unsigned best = 0;
    unsigned contenders = 0;
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      const Node& n = nodes_[i];
      if (n.tx_size == 0 || n.tx[n.tx_head].ready > *start) continue;
      ++contenders;
      const CanFrame& f = n.tx[n.tx_head].frame;
      const unsigned key = (static_cast<unsigned>(f.id) << 1U) | (f.rtr ? 1U : 0U);
      if (winner < 0 || key < best) {
        winner = static_cast<int>(i);
        best = key;
      }
    }
    Node& w = nodes_[static_cast<std::size_t>(winner)];
    stats_.arbitration_losses += contenders - 1;
    current_.active = true;
    current_.sender = static_cast<NodeId>(winner);
    current_.frame = w.tx[w.tx_head].frame;
    current_.start = *start;
    current_.bits = frame_bits(current_.frame);
    current_.end = *start + bit_ * current_.bits.total();
    w.tx_head = (w.tx_head + 1) % w.tx.size();
    --w.tx_size;
    ++stats_.frames;
    stats_.bits += current_.bits.total();
    stats_.stuff_bits += current_.bits.stuff;
    stats_.busy += bit_ * current_.bits.on_bus();
  }
  if (now > stats_.until) stats_.until = now;
}

std::optional<Delivery> VirtualBus::receive(NodeId node) {
  if (node >= nodes_.size()) return std::nullopt;
  Node& n = nodes_[node];
  if (n.rx_size == 0) return std::nullopt;
  const Delivery d = n.rx[n.rx_head];
  n.rx_head = (n.rx_head + 1) % n.rx.size();
  --n.rx_size;
  return d;
}

Time VirtualBus::next_event() const {
  if (current_.active) return current_.end;
  const auto s = next_start();
  return s ? *s : Time::max();
}

bool VirtualBus::idle() const {
  if (current_.active) return false;
  for (const auto& n : nodes_) {
    if (n.tx_size > 0) return false;
  }
  return true;
}

void VirtualBus::reset_stats(Time now) {
  stats_ = BusStats{};
  stats_.since = now;
  stats_.until = now;
}

}  // namespace ibs::can
