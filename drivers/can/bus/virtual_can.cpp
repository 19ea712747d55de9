#include "bus/virtual_can.h"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <thread>

#include "bus/can_frames.h"
#include "bus/unix_socket.h"
#include "bus/vcan_protocol.h"

namespace rgnav::can {

namespace {

using Clock = std::chrono::steady_clock;

int ms_until(Clock::time_point t)
{
  const auto d = std::chrono::duration_cast<std::chrono::milliseconds>(t - Clock::now()).count();
  return d < 0 ? 0 : static_cast<int>(d);
}

}  // namespace

VirtualCan::VirtualCan(VirtualCanOptions options) : options_(std::move(options))
{
  filters_ = {can_filter{0, 0}};  // pass everything, like a fresh CAN_RAW socket
  vcan::make_unix_address(options_.path);  // validates the path (throws)
  const auto deadline = Clock::now() + options_.connect_timeout;
  while (!try_connect()) {
    if (Clock::now() >= deadline)
      throw CanError("virtual CAN: no broker on " + options_.path + " (start vcan_broker first)");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

VirtualCan::~VirtualCan()
{
  if (fd_ >= 0) ::close(fd_);
}

bool VirtualCan::try_connect()
{
  const vcan::UnixAddress a = vcan::make_unix_address(options_.path);
  const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) return false;
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&a.addr), a.len) < 0) {
    ::close(fd);
    return false;
  }
  fd_ = fd;
  if (!options_.client_name.empty())
    send_control(static_cast<uint32_t>(vcan::ControlOp::kHello), 0, 0, 0, options_.client_name);
  return fd_ >= 0;
}

void VirtualCan::lost_connection()
{
  if (fd_ < 0) return;
  ::close(fd_);
  fd_ = -1;
  if (!bus_off_) synthetic_.push_back(make_error_frame(CAN_ERR_BUSOFF));
  bus_off_ = true;
  next_reconnect_ = Clock::now() + options_.reconnect_interval;
}

bool VirtualCan::send(const can_frame& frame, std::chrono::milliseconds timeout)
{
  if (fd_ < 0 || bus_off_ || is_error_frame(frame) || frame.can_dlc > CAN_MAX_DLEN) return false;
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    const ssize_t n = ::send(fd_, &frame, sizeof frame, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n == static_cast<ssize_t>(sizeof frame)) return true;
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      lost_connection();
      return false;
    }
    pollfd p{fd_, POLLOUT, 0};
    const int wait = ms_until(deadline);
    if (wait == 0 || ::poll(&p, 1, wait) <= 0) return false;
  }
}

bool VirtualCan::accept(const can_frame& f)
{
  if (is_error_frame(f)) {
    const ErrorFrameInfo info = classify_error(f);
    if (info.bus_off) bus_off_ = true;
    if (info.restarted) bus_off_ = false;
    return passes_error_mask(f, error_mask_);
  }
  return passes_filters(f, filters_);
}

std::optional<can_frame> VirtualCan::receive(std::chrono::milliseconds timeout)
{
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    while (!synthetic_.empty()) {
      const can_frame f = synthetic_.front();
      synthetic_.pop_front();
      if (passes_error_mask(f, error_mask_)) return f;
    }
    if (fd_ < 0) {
      if (options_.reconnect_interval.count() > 0 && Clock::now() >= next_reconnect_) {
        if (try_connect()) {
          bus_off_ = false;
          synthetic_.push_back(make_error_frame(CAN_ERR_RESTARTED));
          continue;
        }
        next_reconnect_ = Clock::now() + options_.reconnect_interval;
      }
      int wait = ms_until(deadline);
      if (options_.reconnect_interval.count() > 0) wait = std::min(wait, ms_until(next_reconnect_));
      if (ms_until(deadline) == 0) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(std::max(wait, 1)));
      continue;
    }
    can_frame f;
    const ssize_t n = ::recv(fd_, &f, sizeof f, MSG_DONTWAIT);
    if (n == static_cast<ssize_t>(sizeof f)) {
      if (accept(f)) return f;
      continue;
    }
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
      lost_connection();
      continue;
    }
    if (n > 0) continue;  // not a frame: ignore
    const int wait = ms_until(deadline);
    if (wait == 0) return std::nullopt;
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, wait) <= 0) return std::nullopt;
  }
}

bool VirtualCan::send_control(uint32_t op, uint32_t a0, uint32_t a1, uint32_t a2, const std::string& name)
{
  if (fd_ < 0) return false;
  vcan::VcanControl ctl;
  ctl.op = op;
  ctl.arg0 = a0;
  ctl.arg1 = a1;
  ctl.arg2 = a2;
  std::strncpy(ctl.name, name.c_str(), sizeof ctl.name - 1);
  pollfd p{fd_, POLLOUT, 0};
  if (::poll(&p, 1, 100) <= 0) return false;
  return ::send(fd_, &ctl, sizeof ctl, MSG_DONTWAIT | MSG_NOSIGNAL) == static_cast<ssize_t>(sizeof ctl);
}

bool VirtualCan::request_drop_frames(canid_t can_id, canid_t mask, int64_t count)
{
  const uint32_t n = count < 0 ? 0xFFFFFFFFu : static_cast<uint32_t>(std::min<int64_t>(count, 0xFFFFFFFEu));
  return send_control(static_cast<uint32_t>(vcan::ControlOp::kDropFrames), can_id, mask, n, "");
}

bool VirtualCan::request_clear_drops()
{
  return send_control(static_cast<uint32_t>(vcan::ControlOp::kClearDrops), 0, 0, 0, "");
}

bool VirtualCan::request_inject_error(can_err_mask_t error_class, uint8_t controller_detail)
{
  return send_control(static_cast<uint32_t>(vcan::ControlOp::kInjectError), error_class, controller_detail, 0, "");
}

bool VirtualCan::request_bus_off(const std::string& client_name, std::chrono::milliseconds duration)
{
  return send_control(static_cast<uint32_t>(vcan::ControlOp::kBusOff), static_cast<uint32_t>(duration.count()), 0, 0,
                      client_name);
}

bool VirtualCan::request_disconnect(const std::string& client_name)
{
  return send_control(static_cast<uint32_t>(vcan::ControlOp::kDisconnect), 0, 0, 0, client_name);
}

}  // namespace rgnav::can
