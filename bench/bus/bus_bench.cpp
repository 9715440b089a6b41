// Copying a full 256-word process image and reaching devices through their slices.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "ibs/interbus/bus_config.hpp"
#include "ibs/interbus/cycle_time.hpp"
#include "ibs/interbus/process_image.hpp"

namespace {

using ibs::Word;
using namespace ibs::interbus;

// 16 devices of 16 words in/out fill both 256-word images.
BusConfig full_bus() {
  std::vector<DeviceSpec> ring;
  for (int i = 0; i < 16; ++i) {
    std::string name = "d";
    name += std::to_string(i);
    ring.push_back({name, IdCode{0x1203}, {}});
  }
  return make_bus_config(ring);
}

void BM_CopyFullImage(benchmark::State& state) {
  ProcessImage a;
  ProcessImage b;
  for (std::size_t i = 0; i < a.in.size(); ++i) a.in[i] = static_cast<Word>(i);
  for (auto _ : state) {
    b.in = a.in;
    benchmark::DoNotOptimize(b.in.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * 512);
}
BENCHMARK(BM_CopyFullImage);

// Every device: read its input slice, write its output slice (a master cycle's data handling).
void BM_SliceAllDevices(benchmark::State& state) {
  const BusConfig c = full_bus();
  ProcessImage p;
  for (auto _ : state) {
    for (const Device& d : c.devices) {
      const std::span<const Word> in = in_slice(std::as_const(p), d);
      const std::span<Word> out = out_slice(p, d);
      for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<Word>(in[i] + 1U);
    }
    benchmark::DoNotOptimize(p.out.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_SliceAllDevices);

// One device's slice lookup alone.
void BM_SliceOneDevice(benchmark::State& state) {
  const BusConfig c = full_bus();
  ProcessImage p;
  const Device& d = c.devices[7];
  for (auto _ : state) {
    std::span<Word> s = out_slice(p, d);
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_SliceOneDevice);

// The DDI byte view over the whole input image.
void BM_ReadFullImageBytes(benchmark::State& state) {
  ProcessImage p;
  std::array<std::uint8_t, 512> bytes{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(p.read_bytes(Area::in, 0, bytes));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ReadFullImageBytes);

void BM_CycleTime(benchmark::State& state) {
  const BusConfig c = full_bus();
  for (auto _ : state) benchmark::DoNotOptimize(cycle_time(c));
}
BENCHMARK(BM_CycleTime);

}  // namespace
