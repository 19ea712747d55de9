// The controller (procman's sheriff, headless): sends orders to the deputies and shows their
// status. Orders are signed with the shared key (order_auth.h; the key file named by
// orders.key_file of the supervisor config, or --key); `keygen` makes one.
//   rgnav_ctl status [--once]          rgnav_ctl start|stop|restart <process|group> [--wait]
//   rgnav_ctl shutdown [--host H]      rgnav_ctl script <name> --launch FILE
//   rgnav_ctl keygen [--force|--if-missing]
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>
#include <map>
#include <random>
#include <sstream>
#include <thread>

#include "bus/drop_counter.h"
#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "launch_parser.h"
#include "config/config.h"
#include "log/log.h"
#include "order_auth.h"
#include "order_conversions.h"
#include "rgnav/supervisor_order_t.hpp"
#include "runtime/process_main.h"
#include "rgnav/supervisor_status_t.hpp"
#include "script_runner.h"
#include "status_table.h"
#include "time/message_time.h"

namespace sup = rgnav::supervisor;
using Clock = std::chrono::steady_clock;

namespace {

class Controller
{
 public:
  Controller(const std::string& url, std::string status_channel, std::string orders_channel)
      : bus_(url), orders_channel_(std::move(orders_channel))
  {
    std::random_device rd;
    next_id_ = (static_cast<int64_t>(rd()) << 20) ^ getpid();
    rgnav::bus::subscribe<rgnav::supervisor_status_t>(
        bus_, status_channel,
        [this](const rgnav::supervisor_status_t& s, const rgnav::bus::RawMessage&) { status_[s.host] = s; }, &drops_);
  }

  // UDP multicast may lose a datagram: the order goes out three times, each copy signed with
  // a nonce of its own (a deputy takes an exact copy for a replay); deputies act once.
  void send(int8_t order, const std::string& target, const std::string& host)
  {
    if (!key_) throw std::runtime_error("no order key: orders cannot be signed");
    sup::OrderFields o;
    o.utime = rgnav::time::wall_utime();
    last_order_utime_ = o.utime;
    o.order_id = ++next_id_;
    o.host = host;
    o.order = order;
    o.target = target;
    o.source = source_;
    for (int i = 0; i < 3; ++i) {
      sup::sign_order(o, *key_);
      rgnav::bus::publish(bus_, orders_channel_, sup::to_order_msg(o));
      spin(std::chrono::milliseconds(30));
    }
  }
  void set_key(sup::OrderKey key) { key_ = std::move(key); }

  void spin(std::chrono::milliseconds d)
  {
    const auto until = Clock::now() + d;
    while (Clock::now() < until) bus_.handle(std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now()));
  }

  // Statuses newer than `since` (wall us).
  std::map<std::string, rgnav::supervisor_status_t> fresh(int64_t since) const
  {
    std::map<std::string, rgnav::supervisor_status_t> out;
    for (const auto& [h, s] : status_)
      if (s.utime >= since) out[h] = s;
    return out;
  }
  const std::map<std::string, rgnav::supervisor_status_t>& all() const { return status_; }

  static bool matches(const rgnav::process_status_t& p, const std::string& target)
  {
    if (target.empty() || target == "everything" || p.name == target) return true;
    std::stringstream parts(p.group);
    std::string part;
    if (p.group == target || p.group.rfind(target + "/", 0) == 0) return true;
    while (std::getline(parts, part, '/'))
      if (part == target) return true;
    return false;
  }

  // Statuses sent at or after `since` (wall us; take it before sending the order: a deputy may
  // act and report, even exit, while the order is still being repeated).
  bool wait_for(const std::string& target, const std::string& want, std::chrono::milliseconds timeout, int64_t since = -1)
  {
    if (since < 0) since = last_order_utime_ > 0 ? last_order_utime_ : rgnav::time::wall_utime();
    const auto until = Clock::now() + timeout;
    while (Clock::now() < until) {
      spin(std::chrono::milliseconds(50));
      int matched = 0, ok = 0;
      for (const auto& [h, s] : fresh(since)) {
        if (!host_filter_.empty() && h != host_filter_) continue;  // orders went to that deputy only
        for (const auto& p : s.processes) {
          if (!matches(p, target)) continue;
          // A process not built (launched with --skip-missing) cannot run: not waited for.
          if (p.state == rgnav::process_status_t::STATE_STOPPED && p.last_exit == "missing executable") continue;
          ++matched;
          // A oneshot job that finished has done what running means for it.
          const bool done = p.state == rgnav::process_status_t::STATE_STOPPED && p.last_exit.rfind("done", 0) == 0;
          const bool running = p.state == rgnav::process_status_t::STATE_RUNNING || (done && want == "running");
          const bool stopped = p.state == rgnav::process_status_t::STATE_STOPPED || p.state == rgnav::process_status_t::STATE_FAILED;
          if ((want == "running" && running) || (want == "stopped" && stopped)) ++ok;
        }
      }
      if (matched > 0 && ok == matched) return true;
    }
    return false;
  }

 private:
  rgnav::bus::LcmBus bus_;
  rgnav::bus::DropCounter drops_;
  std::string orders_channel_;
  std::optional<sup::OrderKey> key_;
  std::string source_ = sup::order_source("rgnav_ctl");
  int64_t next_id_ = 0;
  int64_t last_order_utime_ = 0;

 public:
  std::string host_filter_;
  std::map<std::string, rgnav::supervisor_status_t> status_;
};

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"rgnav controller: orders to the supervisors and their status"};
  std::string url;
  std::string host;
  std::string status_channel = "SUPERVISOR_STATUS";
  std::string orders_channel = "SUPERVISOR_ORDERS";
  bool wait = false;
  int timeout_ms = 30000;
  app.add_option("--lcm-url", url, "LCM URL");
  app.add_option("--host", host, "only this deputy (default: all)");
  app.add_option("--status-channel", status_channel);
  app.add_option("--orders-channel", orders_channel);
  std::string config_path = rgnav::runtime::default_config_dir() + "/supervisor.yaml";
  std::string key_path;
  app.add_option("--config", config_path, "supervisor config (its orders.key_file names the key)");
  app.add_option("--key", key_path, "order key file (default: the config's orders.key_file)");
  app.require_subcommand(1);
  app.fallthrough();  // --host and --lcm-url also after the sub-command

  auto* status = app.add_subcommand("status", "show the deputies' status (refreshed each second)");
  bool once = false;
  double listen_s = 1.5;
  status->add_flag("--once", once, "print once and exit (1 if no deputy answered)");
  status->add_option("--listen", listen_s, "seconds to collect statuses for --once");

  std::string target;
  std::map<std::string, int8_t> order_cmds = {{"start", rgnav::supervisor_order_t::ORDER_START},
                                              {"stop", rgnav::supervisor_order_t::ORDER_STOP},
                                              {"restart", rgnav::supervisor_order_t::ORDER_RESTART}};
  std::map<std::string, CLI::App*> order_apps;
  for (const auto& [name, code] : order_cmds) {
    auto* sub = app.add_subcommand(name, name + " a process or group (\"everything\" for all)");
    sub->add_option("target", target, "process or group name")->required();
    sub->add_flag("--wait", wait, "wait until the target is running (stopped for stop)");
    sub->add_option("--timeout-ms", timeout_ms, "for --wait");
    order_apps[name] = sub;
  }
  auto* shutdown = app.add_subcommand("shutdown", "stop every process and the deputies");
  shutdown->add_flag("--wait", wait, "wait until the deputies report everything stopped");
  shutdown->add_option("--timeout-ms", timeout_ms, "for --wait");
  auto* script = app.add_subcommand("script", "run a script of a launch config");
  std::string script_name, launch_path;
  script->add_option("name", script_name)->required();
  script->add_option("--launch", launch_path, "launch config holding the script")->required();
  script->add_option("--timeout-ms", timeout_ms, "for each wait");

  auto* keygen = app.add_subcommand("keygen", "make the shared order key (copy the file to every deputy and controller host)");
  bool force = false, if_missing = false;
  keygen->add_flag("--force", force, "replace an existing key (orders signed with the old one are refused from then on)");
  keygen->add_flag("--if-missing", if_missing, "do nothing if there is a key already");

  CLI11_PARSE(app, argc, argv);
  rgnav::log::init("rgnav_ctl", "warn");

  try {
    if (key_path.empty() && !status->parsed()) {
      // The same file the deputies read; a missing config leaves the default places.
      std::string configured;
      try {
        configured = sup::load_order_auth_options(rgnav::config::Config::load(config_path).section("orders")).key_file;
      } catch (const rgnav::config::ConfigError&) {
        if (std::filesystem::exists(config_path)) throw;
      }
      key_path = sup::order_key_path(configured);
    }
    if (keygen->parsed()) {
      if (!force && std::filesystem::exists(key_path)) {
        if (if_missing) return 0;
        std::cout << "order key " << sup::load_order_key(key_path).id << " is at " << key_path
                  << " (kept; --force makes a new one)\n";
        return 0;
      }
      const auto key = sup::create_order_key(key_path, force);
      std::cout << "order key " << key.id << " written to " << key_path
                << " (mode 600); every deputy and controller host needs this same file\n";
      return 0;
    }
    Controller ctl(url, status_channel, orders_channel);
    if (!status->parsed()) ctl.set_key(sup::load_order_key(key_path));
    ctl.host_filter_ = host;
    if (status->parsed()) {
      if (once) {
        ctl.spin(std::chrono::milliseconds(static_cast<int64_t>(listen_s * 1000)));
        std::cout << sup::format_status(ctl.all(), rgnav::time::wall_utime());
        return ctl.all().empty() ? 1 : 0;
      }
      while (true) {
        ctl.spin(std::chrono::milliseconds(1000));
        std::cout << "\033[H\033[2J" << sup::format_status(ctl.all(), rgnav::time::wall_utime()) << std::flush;
      }
    }
    for (const auto& [name, sub] : order_apps) {
      if (!sub->parsed()) continue;
      const int64_t since = rgnav::time::wall_utime();
      ctl.send(order_cmds[name], target == "everything" ? "" : target, host);
      if (!wait) return 0;
      const bool ok = ctl.wait_for(target, name == "stop" ? "stopped" : "running", std::chrono::milliseconds(timeout_ms), since);
      if (!ok) std::cerr << "timed out waiting for " << target << "\n";
      return ok ? 0 : 1;
    }
    if (shutdown->parsed()) {
      const int64_t since = rgnav::time::wall_utime();
      ctl.send(rgnav::supervisor_order_t::ORDER_SHUTDOWN, "", host);
      if (!wait) return 0;
      return ctl.wait_for("", "stopped", std::chrono::milliseconds(timeout_ms), since) ? 0 : 1;
    }
    if (script->parsed()) {
      const auto config = sup::parse_launch_file(launch_path);
      sup::ScriptHooks hooks;
      hooks.send = [&](int8_t order, const std::string& t) { ctl.send(order, t, host); };
      hooks.wait_for = [&](const std::string& t, const std::string& s) {
        return ctl.wait_for(t, s, std::chrono::milliseconds(timeout_ms));
      };
      hooks.sleep_ms = [&](int ms) { ctl.spin(std::chrono::milliseconds(ms)); };
      sup::run_script(config, script_name, hooks);
      return 0;
    }
  } catch (const std::exception& e) {
    std::cerr << "rgnav_ctl: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
