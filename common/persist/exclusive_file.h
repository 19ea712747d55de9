// One writer at a time for a file or a folder: an exclusive flock(2) on a file, taken when a
// previous instance that is still dying (stopped, then terminated or killed by the supervisor)
// has let go. Used by the journal and by the RG kernel's state folder.
#pragma once

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>

namespace rgnav::persist {

// Opens `path` (read-write, created 0644, close-on-exec) and locks it exclusively, trying every
// 20 ms for up to `wait`. Returns the fd: closing it releases the lock. Throws
// std::runtime_error "<path>: cannot open<what>: <reason>" when the file cannot be opened, and
// `held_elsewhere` (the fd closed) when another live process keeps the lock or flock fails.
inline int open_exclusive(const std::string& path, const std::string& what, const std::string& held_elsewhere,
                          std::chrono::milliseconds wait = std::chrono::seconds(3))
{
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(path + ": cannot open" + what + ": " + std::strerror(errno));
  const auto deadline = std::chrono::steady_clock::now() + wait;
  while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK || std::chrono::steady_clock::now() > deadline) {
      ::close(fd);
      throw std::runtime_error(held_elsewhere);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return fd;
}

}  // namespace rgnav::persist
