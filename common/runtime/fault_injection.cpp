#include "runtime/fault_injection.h"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <spdlog/spdlog.h>

#include "bus/typed.h"
#include "rgnav/fault_inject_t.hpp"

namespace rgnav::runtime {

namespace {

// Spins on the CPU (a runaway computation, not a sleep: it competes for the cores as a real
// busy loop would) until `duration` has passed.
void busy_loop(std::chrono::milliseconds duration)
{
  const auto until = std::chrono::steady_clock::now() + duration;
  volatile uint64_t turns = 0;
  while (std::chrono::steady_clock::now() < until) ++turns;
}

}  // namespace

bool fault_injection_enabled()
{
  const char* v = std::getenv(kFaultInjectionEnv);
  return v != nullptr && std::strcmp(v, "1") == 0;
}

bool attach_fault_injection(bus::Bus& bus, const std::string& process_name, bool enabled)
{
  if (!enabled) return false;
  spdlog::warn("fault injection is on ({}=1): listening on {}", kFaultInjectionEnv, kFaultInjectChannel);
  const int32_t pid = static_cast<int32_t>(getpid());
  bus.subscribe(kFaultInjectChannel, [process_name, pid](const bus::RawMessage& raw) {
    fault_inject_t f;
    std::string why;
    // Not counted as input of the process (its input age and counts stay its own).
    if (!bus::decode(raw.data, raw.size, &f, &why)) {
      spdlog::warn("fault injection: malformed {} dropped: {}", kFaultInjectChannel, why);
      return;
    }
    if (f.target != process_name || (f.pid != 0 && f.pid != pid)) return;
    if (f.fault == fault_inject_t::FAULT_BUSY_LOOP && f.duration_ms > 0) {
      spdlog::warn("fault injection: busy loop for {} ms", f.duration_ms);
      busy_loop(std::chrono::milliseconds(f.duration_ms));
      spdlog::warn("fault injection: busy loop over");
    }
  });
  return true;
}

}  // namespace rgnav::runtime
