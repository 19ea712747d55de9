#include "bus/socket_can.h"

#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "bus/can_frames.h"

namespace rgnav::can {

namespace {

// Always watched, whatever the caller asked for: bus-off tracking depends on them.
constexpr can_err_mask_t kInternalErrors = CAN_ERR_BUSOFF | CAN_ERR_RESTARTED;

}  // namespace

bool SocketCan::kernel_supports_can(std::string* why)
{
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    if (why) *why = errno_text("socket(PF_CAN, SOCK_RAW, CAN_RAW)");
    return false;
  }
  ::close(fd);
  return true;
}

SocketCan::SocketCan(const std::string& ifname) : ifname_(ifname)
{
  if (ifname.empty() || ifname.size() >= IFNAMSIZ) throw CanError("SocketCAN: bad interface name '" + ifname + "'");
  fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC | SOCK_NONBLOCK, CAN_RAW);
  if (fd_ < 0) throw CanError(errno_text("SocketCAN " + ifname + ": socket(PF_CAN, SOCK_RAW, CAN_RAW)"));
  ifreq ifr;
  std::memset(&ifr, 0, sizeof ifr);
  std::strncpy(ifr.ifr_name, ifname.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd_, SIOCGIFINDEX, &ifr) < 0) {
    const std::string msg = errno_text("SocketCAN " + ifname + ": no such CAN interface");
    ::close(fd_);
    throw CanError(msg);
  }
  sockaddr_can addr;
  std::memset(&addr, 0, sizeof addr);
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) {
    const std::string msg = errno_text("SocketCAN " + ifname + ": bind");
    ::close(fd_);
    throw CanError(msg);
  }
  apply_error_mask();
}

SocketCan::~SocketCan()
{
  if (fd_ >= 0) ::close(fd_);
}

void SocketCan::apply_error_mask()
{
  const can_err_mask_t mask = user_error_mask_ | kInternalErrors;
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &mask, sizeof mask) < 0)
    throw CanError(errno_text("SocketCAN " + ifname_ + ": CAN_RAW_ERR_FILTER"));
}

void SocketCan::set_error_mask(can_err_mask_t mask)
{
  user_error_mask_ = mask & CAN_ERR_MASK;
  apply_error_mask();
}

void SocketCan::set_filters(const std::vector<can_filter>& filters)
{
  // An empty filter list is a zero-length option: the kernel then passes no data frames.
  const void* data = filters.empty() ? nullptr : filters.data();
  const auto len = static_cast<socklen_t>(filters.size() * sizeof(can_filter));
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, data, len) < 0)
    throw CanError(errno_text("SocketCAN " + ifname_ + ": CAN_RAW_FILTER"));
}

bool SocketCan::send(const can_frame& frame, std::chrono::milliseconds timeout)
{
  if (bus_off_) return false;
  pollfd p{fd_, POLLOUT, 0};
  if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return false;
  const ssize_t n = ::write(fd_, &frame, sizeof frame);
  return n == static_cast<ssize_t>(sizeof frame);
}

std::optional<can_frame> SocketCan::receive(std::chrono::milliseconds timeout)
{
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    can_frame f;
    const ssize_t n = ::read(fd_, &f, sizeof f);
    if (n == static_cast<ssize_t>(sizeof f)) {
      if (!is_error_frame(f)) return f;
      const ErrorFrameInfo info = classify_error(f);
      if (info.bus_off) bus_off_ = true;
      if (info.restarted) bus_off_ = false;
      if (passes_error_mask(f, user_error_mask_)) return f;
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
      throw CanError(errno_text("SocketCAN " + ifname_ + ": read"));
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return std::nullopt;
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return std::nullopt;
  }
}

}  // namespace rgnav::can
