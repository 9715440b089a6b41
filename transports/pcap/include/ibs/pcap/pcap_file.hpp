// pcap files through libpcap (docs/pcap.md): PcapFile writes one, with nanosecond timestamps
// under any link type, into a std::ostream (an OutputFiles stream, so that the file appears all or
// nothing, or a command's standard output); read_pcap() reads a whole one held in memory, pcap or
// pcapng as libpcap reads them, every record with its time in nanoseconds. The INTERBUS capture
// (sim/pcap_recorder.hpp) and the serial lines' (serial/capture.hpp) are written through it.
// Recording and reading are not the cycle path: they allocate and throw.
#pragma once

#include <cstdint>
#include <memory>
#include <ostream>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "ibs/base/time.hpp"

namespace ibs::pcap {

class PcapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Whether this build reads and writes pcap files (libpcap was found at configuration time).
bool available();

// Now as nanoseconds since 1970 (the system clock), for PcapFile's epoch: read once, at a run's start.
Time wall_clock_epoch();

// A pcap file with nanosecond timestamps (magic A1B23C4DH) under `linktype`, written through
// libpcap to `out`. A packet's timestamp is `epoch` (the wall-clock start of the run, as
// nanoseconds since 1970; 0 writes the bare run time) plus its time in the run, so that
// Wireshark's absolute view shows when it happened. Throws PcapError when libpcap refuses or this
// build has no libpcap.
class PcapFile {
 public:
  PcapFile(std::ostream& out, int linktype, Time epoch = Time{0});
  ~PcapFile();
  PcapFile(const PcapFile&) = delete;
  PcapFile& operator=(const PcapFile&) = delete;

  void write(Time at, std::span<const std::uint8_t> packet);
  // Everything written so far into the stream and the stream flushed (a live capture on a pipe:
  // the reader sees each packet as it comes); throws PcapError when the stream failed.
  void flush();
  // Flushes and closes the file; throws PcapError when the stream failed.
  void close();
  [[nodiscard]] std::uint64_t packets() const { return packets_; }

 private:
  struct Handles;
  std::unique_ptr<Handles> h_;
  std::ostream& out_;
  Time epoch_{0};
  std::uint64_t packets_ = 0;
};

// ---- reading ------------------------------------------------------------------------------------

// Whether `head` (a file's first bytes) opens as a pcap file (either byte order, microsecond or
// nanosecond magic) or a pcapng file.
bool looks_like_pcap(std::span<const std::uint8_t> head);

struct Record {
  Time at{0};                    // the timestamp: nanoseconds since 1970 (or since 0 for a bare run time)
  std::uint32_t original = 0;    // the packet's length on the wire (more than data.size() when cut by the snap length)
  std::vector<std::uint8_t> data;
};

struct Reading {
  int linktype = -1;             // the file's link-layer type (LINKTYPE_*); -1 when it could not be opened
  std::vector<Record> records;   // every record read, in file order
  std::string error;             // empty: the file was read to its end; else why reading stopped
};

// The capture in `file`; never throws for bad input: `error` says what libpcap refused (a file
// that is no capture, a record cut short), with the records read before it. A build without
// libpcap reads nothing and says so.
Reading read_pcap(std::span<const std::uint8_t> file);

}  // namespace ibs::pcap
