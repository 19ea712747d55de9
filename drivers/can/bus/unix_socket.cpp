#include "bus/unix_socket.h"

#include <cstddef>
#include <cstring>

#include "bus/can_interface.h"
#include "bus/vcan_protocol.h"

namespace rgnav::can::vcan {

std::string default_socket_path(const std::string& bus_name) { return "/tmp/rgnav-vcan-" + bus_name + ".sock"; }

UnixAddress make_unix_address(const std::string& path)
{
  UnixAddress a;
  a.addr.sun_family = AF_UNIX;
  if (path.empty() || path == "@") throw CanError("virtual CAN: empty socket path");
  if (path.size() >= sizeof(a.addr.sun_path)) throw CanError("virtual CAN: socket path too long: " + path);
  a.abstract = path[0] == '@';
  if (a.abstract) {
    // Abstract names start with a NUL byte and are exactly as long as len says.
    a.addr.sun_path[0] = '\0';
    std::memcpy(a.addr.sun_path + 1, path.data() + 1, path.size() - 1);
    a.len = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + path.size());
  } else {
    std::memcpy(a.addr.sun_path, path.data(), path.size());
    a.len = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + path.size() + 1);
  }
  return a;
}

}  // namespace rgnav::can::vcan
