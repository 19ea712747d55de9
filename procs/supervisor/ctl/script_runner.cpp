#include "script_runner.h"

#include <stdexcept>

#include "rgnav/supervisor_order_t.hpp"

namespace rgnav::supervisor {

void run_script(const LaunchConfig& config, const std::string& name, const ScriptHooks& hooks, int depth)
{
  if (depth > 16) throw std::runtime_error("script \"" + name + "\": run_script nested too deep (a cycle?)");
  const ScriptSpec* script = nullptr;
  for (const auto& s : config.scripts)
    if (s.name == name) script = &s;
  if (!script) throw std::runtime_error("no script \"" + name + "\" in " + config.file);
  for (const auto& a : script->actions) {
    const std::string target = a.target == ScriptAction::Target::kEverything ? "" : a.ident;
    switch (a.kind) {
      case ScriptAction::Kind::kStart:
      case ScriptAction::Kind::kStop:
      case ScriptAction::Kind::kRestart: {
        const int8_t order = a.kind == ScriptAction::Kind::kStart  ? supervisor_order_t::ORDER_START
                             : a.kind == ScriptAction::Kind::kStop ? supervisor_order_t::ORDER_STOP
                                                                   : supervisor_order_t::ORDER_RESTART;
        hooks.send(order, target);
        if (!a.wait_status.empty() && !hooks.wait_for(target, a.wait_status))
          throw std::runtime_error(a.where.str() + ": timed out waiting for \"" + target + "\" to be " + a.wait_status);
        break;
      }
      case ScriptAction::Kind::kWaitMs:
        hooks.sleep_ms(a.delay_ms);
        break;
      case ScriptAction::Kind::kWaitStatus:
        if (!hooks.wait_for(target, a.wait_status))
          throw std::runtime_error(a.where.str() + ": timed out waiting for \"" + target + "\" to be " + a.wait_status);
        break;
      case ScriptAction::Kind::kRunScript:
        run_script(config, a.ident, hooks, depth + 1);
        break;
    }
  }
}

}  // namespace rgnav::supervisor
