// Fault injection into a running process, for the fault harness only (tests/fault). Off unless
// the process was started with RGNAV_FAULT_INJECTION=1 in its environment, which only the
// harness sets (for the stack it launches); a robot's processes never listen.
//
// When on, the process listens on FAULT_INJECT (fault_inject_t) for faults addressed to it (by
// process name, and pid unless 0) and runs them in the thread that dispatches the bus, which is
// the event loop: FAULT_BUSY_LOOP spins there for duration_ms without returning, so no input is
// handled, no timer runs and the loop's progress counter stands still, while the heartbeat
// beside the loop goes on. That is a hung process that still beats, which the supervisor must
// tell by its progress (work_timeout_ms), and which the drive chain must survive.
#pragma once

#include <string>

#include "bus/bus.h"

namespace rgnav::runtime {

inline constexpr const char* kFaultInjectionEnv = "RGNAV_FAULT_INJECTION";
inline constexpr const char* kFaultInjectChannel = "FAULT_INJECT";

// True when the environment turns fault injection on (RGNAV_FAULT_INJECTION=1).
bool fault_injection_enabled();

// Subscribes `bus` to FAULT_INJECT for the process called `process_name` if `enabled`;
// the subscription lives as long as the bus. Returns whether it subscribed.
bool attach_fault_injection(bus::Bus& bus, const std::string& process_name, bool enabled = fault_injection_enabled());

}  // namespace rgnav::runtime
