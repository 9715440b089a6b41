#include "ibs/serial/serial_port.hpp"

#include <linux/serial.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <termios.h>
#include <unistd.h>

#include <asio.hpp>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "ibs/serial/byte_log.hpp"

namespace ibs::serial {

Framing parse_framing(std::string_view text) {
  const auto bad = [&]() {
    return std::invalid_argument(
        "framing '" + std::string(text) +
        "': expected data bits 5-8, parity N/E/O, stop bits 1-2 (8N1, 7E1)");
  };
  if (text.size() != 3) throw bad();
  Framing f;
  if (text[0] < '5' || text[0] > '8') throw bad();
  f.data_bits = text[0] - '0';
  switch (text[1]) {
    case 'N':
    case 'n':
      f.parity = Parity::none;
      break;
    case 'E':
    case 'e':
      f.parity = Parity::even;
      break;
    case 'O':
    case 'o':
      f.parity = Parity::odd;
      break;
    default:
      throw bad();
  }
  if (text[2] != '1' && text[2] != '2') throw bad();
  f.stop_bits = text[2] - '0';
  return f;
}

std::string to_string(const Framing& f) {
  std::string s = std::to_string(f.data_bits);
  s += f.parity == Parity::none ? 'N' : f.parity == Parity::even ? 'E' : 'O';
  s += std::to_string(f.stop_bits);
  return s;
}

struct SerialPort::Impl {
  asio::io_context io;
  asio::serial_port port{io};
  std::string name;
  bool pty = false;
  Rs485Status rs485 = Rs485Status::not_requested;
  std::vector<std::string> notes;
  ByteLog* log = nullptr;
  ByteTap* tap = nullptr;
  std::uint32_t baud = 0;
};

namespace {

// Unix98 pty slaves have majors 136..143; a master answers TIOCGPTN.
bool detect_pty(int fd) {
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISCHR(st.st_mode)) {
    const unsigned m = major(st.st_rdev);
    if (m >= 136 && m <= 143) return true;
  }
  unsigned n = 0;
  return ::ioctl(fd, TIOCGPTN, &n) == 0;
}

[[noreturn]] void fail(const std::string& name, const std::string& what,
                       const std::error_code& ec) {
  throw std::runtime_error("serial port " + name + ": " + what + ": " + ec.message());
}

template <class Option>
void apply(SerialPort::Impl& p, const Option& option, const std::string& what) {
  asio::error_code ec;
  p.port.set_option(option, ec);
  if (!ec) return;
  if (p.pty) {
    p.notes.push_back(what + " not supported (pty), ignored");
    return;
  }
  fail(p.name, "cannot set " + what, ec);
}

void configure(SerialPort::Impl& p, const PortOptions& o) {
  using B = asio::serial_port_base;
  p.pty = detect_pty(p.port.native_handle());
  p.baud = o.baud;
  apply(p, B::baud_rate(o.baud), std::to_string(o.baud) + " baud");
  apply(p, B::character_size(static_cast<unsigned>(o.framing.data_bits)),
        std::to_string(o.framing.data_bits) + " data bits");
  apply(p,
        B::parity(o.framing.parity == Parity::none   ? B::parity::none
                  : o.framing.parity == Parity::even ? B::parity::even
                                                     : B::parity::odd),
        "parity");
  apply(p, B::stop_bits(o.framing.stop_bits == 2 ? B::stop_bits::two : B::stop_bits::one),
        "stop bits");
  apply(p, B::flow_control(B::flow_control::none), "flow control");
  if (o.rs485) {
    // The driver switches the transmitter on while it sends (libmodbus's first choice).
    serial_rs485 rs{};
    rs.flags = SER_RS485_ENABLED | SER_RS485_RTS_ON_SEND;
    if (::ioctl(p.port.native_handle(), TIOCSRS485, &rs) == 0) {
      p.rs485 = Rs485Status::enabled;
    } else {
      p.rs485 = Rs485Status::not_supported;
      p.notes.push_back(std::string("RS-485 direction control (TIOCSRS485) not supported: ") +
                        std::strerror(errno));
    }
  }
}

}  // namespace

SerialPort::SerialPort(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SerialPort::SerialPort(SerialPort&&) noexcept = default;
SerialPort& SerialPort::operator=(SerialPort&&) noexcept = default;
SerialPort::~SerialPort() = default;

SerialPort SerialPort::open(const std::string& path, const PortOptions& options) {
  auto impl = std::make_unique<Impl>();
  impl->name = path;
  asio::error_code ec;
  impl->port.open(path, ec);
  if (ec) fail(path, "cannot open", ec);
  configure(*impl, options);
  return SerialPort(std::move(impl));
}

SerialPort SerialPort::adopt(int fd, const std::string& name, const PortOptions& options) {
  auto impl = std::make_unique<Impl>();
  impl->name = name;
  asio::error_code ec;
  impl->port.assign(fd, ec);
  if (ec) fail(name, "cannot take the descriptor", ec);
  configure(*impl, options);
  return SerialPort(std::move(impl));
}

void SerialPort::set_baud(std::uint32_t baud) {
  Impl& p = *impl_;
  if (baud == p.baud) return;
  ::tcdrain(p.port.native_handle());
  p.baud = baud;
  const std::size_t notes = p.notes.size();
  apply(p, asio::serial_port_base::baud_rate(baud), std::to_string(baud) + " baud");
  p.notes.resize(notes);  // a pty's "not supported" was said at open already
}

std::uint32_t SerialPort::baud() const { return impl_->baud; }

std::size_t SerialPort::read(std::span<std::uint8_t> buf, std::chrono::nanoseconds timeout) {
  Impl& p = *impl_;
  std::size_t got = 0;
  asio::error_code result;
  bool done = false;
  p.port.async_read_some(asio::buffer(buf.data(), buf.size()),
                         [&](const asio::error_code& ec, std::size_t n) {
                           result = ec;
                           got = n;
                           done = true;
                         });
  p.io.restart();
  p.io.run_for(timeout);
  if (!done) {
    p.port.cancel();
    p.io.restart();
    p.io.run();  // the cancelled read completes with operation_aborted, or with data that raced
  }
  if (result && result != asio::error::operation_aborted) {
    throw std::system_error(result, "serial port " + p.name + ": read");
  }
  if (got > 0 && p.log != nullptr) p.log->record(Direction::rx, p.name, buf.first(got));
  if (got > 0 && p.tap != nullptr) p.tap->bytes(Direction::rx, buf.first(got));
  return got;
}

void SerialPort::write(std::span<const std::uint8_t> bytes) {
  Impl& p = *impl_;
  asio::error_code ec;
  asio::write(p.port, asio::buffer(bytes.data(), bytes.size()), ec);
  if (ec) throw std::system_error(ec, "serial port " + p.name + ": write");
  if (p.log != nullptr) p.log->record(Direction::tx, p.name, bytes);
  if (p.tap != nullptr && !bytes.empty()) p.tap->bytes(Direction::tx, bytes);
  ::tcdrain(p.port.native_handle());  // a pty may refuse; the bytes are in its buffer then
}

void SerialPort::discard_input() {
  ::tcflush(impl_->port.native_handle(), TCIFLUSH);
}

const std::string& SerialPort::name() const {
  return impl_->name;
}
bool SerialPort::is_pty() const {
  return impl_->pty;
}
Rs485Status SerialPort::rs485() const {
  return impl_->rs485;
}
const std::vector<std::string>& SerialPort::notes() const {
  return impl_->notes;
}
int SerialPort::native_handle() const {
  return impl_->port.native_handle();
}
void SerialPort::set_log(ByteLog* log) {
  impl_->log = log;
}
void SerialPort::set_tap(ByteTap* tap) {
  impl_->tap = tap;
}

}  // namespace ibs::serial
