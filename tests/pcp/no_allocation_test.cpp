// The cycle path allocates nothing (design.md): whole sessions of every service, with faults and
// restarts, run between two readings of a global allocation counter.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <new>

#include "ibs/pcp/client.hpp"
#include "pcp_harness.hpp"
#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/pcp/server.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace ibs::pcp {
namespace {

using namespace ibs::devices::mc6000;

struct Rig {
  explicit Rig(int words)
      : client([&] {
          ClientConfig c;
          c.channel_words = words;
          return c;
        }()),
        parameters(StartMode::power_on),
        server([&] {
          ServerConfig c = ibs::devices::mc6000::server_config(1);
          c.channel_words = words;
          return c;
        }(), parameters.served) {}

  // Lock-step with a deterministic fault every 7th cycle (the servo's word is not delivered).
  void cycle() {
    now += 1ms;
    ++n;
    const auto to_server = m2s;
    if (n % 7 != 0) seen_by_client = s2m;
    client.step(now, seen_by_client, m2s);
    server.step(now, to_server, s2m);
  }
  bool await(Result& out) {
    for (int i = 0; i < 20000; ++i) {
      cycle();
      if (auto r = client.take_result()) {
        out = *r;
        return true;
      }
    }
    return false;
  }

  Client client;
  test::Served parameters;
  Server server;
  Time now{};
  long n = 0;
  std::array<Word, 4> m2s{};
  std::array<Word, 4> s2m{};
  std::array<Word, 4> seen_by_client{};
};

TEST(CyclePath, TheCounterSeesAllocations) {
  const long before = g_allocations.load();
  void* p = ::operator new(16);  // a direct call: never elided like a new-expression may be
  ::operator delete(p);
  EXPECT_EQ(g_allocations.load() - before, 1);
}

TEST(CyclePath, AllocatesNothing) {
  for (const int words : {1, 2, 4}) {
    Rig rig(words);
    Result r;
    int ok = 0;
    const long before = g_allocations.load();
    for (int round = 0; round < 3; ++round) {
      rig.client.initiate(rig.now);
      ok += rig.await(r) && r.ok() ? 1 : 0;
      rig.client.read(rig.now, ParameterRef::number(kSerr));
      ok += rig.await(r) && r.ok() ? 1 : 0;
      rig.client.write(rig.now, ParameterRef::number(428), DataType::int32q16, 132.15);
      ok += rig.await(r) && r.ok() ? 1 : 0;
      rig.client.read(rig.now, ParameterRef::number(428), DataType::int32q16);
      ok += rig.await(r) && r.ok() ? 1 : 0;
      rig.client.write(rig.now, ParameterRef::number(84), Value{DataType::usign16, 5});
      ok += rig.await(r) && r.ok() ? 1 : 0;
      rig.client.write(rig.now, ParameterRef::number(999), Value{DataType::usign16, 5});
      ok += rig.await(r) && r.kind == ResultKind::negative ? 1 : 0;
      rig.client.get_ov(rig.now, ParameterRef::number(kIbstu));
      ok += rig.await(r) && r.ok() ? 1 : 0;
      rig.client.identify(rig.now);
      ok += rig.await(r) && r.ok() ? 1 : 0;
      rig.client.status(rig.now);
      ok += rig.await(r) && r.ok() ? 1 : 0;
      rig.server.information_report(kIbsta);
      for (int i = 0; i < 100; ++i) rig.cycle();
      ok += rig.client.take_information_report().has_value() ? 1 : 0;
      rig.client.abort(rig.now);
      for (int i = 0; i < 100; ++i) rig.cycle();
      rig.client.initiate(rig.now);
      ok += rig.await(r) && r.ok() ? 1 : 0;
      rig.client.read(rig.now, ParameterRef::number(83));
      for (int i = 0; i < 5; ++i) rig.cycle();
      rig.parameters.drive.parameters().power_on(rig.now);
      rig.server.power_on(rig.now);
      ok += rig.await(r) && r.kind == ResultKind::link_reset ? 1 : 0;
    }
    const long after = g_allocations.load();
    EXPECT_EQ(after - before, 0) << words << " words";
    EXPECT_EQ(ok, 3 * 12) << words << " words: the sessions did what they should";
  }
}

}  // namespace
}  // namespace ibs::pcp
