// sockaddr_un handling shared by the broker and its clients: filesystem paths and, with a
// leading '@', Linux abstract-namespace names (no file to clean up, gone with the process).
#pragma once

#include <sys/socket.h>
#include <sys/un.h>

#include <string>

namespace rgnav::can::vcan {

struct UnixAddress
{
  sockaddr_un addr{};
  socklen_t len = 0;
  bool abstract = false;
};

// Throws CanError if the path is empty or too long.
UnixAddress make_unix_address(const std::string& path);

}  // namespace rgnav::can::vcan
