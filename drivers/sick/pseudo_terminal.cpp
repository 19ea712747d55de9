#include "pseudo_terminal.h"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace rgnav::drivers::sick {

namespace {

std::runtime_error sys_error(const std::string& what) { return std::runtime_error(what + ": " + std::strerror(errno)); }

int speed_to_bps(speed_t s)
{
  switch (s) {
    case B9600: return 9600;
    case B19200: return 19200;
    case B38400: return 38400;
#ifdef B500000
    case B500000: return 500000;
#endif
    default: return 0;
  }
}

}  // namespace

PseudoTerminal::PseudoTerminal(std::string symlink_path) : symlink_path_(std::move(symlink_path)) {}

PseudoTerminal::~PseudoTerminal() { close(); }

void PseudoTerminal::open()
{
  close();
  master_fd_ = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (master_fd_ < 0) throw sys_error("posix_openpt");
  if (grantpt(master_fd_) != 0 || unlockpt(master_fd_) != 0) {
    const auto e = sys_error("grantpt/unlockpt");
    close();
    throw e;
  }
  char name[128] = {0};
  if (ptsname_r(master_fd_, name, sizeof name) != 0) {
    const auto e = sys_error("ptsname_r");
    close();
    throw e;
  }
  slave_path_ = name;
  slave_fd_ = ::open(name, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (slave_fd_ < 0) {
    const auto e = sys_error("open " + slave_path_);
    close();
    throw e;
  }
  // Raw from the start: no echo back to the device, no line discipline between the two.
  termios tio{};
  tcgetattr(slave_fd_, &tio);
  cfmakeraw(&tio);
  tcsetattr(slave_fd_, TCSANOW, &tio);
  if (!symlink_path_.empty()) {
    // Atomic replace: a driver never sees a half-made link.
    const std::string tmp = symlink_path_ + ".tmp" + std::to_string(getpid());
    ::unlink(tmp.c_str());
    if (::symlink(slave_path_.c_str(), tmp.c_str()) != 0 || ::rename(tmp.c_str(), symlink_path_.c_str()) != 0) {
      const auto e = sys_error("symlink " + symlink_path_);
      close();
      throw e;
    }
  }
}

void PseudoTerminal::close()
{
  if (!symlink_path_.empty() && master_fd_ >= 0) ::unlink(symlink_path_.c_str());
  if (slave_fd_ >= 0) ::close(slave_fd_);
  if (master_fd_ >= 0) ::close(master_fd_);
  slave_fd_ = -1;
  master_fd_ = -1;
}

int PseudoTerminal::slave_baud() const
{
  if (slave_fd_ < 0) return 0;
  termios tio{};
  if (tcgetattr(slave_fd_, &tio) != 0) return 0;
  return speed_to_bps(cfgetospeed(&tio));
}

}  // namespace rgnav::drivers::sick
