// The master's cycle loop: one driver per ring device, slices of the process image, no
// allocation per cycle.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "ibs/sim/master_loop.hpp"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  if (g_counting.load()) g_allocations.fetch_add(1);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
// The nothrow forms too, so that every allocation and its release go through malloc/free.
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  if (g_counting.load()) g_allocations.fetch_add(1);
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace ibs::sim {
namespace {

TEST(MasterLoop, FullBusOf64ServosCyclesWithoutAllocating) {
  std::vector<interbus::DeviceSpec> specs;
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  const auto layout = interbus::mc6000::make_layout(12, 2);  // 4 process-data words, no PCP
  for (int i = 0; i < 64; ++i) {
    specs.push_back({"mc" + std::to_string(i), interbus::IdCode{layout.id_code}, std::nullopt});
    drivers.push_back(std::make_unique<devices::Mc6000Driver>(layout));
  }
  MasterLoop loop(interbus::make_bus_config(specs), std::move(drivers));
  EXPECT_EQ(loop.config().in_words, 256U);
  interbus::ProcessImage image;
  loop.initial(image);
  std::vector<LinkState> links(64);
  for (std::size_t i = 0; i < 64; ++i) {
    loop.driver(i).sequencer().request(drivecom::Target::enabled, 0ns);
    loop.driver(i).set_reference(100.0 * static_cast<double>(i));
  }
  for (std::size_t i = 0; i < 64; ++i) image.in[4 * i] = 0x0231;  // every servo READY
  g_allocations = 0;
  g_counting = true;
  for (int c = 0; c < 100; ++c) loop.cycle(image, std::chrono::milliseconds(c), links);
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 0);
  // Each servo got ENABLE and its own reference in its own slice (Q16, high word first).
  for (std::size_t i = 0; i < 64; ++i) {
    EXPECT_EQ(image.out[4 * i], 0x000F) << i;
    EXPECT_EQ(make_dword(image.out[4 * i + 1], image.out[4 * i + 2]),
              static_cast<std::uint32_t>(100 * i) << 16U)
        << i;
  }
}

TEST(MasterLoop, RefusesMismatchedDrivers) {
  std::vector<interbus::DeviceSpec> specs{{"vf", interbus::IdCode{0x033B}, std::nullopt}};
  EXPECT_THROW(MasterLoop(interbus::make_bus_config(specs), {}), std::invalid_argument);
}

}  // namespace
}  // namespace ibs::sim
