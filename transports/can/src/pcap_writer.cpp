#include "ibs/can/pcap_writer.hpp"

#include <pcap/pcap.h>

#include <cstring>

namespace ibs::can {

struct PcapWriter::Handles {
  pcap_t* pcap = nullptr;
  pcap_dumper_t* dumper = nullptr;
  ~Handles() {
    if (dumper) pcap_dump_close(dumper);
    if (pcap) pcap_close(pcap);
  }
};

std::size_t socketcan_record(const canlust::CanFrame& f, std::uint8_t (&out)[16]) {
  std::memset(out, 0, sizeof out);
  const std::uint32_t id = (f.id & 0x7FFU) | (f.rtr ? 0x40000000U : 0U);
  out[0] = static_cast<std::uint8_t>(id >> 24U);
  out[1] = static_cast<std::uint8_t>(id >> 16U);
  out[2] = static_cast<std::uint8_t>(id >> 8U);
  out[3] = static_cast<std::uint8_t>(id);
  out[4] = f.dlc;  // then __pad, __res0, len8_dlc: 0
  const std::size_t n = f.rtr ? 0U : f.dlc;
  for (std::size_t i = 0; i < n; ++i) out[8 + i] = f.data[i];
  return 8 + n;
}

PcapWriter::PcapWriter(std::unique_ptr<Handles> h) : h_(std::move(h)) {}
PcapWriter::~PcapWriter() = default;

Opened<PcapWriter> PcapWriter::open(const std::string& path) {
  Opened<PcapWriter> r;
  auto h = std::make_unique<Handles>();
  h->pcap = pcap_open_dead(kLinktypeCanSocketcan, 65535);
  if (!h->pcap) {
    r.error = "pcap_open_dead(LINKTYPE_CAN_SOCKETCAN) failed";
    return r;
  }
  h->dumper = pcap_dump_open(h->pcap, path.c_str());
  if (!h->dumper) {
    r.error = "pcap_dump_open " + path + ": " + pcap_geterr(h->pcap);
    return r;
  }
  r.transport.reset(new PcapWriter(std::move(h)));
  return r;
}

void PcapWriter::write(const canlust::CanFrame& f, Time at) {
  std::uint8_t rec[16];
  const std::size_t n = socketcan_record(f, rec);
  pcap_pkthdr hdr{};
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(epoch_ + at).count();
  hdr.ts.tv_sec = us / 1'000'000;
  hdr.ts.tv_usec = us % 1'000'000;
  hdr.caplen = static_cast<bpf_u_int32>(n);
  hdr.len = static_cast<bpf_u_int32>(n);
  pcap_dump(reinterpret_cast<u_char*>(h_->dumper), &hdr, rec);
  ++records_;
}

void PcapWriter::flush() { pcap_dump_flush(h_->dumper); }

}  // namespace ibs::can
