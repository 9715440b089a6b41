#include "ibs/devices/dfs1/master.hpp"

namespace ibs::devices::dfs1 {

namespace proto = ::ibs::dfs1;

std::optional<Ticket> Master::submit(const proto::Frame& request) {
  if (proto::check_request(request) != proto::RequestCheck::ok) return std::nullopt;
  if (queued_ + done_count_ + (active_ ? 1U : 0U) >= kCapacity) return std::nullopt;
  const Ticket t = next_ticket_++;
  queue_[(queue_head_ + queued_) % kCapacity] = {t, request};
  ++queued_;
  return t;
}

std::span<const std::uint8_t> Master::pending(Time now) {
  if (!active_ && queued_ > 0) {
    const auto& [ticket, request] = queue_[queue_head_];
    if (transaction_.start(request, now) == proto::StartStatus::accepted) {
      active_ = true;
      active_ticket_ = ticket;
      sent_ = 0;
    }
    queue_head_ = (queue_head_ + 1) % kCapacity;
    --queued_;
  }
  if (!active_ || transaction_.state() != proto::HostTransaction::State::sending) return {};
  return transaction_.tx().subspan(sent_);
}

void Master::consume(std::size_t n, Time now) {
  if (!active_ || transaction_.state() != proto::HostTransaction::State::sending) return;
  sent_ += n;
  if (sent_ >= transaction_.tx().size()) {
    transaction_.transmitted(now);
    collect();
  }
}

void Master::receive(std::uint8_t byte, Time now) {
  transaction_.receive(byte, now);
  collect();
}

void Master::receive(std::span<const std::uint8_t> bytes, Time now) {
  for (std::uint8_t b : bytes) receive(b, now);
}

void Master::poll(Time now) {
  transaction_.poll(now);
  collect();
}

void Master::collect() {
  if (!active_) return;
  if (auto r = transaction_.take_result()) {
    done_[(done_head_ + done_count_) % kCapacity] = Completion{active_ticket_, *r};
    ++done_count_;
    active_ = false;
  }
}

std::optional<Completion> Master::take_completion() {
  if (done_count_ == 0) return std::nullopt;
  Completion c = done_[done_head_];
  done_head_ = (done_head_ + 1) % kCapacity;
  --done_count_;
  return c;
}

}  // namespace ibs::devices::dfs1
