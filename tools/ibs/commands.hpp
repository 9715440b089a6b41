// The `ibs` subcommands. Each returns the process exit code.
#pragma once

#include <cstdint>
#include <string>

namespace ibs::cli {

// Exit codes shared by all subcommands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitMismatch = 1;  // replay: a row did not match
inline constexpr int kExitBadInput = 2;  // malformed file, bad option, refused configuration

struct RunOptions {
  std::string scenario;   // empty: the built-in default scenario
  bool json = false;
  std::string trace_dir;  // empty: no traces
  std::string vcd_file;   // empty: no VCD
  unsigned threads = 1;   // device-stepping threads (sim::SimOptions::threads): 0 = automatic
};

struct CampaignOptions {
  std::uint64_t seed = 1;
  std::uint64_t transactions = 100000;
  bool json = false;
  bool enable_during_download = false;
};

int replay(const std::string& emulate, const std::string& file);
int decode(const std::string& file);
int run(const RunOptions& options);
// The fault campaign (sim/campaign.hpp): exit 1 when a check failed.
int campaign(const CampaignOptions& options);

}  // namespace ibs::cli
