// ALIGNED_SCAN / GATEWAY_EVENTS messages -> the kernel's plain inputs.
#pragma once

#include "procs/rg_kernel/rg_kernel.h"
#include "rgnav/aligned_scan_t.hpp"
#include "rgnav/gateway_event_t.hpp"

namespace rgnav::rg_kernel {

ScanInput to_input(const aligned_scan_t& m);
GatewayEventInput to_input(const gateway_event_t& m);

}  // namespace rgnav::rg_kernel
