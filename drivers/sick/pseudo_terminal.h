// A pseudo-terminal pair owned by a device emulator: the master side is the "device", the
// slave path is the serial port a driver opens. An optional symlink gives the port a stable
// name across close()/open() cycles, the way a udev rule names a USB-serial adapter; close()
// removes it, so a driver sees the port vanish exactly as when the adapter is unplugged.
#pragma once

#include <string>

namespace rgnav::drivers::sick {

class PseudoTerminal
{
 public:
  explicit PseudoTerminal(std::string symlink_path = "");
  ~PseudoTerminal();
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  // Creates a fresh pair (posix_openpt, grantpt, unlockpt), sets the slave raw and points
  // the symlink at it. Throws std::runtime_error on failure.
  void open();
  // Closes both sides (the driver's reads then fail with a hang-up) and removes the symlink.
  void close();
  bool is_open() const { return master_fd_ >= 0; }

  int master_fd() const { return master_fd_; }
  const std::string& slave_path() const { return slave_path_; }
  // The symlink if one was requested, else the slave path.
  std::string port_path() const { return symlink_path_.empty() ? slave_path_ : symlink_path_; }
  // Baud the slave side is currently set to (by whoever opened it), 0 if unknown.
  int slave_baud() const;

 private:
  std::string symlink_path_;
  std::string slave_path_;
  int master_fd_ = -1;
  // Held open so the pair survives the driver closing and reopening the port (otherwise the
  // master sees a hang-up) and so the termios the driver sets stay readable here.
  int slave_fd_ = -1;
};

}  // namespace rgnav::drivers::sick
