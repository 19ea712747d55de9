// The deputy: supervises the commands of one launch config that belong to this host.
//   supervisor --launch deploy/launch/sim.pmd [--host b21r-main] [--record logs/run1]
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <optional>

#include "child_process.h"
#include "launch_parser.h"
#include "launch_plan.h"
#include "order_auth.h"
#include "recording.h"
#include "runtime/process_main.h"
#include "supervisor.h"
#include "supervisor_node.h"

namespace sup = rgnav::supervisor;

int main(int argc, char** argv)
{
  std::string launch_path;
  std::string host;
  std::string state_dir;
  std::string record_dir;
  double record_split_mb = 0;
  bool skip_missing = false;
  const auto flags = [&](CLI::App& app) {
    app.add_option("--launch", launch_path, "procman-style launch config")->required();
    app.add_option("--host", host, "deputy host name (default: this machine's hostname)");
    app.add_option("--state-dir", state_dir, "state and lock files (default: /run/rgnav, $XDG_RUNTIME_DIR/rgnav or /tmp)");
    app.add_option("--record", record_dir, "record the bus with lcm-logger into this folder");
    app.add_option("--record-split-mb", record_split_mb, "start a new log file every N MB (0: one file)");
    app.add_flag("--skip-missing", skip_missing, "leave commands whose executable is missing stopped");
  };
  return rgnav::runtime::process_main(argc, argv, "supervisor", [&](rgnav::runtime::ProcessContext& ctx) -> std::shared_ptr<void> {
    auto options = sup::load_supervisor_options(ctx.config.section("supervisor"));
    const auto channels = sup::load_supervisor_channels(ctx.config.section("channels"));
    // Orders are carried out only when signed with the shared key. Without a key file the
    // watchdog still runs (the safety net must not hang on a credential) and refuses every
    // order; a key file that is there but unsafe or broken is a config error.
    const auto order_options = sup::load_order_auth_options(ctx.config.section("orders"));
    const std::string key_path = sup::order_key_path(order_options.key_file);
    std::optional<sup::OrderKey> order_key;
    std::string no_key;
    try {
      order_key = sup::load_order_key(key_path);
    } catch (const sup::OrderKeyMissing& e) {
      no_key = std::string(e.what()) + ": every order is refused";
    } catch (const sup::OrderKeyError& e) {
      throw rgnav::config::ConfigError(ctx.config_path + ": orders.key_file: " + e.what());
    }
    if (host.empty()) {
      char buf[256] = {0};
      gethostname(buf, sizeof buf - 1);
      host = buf;
    }
    const auto env = sup::launch_environment(argv[0]);
    for (const auto& [k, v] : env) setenv(k.c_str(), v.c_str(), 0);
    // This host's state folder; commands may keep run files there (${RGNAV_RUN_DIR}).
    const std::string dir = (state_dir.empty() ? (options.state_dir.empty() ? sup::default_state_dir() : options.state_dir) : state_dir) + "/" + host;
    setenv("RGNAV_RUN_DIR", dir.c_str(), 1);
    sup::PlanOptions plan_options{std::getenv("RGNAV_ROOT"), std::string(std::getenv("RGNAV_BUILD")) + "/bin", skip_missing};
    sup::LaunchPlan plan;
    try {
      auto config = sup::parse_launch_file(launch_path);
      if (!record_dir.empty()) sup::add_recorder(config, host, record_dir, record_split_mb, ctx.node.bus().url());
      plan = sup::make_plan(config, plan_options);
    } catch (const sup::LaunchError& e) {
      throw rgnav::config::ConfigError(e.what());
    }
    // --check-config builds everything on a fake bus and must not touch processes.
    if (ctx.node.bus().url() == "fake://") return std::make_shared<sup::LaunchPlan>(std::move(plan));

    sup::make_dirs(dir);
    auto self_lock = std::make_shared<sup::SelfLock>(dir + "/supervisor.lock");
    auto supervisor = std::make_unique<sup::Supervisor>(std::move(plan), host, options, dir);
    if (!no_key.empty()) supervisor->note_alert(no_key);
    const auto now = std::chrono::steady_clock::now();
    supervisor->recover(now);
    supervisor->start_all(now);
    sup::OrderGate orders(sup::OrderVerifier(order_key, key_path, order_options.max_age));
    auto node = std::make_shared<sup::SupervisorNode>(ctx.node, std::move(supervisor), options, channels, std::move(orders));
    // The node (which stops the children) goes before the lock is released.
    return std::make_shared<std::pair<std::shared_ptr<sup::SupervisorNode>, std::shared_ptr<sup::SelfLock>>>(node, self_lock);
  }, flags);
}
