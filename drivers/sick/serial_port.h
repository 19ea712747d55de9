// A serial port in raw 8N1 mode, opened non-blocking, closed by the destructor. Works on real
// UARTs, USB adapters and pseudo-terminals (a pty accepts the termios calls; its "baud rate"
// is only recorded, which is what lets the LMS emulator notice a host at the wrong rate).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace rgnav::drivers::sick {

class SerialError : public std::runtime_error
{
 public:
  using std::runtime_error::runtime_error;
};

// True for the rates termios can express that the LMS 2xx also speaks.
bool serial_baud_supported(int bps);

class SerialPort
{
 public:
  // Throws SerialError (with errno text) when the port cannot be opened or configured.
  SerialPort(const std::string& path, int bps);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;
  SerialPort(SerialPort&& other) noexcept;
  SerialPort& operator=(SerialPort&& other) noexcept;

  // Sets input and output speed; throws SerialError.
  void set_baud(int bps);
  int baud() const { return bps_; }

  enum class ReadStatus { kData, kNoData, kClosed };
  struct ReadResult
  {
    ReadStatus status;
    size_t size;
  };
  // Non-blocking: what is there now (kNoData if nothing), kClosed when the device vanished
  // (hang-up, EOF, EIO — an unplugged USB adapter or a closed pty master).
  ReadResult read_some(uint8_t* buf, size_t capacity);
  // Waits up to `timeout` for input; false on timeout. Throws SerialError on poll failure.
  bool wait_readable(std::chrono::milliseconds timeout) const;
  // Writes all bytes (waiting for room at most `timeout`); false if the device vanished or
  // the write did not complete in time.
  bool write_all(const uint8_t* data, size_t size, std::chrono::milliseconds timeout = std::chrono::milliseconds(500));
  // Discards unread input and unsent output.
  void flush();

  int fd() const { return fd_; }
  const std::string& path() const { return path_; }

 private:
  void close_fd();
  int fd_ = -1;
  int bps_ = 0;
  std::string path_;
};

}  // namespace rgnav::drivers::sick
