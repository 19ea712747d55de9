#include "serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace rgnav::drivers::sick {

namespace {

speed_t to_speed(int bps)
{
  switch (bps) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
#ifdef B500000
    case 500000: return B500000;
#endif
    default: return B0;
  }
}

std::string errno_text(const std::string& what, const std::string& path)
{
  return what + " " + path + ": " + std::strerror(errno);
}

}  // namespace

bool serial_baud_supported(int bps) { return to_speed(bps) != B0; }

SerialPort::SerialPort(const std::string& path, int bps) : path_(path)
{
  if (!serial_baud_supported(bps)) throw SerialError("unsupported baud rate " + std::to_string(bps));
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw SerialError(errno_text("cannot open", path));
  termios tio{};
  if (tcgetattr(fd_, &tio) != 0) {
    const std::string msg = errno_text("not a serial port:", path);
    close_fd();
    throw SerialError(msg);
  }
  cfmakeraw(&tio);  // 8 data bits, no parity, no echo, no translation
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS | PARENB);
  tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 1;  // with O_NONBLOCK: EAGAIN when empty, 0 only on hang-up
  tio.c_cc[VTIME] = 0;
  if (tcsetattr(fd_, TCSANOW, &tio) != 0) {
    const std::string msg = errno_text("cannot configure", path);
    close_fd();
    throw SerialError(msg);
  }
  set_baud(bps);
  flush();
}

SerialPort::~SerialPort() { close_fd(); }

SerialPort::SerialPort(SerialPort&& other) noexcept : fd_(other.fd_), bps_(other.bps_), path_(std::move(other.path_))
{
  other.fd_ = -1;
}

SerialPort& SerialPort::operator=(SerialPort&& other) noexcept
{
  if (this != &other) {
    close_fd();
    fd_ = other.fd_;
    bps_ = other.bps_;
    path_ = std::move(other.path_);
    other.fd_ = -1;
  }
  return *this;
}

void SerialPort::close_fd()
{
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void SerialPort::set_baud(int bps)
{
  const speed_t speed = to_speed(bps);
  if (speed == B0) throw SerialError("unsupported baud rate " + std::to_string(bps));
  termios tio{};
  if (tcgetattr(fd_, &tio) != 0) throw SerialError(errno_text("tcgetattr", path_));
  cfsetispeed(&tio, speed);
  cfsetospeed(&tio, speed);
  // TCSADRAIN: a request sent just before the switch still leaves at the old rate.
  if (tcsetattr(fd_, TCSADRAIN, &tio) != 0) throw SerialError(errno_text("cannot set baud on", path_));
  bps_ = bps;
}

SerialPort::ReadResult SerialPort::read_some(uint8_t* buf, size_t capacity)
{
  for (;;) {
    const ssize_t n = ::read(fd_, buf, capacity);
    if (n > 0) return {ReadStatus::kData, static_cast<size_t>(n)};
    if (n == 0) return {ReadStatus::kClosed, 0};
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return {ReadStatus::kNoData, 0};
    return {ReadStatus::kClosed, 0};  // EIO, ENXIO, ENODEV: the device is gone
  }
}

bool SerialPort::wait_readable(std::chrono::milliseconds timeout) const
{
  pollfd p{fd_, POLLIN, 0};
  for (;;) {
    const int r = ::poll(&p, 1, static_cast<int>(timeout.count()));
    if (r >= 0) return r > 0;
    if (errno != EINTR) throw SerialError(errno_text("poll", path_));
  }
}

bool SerialPort::write_all(const uint8_t* data, size_t size, std::chrono::milliseconds timeout)
{
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd_, data + done, size - done);
    if (n > 0) {
      done += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) return false;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd_, POLLOUT, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) < 0 && errno != EINTR) return false;
    if (p.revents & (POLLHUP | POLLERR)) return false;
  }
  return true;
}

void SerialPort::flush() { tcflush(fd_, TCIOFLUSH); }

}  // namespace rgnav::drivers::sick
