// Runs a procman script (start/stop/restart with optional waits, wait ms, wait status,
// run_script) by sending orders and watching the deputies' status, as the sheriff does.
#pragma once

#include <functional>
#include <string>

#include "launch_config.h"

namespace rgnav::supervisor {

struct ScriptHooks
{
  // Sends an order (ORDER_* of supervisor_order_t) for a command, group or "" (everything).
  std::function<void(int8_t order, const std::string& target)> send;
  // Waits until every command of the target is "running" or "stopped"; false on timeout.
  std::function<bool(const std::string& target, const std::string& status)> wait_for;
  std::function<void(int ms)> sleep_ms;
};

// Throws std::runtime_error if the script is unknown, nests too deep, or a wait times out.
void run_script(const LaunchConfig& config, const std::string& name, const ScriptHooks& hooks, int depth = 0);

}  // namespace rgnav::supervisor
