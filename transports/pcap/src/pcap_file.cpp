#include "ibs/pcap/pcap_file.hpp"

#include <chrono>
#include <cstdio>

#ifdef IBS_PCAP_HAVE_LIBPCAP
#include <pcap/pcap.h>
#endif

namespace ibs::pcap {

Time wall_clock_epoch() {
  return std::chrono::duration_cast<Time>(std::chrono::system_clock::now().time_since_epoch());
}

bool looks_like_pcap(std::span<const std::uint8_t> head) {
  if (head.size() < 4) return false;
  const std::uint32_t b0 = head[0];
  const std::uint32_t b1 = head[1];
  const std::uint32_t b2 = head[2];
  const std::uint32_t b3 = head[3];
  const std::uint32_t le = b0 | (b1 << 8U) | (b2 << 16U) | (b3 << 24U);
  const std::uint32_t be = (b0 << 24U) | (b1 << 16U) | (b2 << 8U) | b3;
  for (const std::uint32_t magic : {0xA1B2C3D4U, 0xA1B23C4DU}) {
    if (le == magic || be == magic) return true;
  }
  return le == 0x0A0D0D0AU;  // pcapng's section header block (the same bytes in either order)
}

#ifdef IBS_PCAP_HAVE_LIBPCAP

bool available() { return true; }

namespace {

// libpcap writes to a FILE*; this one passes every byte on to the std::ostream.
ssize_t cookie_write(void* cookie, const char* data, std::size_t size) {
  auto* out = static_cast<std::ostream*>(cookie);
  out->write(data, static_cast<std::streamsize>(size));
  return *out ? static_cast<ssize_t>(size) : -1;
}
int cookie_close(void* cookie) {
  auto* out = static_cast<std::ostream*>(cookie);
  out->flush();
  return *out ? 0 : -1;
}

}  // namespace

struct PcapFile::Handles {
  pcap_t* pcap = nullptr;
  pcap_dumper_t* dumper = nullptr;
  ~Handles() {
    if (dumper) pcap_dump_close(dumper);
    if (pcap) pcap_close(pcap);
  }
};

PcapFile::PcapFile(std::ostream& out, int linktype, Time epoch)
    : h_(std::make_unique<Handles>()), out_(out), epoch_(epoch) {
  h_->pcap = pcap_open_dead_with_tstamp_precision(linktype, 65535, PCAP_TSTAMP_PRECISION_NANO);
  if (h_->pcap == nullptr) throw PcapError("libpcap: pcap_open_dead(" + std::to_string(linktype) + ") failed");
  cookie_io_functions_t io{};
  io.write = cookie_write;
  io.close = cookie_close;
  FILE* f = fopencookie(&out_, "w", io);
  if (f == nullptr) throw PcapError("cannot open a stream for libpcap");
  h_->dumper = pcap_dump_fopen(h_->pcap, f);
  if (h_->dumper == nullptr) {
    std::fclose(f);
    throw PcapError(std::string("libpcap: ") + pcap_geterr(h_->pcap));
  }
}

PcapFile::~PcapFile() = default;

void PcapFile::write(Time at, std::span<const std::uint8_t> packet) {
  if (h_->dumper == nullptr) throw PcapError("the capture was closed already");
  pcap_pkthdr hdr{};
  const auto ns = (at.count() < 0 ? 0 : at.count()) + (epoch_.count() < 0 ? 0 : epoch_.count());
  hdr.ts.tv_sec = ns / 1'000'000'000;
  hdr.ts.tv_usec = ns % 1'000'000'000;  // nanoseconds in this precision
  hdr.caplen = static_cast<bpf_u_int32>(packet.size());
  hdr.len = static_cast<bpf_u_int32>(packet.size());
  pcap_dump(reinterpret_cast<u_char*>(h_->dumper), &hdr, packet.data());
  ++packets_;
}

void PcapFile::flush() {
  if (h_->dumper == nullptr) return;
  const bool flushed = pcap_dump_flush(h_->dumper) == 0;  // the FILE* into the stream
  out_.flush();
  if (!flushed || !out_) throw PcapError("cannot write the capture (disk full? a reader gone?)");
}

void PcapFile::close() {
  if (h_->dumper == nullptr) return;
  const bool flushed = pcap_dump_flush(h_->dumper) == 0;
  pcap_dump_close(h_->dumper);  // closes the FILE*, which flushes into the stream
  h_->dumper = nullptr;
  if (!flushed || !out_) throw PcapError("cannot write the capture (disk full?)");
}

Reading read_pcap(std::span<const std::uint8_t> file) {
  Reading r;
  if (file.empty()) {
    r.error = "an empty file";
    return r;
  }
  // libpcap reads a FILE*: the bytes in memory as one (read only; fmemopen does not write "rb").
  FILE* f = fmemopen(const_cast<std::uint8_t*>(file.data()), file.size(), "rb");
  if (f == nullptr) {
    r.error = "cannot open the bytes as a stream";
    return r;
  }
  char errbuf[PCAP_ERRBUF_SIZE] = "";
  pcap_t* p = pcap_fopen_offline_with_tstamp_precision(f, PCAP_TSTAMP_PRECISION_NANO, errbuf);
  if (p == nullptr) {
    std::fclose(f);  // not taken by libpcap when it refuses
    r.error = errbuf;
    return r;
  }
  r.linktype = pcap_datalink(p);
  for (;;) {
    pcap_pkthdr* hdr = nullptr;
    const u_char* data = nullptr;
    const int rc = pcap_next_ex(p, &hdr, &data);
    if (rc == PCAP_ERROR_BREAK) break;  // the end of the file
    if (rc != 1) {
      r.error = pcap_geterr(p);
      break;
    }
    Record rec;
    const std::int64_t sec = hdr->ts.tv_sec;  // time_t and suseconds_t: a long here, not everywhere
    const std::int64_t frac = hdr->ts.tv_usec;
    rec.at = Time{sec * 1'000'000'000 + frac};
    rec.original = hdr->len;
    rec.data.assign(data, data + hdr->caplen);
    r.records.push_back(std::move(rec));
  }
  pcap_close(p);  // closes `f` too
  return r;
}

#else

bool available() { return false; }

namespace {
constexpr const char* kNoLibpcap = "this ibs was built without libpcap (Debian package libpcap-dev): no captures";
}

struct PcapFile::Handles {};

PcapFile::PcapFile(std::ostream& out, int /*linktype*/, Time epoch) : out_(out), epoch_(epoch) {
  throw PcapError(kNoLibpcap);
}
PcapFile::~PcapFile() = default;
void PcapFile::write(Time /*at*/, std::span<const std::uint8_t> /*packet*/) {}
void PcapFile::flush() {}
void PcapFile::close() {}

Reading read_pcap(std::span<const std::uint8_t> /*file*/) {
  Reading r;
  r.error = kNoLibpcap;
  return r;
}

#endif

}  // namespace ibs::pcap
