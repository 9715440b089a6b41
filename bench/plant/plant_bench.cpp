// One MC6000 plant step (1 ms of simulated time), in the torque limit and in the linear mode.
#include <benchmark/benchmark.h>

#include "ibs/devices/mc6000/plant.hpp"

namespace {

using namespace ibs::devices;

void BM_PlantStepLinear(benchmark::State& state) {
  DrivePlant plant;
  for (int k = 0; k < 1000; ++k) plant.step({2500.25, 0.0, true});  // settled: linear mode
  const PlantInput in{2500.25, 0.5, true};
  for (auto _ : state) benchmark::DoNotOptimize(plant.step(in));
}
BENCHMARK(BM_PlantStepLinear);

void BM_PlantStepLimited(benchmark::State& state) {
  DrivePlant plant;
  for (auto _ : state) {
    // A reference far away keeps the command clipped; reset keeps the state bounded.
    benchmark::DoNotOptimize(plant.step({1.0e9, 0.0, true}));
    if (plant.state()(0) > 1.0e5) plant.reset();
  }
}
BENCHMARK(BM_PlantStepLimited);

void BM_PlantConstruct(benchmark::State& state) {
  for (auto _ : state) {
    DrivePlant plant;
    benchmark::DoNotOptimize(plant.discrete(DrivePlant::Mode::linear).a(0, 0));
  }
}
BENCHMARK(BM_PlantConstruct);

}  // namespace
