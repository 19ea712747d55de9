#include "bus/vcan_broker.h"

#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "bus/can_frames.h"
#include "bus/can_interface.h"
#include "bus/unix_socket.h"
#include "bus/vcan_protocol.h"
#include "runtime/realtime.h"

namespace rgnav::can {

namespace {

// Whether a broker is already answering on this address.
bool someone_listens(const vcan::UnixAddress& a)
{
  const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  const bool ok = ::connect(fd, reinterpret_cast<const sockaddr*>(&a.addr), a.len) == 0;
  ::close(fd);
  return ok;
}

}  // namespace

VcanBroker::VcanBroker(const std::string& path) : path_(path)
{
  const vcan::UnixAddress a = vcan::make_unix_address(path);
  listen_fd_ = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (listen_fd_ < 0) throw CanError(errno_text("vcan broker " + path + ": socket"));
  if (!a.abstract) {
    if (someone_listens(a)) {
      ::close(listen_fd_);
      throw CanError("vcan broker " + path + ": another broker is already serving this bus");
    }
    ::unlink(path.c_str());  // stale file of a broker that died
  }
  if (::bind(listen_fd_, reinterpret_cast<const sockaddr*>(&a.addr), a.len) < 0 || ::listen(listen_fd_, 64) < 0) {
    const std::string msg = errno_text("vcan broker " + path + ": bind/listen");
    ::close(listen_fd_);
    throw CanError(msg);
  }
  unlink_on_close_ = !a.abstract;
  wake_fd_ = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (wake_fd_ < 0) {
    const std::string msg = errno_text("vcan broker: eventfd");
    ::close(listen_fd_);
    throw CanError(msg);
  }
}

VcanBroker::~VcanBroker()
{
  stop();
  for (auto& c : clients_) ::close(c.fd);
  ::close(listen_fd_);
  ::close(wake_fd_);
  if (unlink_on_close_) ::unlink(path_.c_str());
}

void VcanBroker::start(int realtime_priority)
{
  if (thread_.joinable()) return;
  stop_ = false;
  thread_ = std::thread([this, realtime_priority] {
    if (realtime_priority > 0)
      runtime::request_realtime_logged("virtual CAN bus thread", realtime_priority, false, "frames may stall under load");
    while (!stop_) run_once(std::chrono::milliseconds(100));
  });
}

void VcanBroker::stop()
{
  stop_ = true;
  wake();
  if (thread_.joinable()) thread_.join();
}

void VcanBroker::wake()
{
  const uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_fd_, &one, sizeof one);
}

void VcanBroker::run_once(std::chrono::milliseconds timeout)
{
  std::vector<pollfd> fds;
  {
    std::lock_guard<std::mutex> lock(mu_);
    fds.push_back({listen_fd_, POLLIN, 0});
    fds.push_back({wake_fd_, POLLIN, 0});
    bool timers = false;
    for (const auto& c : clients_) {
      fds.push_back({c.fd, POLLIN, 0});
      timers = timers || c.bus_off_until.has_value();
    }
    // Bus-off periods end on time, not on the next packet.
    if (timers) timeout = std::min(timeout, std::chrono::milliseconds(2));
  }
  const int r = ::poll(fds.data(), fds.size(), static_cast<int>(timeout.count()));
  std::lock_guard<std::mutex> lock(mu_);
  if (r > 0) {
    if (fds[1].revents & POLLIN) {
      uint64_t v;
      [[maybe_unused]] const ssize_t n = ::read(wake_fd_, &v, sizeof v);
    }
    // Clients may have been added or removed by hooks since poll(); match by fd.
    for (size_t k = 2; k < fds.size(); ++k) {
      if (!(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      auto it = std::find_if(clients_.begin(), clients_.end(), [&](const Client& c) { return c.fd == fds[k].fd; });
      if (it == clients_.end()) continue;
      const size_t i = static_cast<size_t>(it - clients_.begin());
      if (!read_client(i)) close_client(i);
    }
    if (fds[0].revents & POLLIN) accept_clients();
  }
  expire_bus_off(Clock::now());
}

void VcanBroker::accept_clients()
{
  for (;;) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0) return;
    // Room for a few hundred frames per client: a busy bus for ~0.5 s without reading.
    const int buf = 256 * 1024;
    ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &buf, sizeof buf);
    clients_.push_back({fd, "client-" + std::to_string(next_client_++), std::nullopt});
  }
}

bool VcanBroker::read_client(size_t i)
{
  for (;;) {
    alignas(8) uint8_t buf[128];
    const ssize_t n = ::recv(clients_[i].fd, buf, sizeof buf, MSG_DONTWAIT);
    if (n == 0) return false;
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    if (n == static_cast<ssize_t>(sizeof(can_frame))) {
      can_frame f;
      std::memcpy(&f, buf, sizeof f);
      if (f.can_dlc > CAN_MAX_DLEN || is_error_frame(f)) {
        ++stats_.rejected;
        continue;
      }
      ++stats_.frames_in;
      forward(i, f);
    } else if (n == static_cast<ssize_t>(sizeof(vcan::VcanControl))) {
      // A control packet may remove clients (and shift indices): finish this client's turn;
      // what it sent after the packet is read on the next poll.
      handle_control(i, buf);
      return true;
    } else {
      ++stats_.rejected;
    }
  }
}

void VcanBroker::forward(size_t from, const can_frame& f)
{
  if (clients_[from].bus_off_until) {
    ++stats_.dropped_by_hook;
    return;
  }
  for (auto& rule : drops_) {
    if (rule.remaining == 0) continue;
    if ((f.can_id & rule.mask) != (rule.id & rule.mask)) continue;
    if (rule.remaining > 0) --rule.remaining;
    ++stats_.dropped_by_hook;
    return;
  }
  for (size_t k = 0; k < clients_.size(); ++k) {
    if (k == from || clients_[k].bus_off_until) continue;
    deliver(clients_[k], f);
  }
}

void VcanBroker::deliver(Client& c, const can_frame& f)
{
  const ssize_t n = ::send(c.fd, &f, sizeof f, MSG_DONTWAIT | MSG_NOSIGNAL);
  if (n == static_cast<ssize_t>(sizeof f))
    ++stats_.deliveries;
  else
    ++stats_.overflow_drops;
}

void VcanBroker::handle_control(size_t from, const void* data)
{
  vcan::VcanControl ctl;
  std::memcpy(&ctl, data, sizeof ctl);
  if (ctl.magic != vcan::kControlMagic) {
    ++stats_.rejected;
    return;
  }
  ctl.name[sizeof ctl.name - 1] = '\0';
  const std::string name = ctl.name;
  switch (static_cast<vcan::ControlOp>(ctl.op)) {
    case vcan::ControlOp::kHello:
      if (!name.empty()) clients_[from].name = name;
      break;
    case vcan::ControlOp::kDropFrames:
      drops_.push_back({ctl.arg0, ctl.arg1, ctl.arg2 == 0xFFFFFFFFu ? -1 : static_cast<int64_t>(ctl.arg2)});
      break;
    case vcan::ControlOp::kClearDrops:
      drops_.clear();
      break;
    case vcan::ControlOp::kInjectError:
      for (auto& c : clients_) deliver(c, make_error_frame(ctl.arg0, static_cast<uint8_t>(ctl.arg1)));
      break;
    case vcan::ControlOp::kBusOff:
      bus_off_locked(name, std::chrono::milliseconds(ctl.arg0));
      break;
    case vcan::ControlOp::kDisconnect:
      disconnect_locked(name);
      break;
    default:
      ++stats_.rejected;
  }
}

void VcanBroker::expire_bus_off(Clock::time_point now)
{
  for (auto& c : clients_) {
    if (c.bus_off_until && now >= *c.bus_off_until) {
      c.bus_off_until.reset();
      deliver(c, make_error_frame(CAN_ERR_RESTARTED));
    }
  }
}

void VcanBroker::close_client(size_t i)
{
  ::close(clients_[i].fd);
  clients_.erase(clients_.begin() + static_cast<std::ptrdiff_t>(i));
}

VcanBroker::Client* VcanBroker::find(const std::string& name)
{
  for (auto& c : clients_)
    if (c.name == name) return &c;
  return nullptr;
}

void VcanBroker::drop_frames(canid_t can_id, canid_t mask, int64_t count)
{
  std::lock_guard<std::mutex> lock(mu_);
  drops_.push_back({can_id, mask, count < 0 ? -1 : count});
}

void VcanBroker::clear_drops()
{
  std::lock_guard<std::mutex> lock(mu_);
  drops_.clear();
}

void VcanBroker::inject_error(can_err_mask_t error_class, uint8_t controller_detail)
{
  std::lock_guard<std::mutex> lock(mu_);
  for (auto& c : clients_) deliver(c, make_error_frame(error_class, controller_detail));
}

bool VcanBroker::bus_off(const std::string& client_name, std::chrono::milliseconds duration)
{
  std::lock_guard<std::mutex> lock(mu_);
  const bool ok = bus_off_locked(client_name, duration);
  wake();
  return ok;
}

bool VcanBroker::bus_off_locked(const std::string& name, std::chrono::milliseconds duration)
{
  Client* c = find(name);
  if (!c) return false;
  deliver(*c, make_error_frame(CAN_ERR_BUSOFF));
  c->bus_off_until = Clock::now() + duration;
  return true;
}

bool VcanBroker::disconnect(const std::string& client_name)
{
  std::lock_guard<std::mutex> lock(mu_);
  return disconnect_locked(client_name);
}

bool VcanBroker::disconnect_locked(const std::string& name)
{
  for (size_t i = 0; i < clients_.size(); ++i) {
    if (clients_[i].name != name) continue;
    close_client(i);
    return true;
  }
  return false;
}

std::vector<std::string> VcanBroker::client_names() const
{
  std::lock_guard<std::mutex> lock(mu_);
  std::vector<std::string> names;
  for (const auto& c : clients_) names.push_back(c.name);
  return names;
}

VcanBrokerStats VcanBroker::stats() const
{
  std::lock_guard<std::mutex> lock(mu_);
  return stats_;
}

}  // namespace rgnav::can
