// CanInterface as a client of the user-space virtual CAN bus (vcan_broker.h). Filters and the
// error mask are applied here, with the kernel's semantics. Losing the broker looks like what
// it is to a CAN user, a bus-off: the interface reports bus_off() and delivers a CAN_ERR_BUSOFF
// error frame; if reconnect_interval > 0 it keeps trying and, once back, delivers
// CAN_ERR_RESTARTED, as a controller does after its bus-off recovery.
#pragma once

#include <chrono>
#include <deque>
#include <string>
#include <vector>

#include "bus/can_interface.h"

namespace rgnav::can {

struct VirtualCanOptions
{
  std::string path;         // broker socket; '@name' = abstract namespace
  std::string client_name;  // how the broker's test hooks address this client ("" = assigned)
  // How long the constructor waits for a broker that is still starting.
  std::chrono::milliseconds connect_timeout{2000};
  // 0: stay disconnected once the broker is lost; else retry this often.
  std::chrono::milliseconds reconnect_interval{0};
};

class VirtualCan final : public CanInterface
{
 public:
  // Throws CanError if no broker answers within connect_timeout.
  explicit VirtualCan(VirtualCanOptions options);
  ~VirtualCan() override;
  VirtualCan(const VirtualCan&) = delete;
  VirtualCan& operator=(const VirtualCan&) = delete;

  bool send(const can_frame& frame, std::chrono::milliseconds timeout) override;
  std::optional<can_frame> receive(std::chrono::milliseconds timeout) override;
  int fd() const override { return fd_; }
  void set_filters(const std::vector<can_filter>& filters) override { filters_ = filters; }
  void set_error_mask(can_err_mask_t mask) override { error_mask_ = mask & CAN_ERR_MASK; }
  bool bus_off() const override { return bus_off_; }
  std::string name() const override { return "vcan:" + options_.path; }

  bool connected() const { return fd_ >= 0; }

  // Test hooks, executed by the broker (see VcanBroker for their meaning).
  bool request_drop_frames(canid_t can_id, canid_t mask, int64_t count);
  bool request_clear_drops();
  bool request_inject_error(can_err_mask_t error_class, uint8_t controller_detail = 0);
  bool request_bus_off(const std::string& client_name, std::chrono::milliseconds duration);
  bool request_disconnect(const std::string& client_name);

 private:
  bool try_connect();
  void lost_connection();
  bool send_control(uint32_t op, uint32_t a0, uint32_t a1, uint32_t a2, const std::string& name);
  // Routes a received frame: updates bus-off state, applies filters. True if it is for the user.
  bool accept(const can_frame& f);

  VirtualCanOptions options_;
  int fd_ = -1;
  std::vector<can_filter> filters_;
  can_err_mask_t error_mask_ = 0;
  bool bus_off_ = false;
  std::deque<can_frame> synthetic_;  // error frames this side generates (connection lost/back)
  std::chrono::steady_clock::time_point next_reconnect_{};
};

}  // namespace rgnav::can
