// CanInterface over the kernel's SocketCAN (PF_CAN, SOCK_RAW, CAN_RAW) bound to one network
// interface (can0, vcan0, ...). Receive filters and the error mask are the kernel's own
// (CAN_RAW_FILTER, CAN_RAW_ERR_FILTER); bus-off is tracked from the error frames the driver
// reports, so the error mask always includes CAN_ERR_BUSOFF | CAN_ERR_RESTARTED internally
// (those frames are swallowed unless the caller asked for them).
#pragma once

#include <string>
#include <vector>

#include "bus/can_interface.h"

namespace rgnav::can {

class SocketCan final : public CanInterface
{
 public:
  // Opens and binds; throws CanError naming the interface and errno (no CAN support in the
  // kernel, no such interface, ...).
  explicit SocketCan(const std::string& ifname);
  ~SocketCan() override;
  SocketCan(const SocketCan&) = delete;
  SocketCan& operator=(const SocketCan&) = delete;

  // Whether this kernel can open a CAN_RAW socket at all; `why` says what failed.
  static bool kernel_supports_can(std::string* why);

  bool send(const can_frame& frame, std::chrono::milliseconds timeout) override;
  std::optional<can_frame> receive(std::chrono::milliseconds timeout) override;
  int fd() const override { return fd_; }
  void set_filters(const std::vector<can_filter>& filters) override;
  void set_error_mask(can_err_mask_t mask) override;
  bool bus_off() const override { return bus_off_; }
  std::string name() const override { return "socketcan:" + ifname_; }

 private:
  void apply_error_mask();

  std::string ifname_;
  int fd_ = -1;
  can_err_mask_t user_error_mask_ = 0;
  bool bus_off_ = false;
};

}  // namespace rgnav::can
