// `emulate --json` of `ibs lustbus`, `ibs dfs1` and `ibs canlust` (docs/lustbus.md, docs/dfs1.md
// and docs/canlust.md, "Events as JSON"): one JSON object a line on standard output per event, in
// one shape for every bus, so that a program follows an emulator's line without reading its text.
// Every object has `time_s` (seconds since the emulator began to serve) and `event`; an event of
// one drive has its `device` (as given, `vf1000@1`) and `address` (the LUSTBUS address, the DFS-1
// UID, the CANLust 571-CLADR). Errors stay on standard error as text.
//
// The emulators' loops are the tool's own (floor 4, steady clock, real ports); printing allocates
// there as the byte log of --log does. The serial lines' watcher is watched_line_device.hpp.
#pragma once

#include <chrono>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <string_view>

#include "ibs/base/time.hpp"

namespace ibs::cli {

class EmulateEvents {
 public:
  explicit EmulateEvents(std::ostream& out) : out_(out) {}

  // An object with `time_s` and `event`; the caller adds the rest and print()s it.
  [[nodiscard]] static nlohmann::ordered_json event(Time at, std::string_view what) {
    nlohmann::ordered_json j;
    j["time_s"] = std::chrono::duration<double>(at).count();
    j["event"] = std::string(what);
    return j;
  }
  // The same for one drive.
  [[nodiscard]] static nlohmann::ordered_json event(Time at, std::string_view what, const std::string& device,
                                                    unsigned address) {
    nlohmann::ordered_json j = event(at, what);
    j["device"] = device;
    j["address"] = address;
    return j;
  }
  // Where the emulator serves, its first line: `pty: PATH` / `port: PATH` (and `pty link: PATH`),
  // or with --json the `serving` event that says the same.
  void serving(bool json, const std::string& key, const std::string& path, const std::string& link) {
    if (!json) {
      out_ << key << ": " << path << "\n";
      if (!link.empty()) out_ << "pty link: " << link << "\n";
      out_ << std::flush;
      return;
    }
    nlohmann::ordered_json j = event(Time{0}, "serving");
    j[key] = path;
    if (!link.empty()) j["pty_link"] = link;
    print(j);
  }
  void print(const nlohmann::ordered_json& j) { out_ << j.dump() << '\n' << std::flush; }

 private:
  std::ostream& out_;
};

}  // namespace ibs::cli
