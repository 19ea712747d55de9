// The seam between CAN users (CANopen master, drive emulator) and a CAN bus. Two real
// implementations exist: SocketCan (kernel PF_CAN/CAN_RAW on can0, vcan0, ...) and VirtualCan
// (a client of the user-space broker in vcan_broker.h, for machines without kernel CAN).
// Frames are the kernel's `struct can_frame` in both, so code above this line is identical.
#pragma once

#include <linux/can.h>
#include <linux/can/error.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rgnav::can {

class CanError : public std::runtime_error
{
 public:
  using std::runtime_error::runtime_error;
};

// "what: <the text of errno>": the message of a CanError after a failed system call.
inline std::string errno_text(const std::string& what) { return what + ": " + std::strerror(errno); }

class CanInterface
{
 public:
  virtual ~CanInterface() = default;

  // Queues one frame, waiting up to `timeout` for room. False if it could not be sent
  // (timeout, bus-off, connection lost); the frame is then gone, as on a real controller.
  virtual bool send(const can_frame& frame, std::chrono::milliseconds timeout) = 0;
  // The next frame that passes the filters (data or, if enabled, error frames), waiting up to
  // `timeout`; nullopt on timeout.
  virtual std::optional<can_frame> receive(std::chrono::milliseconds timeout) = 0;
  // Readable when receive() has a frame; -1 while there is no connection (poll with a timeout).
  virtual int fd() const = 0;

  // Receive filters with CAN_RAW_FILTER semantics: a frame passes if any filter matches
  // ((id & mask) == (filter.can_id & mask), inverted with CAN_INV_FILTER). Empty: nothing
  // passes; the default is one filter that passes everything.
  virtual void set_filters(const std::vector<can_filter>& filters) = 0;
  // Error classes (CAN_ERR_* bits of can_id) delivered as error frames; 0 = none (default).
  virtual void set_error_mask(can_err_mask_t mask) = 0;
  // True between a bus-off error frame and the controller's restart.
  virtual bool bus_off() const = 0;
  virtual std::string name() const = 0;
};

}  // namespace rgnav::can
