#include <iostream>

#include "commands.hpp"
#include "ibs/devices/trace_adapters.hpp"

namespace ibs::cli {

int replay(const std::string& emulate, const std::string& file) {
  try {
    const trace::Trace t = trace::load(file);
    const auto explainer = devices::make_explainer(t);
    trace::ReplayResult r;
    if (emulate == "device") {
      const auto device = devices::make_device_side(t);
      r = trace::replay_device(t, *device, *explainer);
    } else {
      const auto master = devices::make_master_side(t);
      r = trace::replay_master(t, *master, *explainer);
    }
    if (!r.matched) {
      std::cout << r.message << "\n";
      std::cout << "replay: " << r.steps_matched << " steps matched before the mismatch\n";
      return kExitMismatch;
    }
    std::cout << r.message << "\n";
    return kExitOk;
  } catch (const trace::TraceError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
}

int decode(const std::string& file) {
  try {
    const trace::Trace t = trace::load(file);
    const auto explainer = devices::make_explainer(t);
    std::cout << trace::write(trace::decode(t, *explainer));
    return kExitOk;
  } catch (const trace::TraceError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
}

}  // namespace ibs::cli
