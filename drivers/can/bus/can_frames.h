// Small helpers on `struct can_frame`: building frames, filter matching with CAN_RAW_FILTER
// semantics (VirtualCan filters in user space exactly as the kernel does), error frame
// classification, and a candump-style text form for logs.
#pragma once

#include <linux/can.h>
#include <linux/can/error.h>

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace rgnav::can {

// A standard (11-bit) data frame.
can_frame make_frame(canid_t id, std::initializer_list<uint8_t> data);
can_frame make_frame(canid_t id, const uint8_t* data, uint8_t dlc);

bool is_error_frame(const can_frame& f);
bool is_extended(const can_frame& f);
// The 11- or 29-bit identifier without flag bits.
canid_t frame_id(const can_frame& f);

// CAN_RAW_FILTER semantics (see CanInterface::set_filters).
bool passes_filters(const can_frame& f, const std::vector<can_filter>& filters);
// Error frames pass if their class bits intersect the mask.
bool passes_error_mask(const can_frame& f, can_err_mask_t mask);

// What an error frame says about the controller.
struct ErrorFrameInfo
{
  bool bus_off = false;     // CAN_ERR_BUSOFF
  bool restarted = false;   // CAN_ERR_RESTARTED: back on the bus after bus-off
  bool error_passive = false;
  bool warning = false;
  std::string text;         // human-readable summary
};
ErrorFrameInfo classify_error(const can_frame& f);
can_frame make_error_frame(can_err_mask_t error_class, uint8_t controller_detail = 0);

// "701#05", "181#2700E8030000" — the candump/cansend notation.
std::string to_string(const can_frame& f);

}  // namespace rgnav::can
