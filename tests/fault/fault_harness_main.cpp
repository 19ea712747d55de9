// Fault-injection harness: ./rgnav bench faults runs it over the launch configs; ctest runs a
// short form over the test stack. Writes one JSON row per (process, fault).
//   fault_harness --launch tests/fault/fault_stack.pmd --out logs/bench/faults.json
#include <CLI/CLI.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "fault_harness.h"
#include "log/log.h"
#include "order_key.h"

int main(int argc, char** argv)
{
  rgnav::fault::HarnessOptions o;
  std::string out;
  bool append = false;
  bool no_supervisor_fault = false;
  int timeout_ms = 500, period_ms = 200, restart_bound_ms = 3000, stop_bound_ms = 200;
  CLI::App app{"rgnav fault-injection harness"};
  app.add_option("--launch", o.launch, "launch config")->required();
  app.add_option("--host", o.host, "deputy host name to launch as");
  app.add_option("--supervisor", o.supervisor_bin, "supervisor executable")->required();
  app.add_option("--supervisor-config", o.supervisor_config, "supervisor YAML config");
  app.add_option("--state-dir", o.state_dir, "state folder")->required();
  app.add_option("--log", o.log_file, "supervisor output file")->required();
  app.add_option("--lcm-url", o.lcm_url, "LCM URL");
  app.add_option("--process", o.processes, "only these processes (repeatable)");
  app.add_option("--fault", o.faults, "only these faults (repeatable): sigkill sigstop busy_loop crash_loop flood malformed loss_dup_delay");
  app.add_flag("--no-supervisor-fault", no_supervisor_fault, "skip killing the supervisor itself");
  app.add_flag("--busy-loop-mid-work", o.busy_loop_mid_work, "send busy loops while the process's loop is in a step of work");
  app.add_option("--host-stall-ms", o.host_stall_ms, "before the process faults, stop the whole stack this long while driving (repeatable)");
  app.add_option("--heartbeat-timeout-ms", timeout_ms, "the supervisor's heartbeat timeout");
  app.add_option("--heartbeat-period-ms", period_ms, "the processes' heartbeat period");
  app.add_option("--restart-bound-ms", restart_bound_ms, "fault to heartbeating again");
  app.add_option("--stop-bound-ms", stop_bound_ms, "fault of a drive-chain process to commanded velocity zero");
  app.add_option("--flood", o.flood_messages, "messages per input in a flood");
  app.add_option("--flood-rate", o.flood_rate_hz, "flood rate per input [Hz]");
  app.add_option("--out", out, "JSON rows (written, or appended with --append)");
  app.add_flag("--append", append, "add rows to an existing --out file");
  CLI11_PARSE(app, argc, argv);
  rgnav::log::init("fault_harness", "info");
  o.supervisor_fault = !no_supervisor_fault;
  o.heartbeat_timeout = std::chrono::milliseconds(timeout_ms);
  o.heartbeat_period = std::chrono::milliseconds(period_ms);
  o.restart_bound = std::chrono::milliseconds(restart_bound_ms);
  o.stop_bound = std::chrono::milliseconds(stop_bound_ms);
  // The supervisor's own bounds on a busy loop, from its config (defaults otherwise).
  if (!o.supervisor_config.empty()) {
    try {
      const YAML::Node s = YAML::LoadFile(o.supervisor_config)["supervisor"];
      if (s && s["work_timeout_ms"]) o.work_timeout = std::chrono::milliseconds(s["work_timeout_ms"].as<int>());
      if (s && s["hung_grace_ms"]) o.hung_grace = std::chrono::milliseconds(s["hung_grace_ms"].as<int>());
    } catch (const std::exception& e) {
      std::cerr << "fault_harness: " << o.supervisor_config << ": " << e.what() << "\n";
      return 2;
    }
  }

  // Orders to the supervisor are signed (procs/supervisor/order_auth.h): with the key its config
  // names, or, where it names none, with a key of this run's own, made in the state folder and
  // handed to the supervisor through $RGNAV_ORDERS_KEY (the operator's own key is not needed).
  try {
    std::string configured;
    if (!o.supervisor_config.empty()) {
      const YAML::Node orders = YAML::LoadFile(o.supervisor_config)["orders"];
      if (orders && orders["key_file"]) configured = orders["key_file"].as<std::string>();
    }
    if (configured.empty()) {
      o.order_key_file = o.state_dir + "/orders.key";
      if (!std::filesystem::exists(o.order_key_file)) rgnav::supervisor::create_order_key(o.order_key_file, false);
      setenv("RGNAV_ORDERS_KEY", o.order_key_file.c_str(), 1);
    } else {
      o.order_key_file = rgnav::supervisor::order_key_path(configured);
    }
    rgnav::supervisor::load_order_key(o.order_key_file);  // refused now, not at the first order
  } catch (const std::exception& e) {
    std::cerr << "fault_harness: order key: " << e.what() << "\n";
    return 2;
  }

  std::vector<rgnav::fault::FaultRow> rows;
  try {
    rows = rgnav::fault::run_harness(o);
  } catch (const std::exception& e) {
    std::cerr << "fault_harness: " << e.what() << "\n";
    return 2;
  }

  nlohmann::json doc = nlohmann::json::object();
  if (append && !out.empty()) {
    std::ifstream in(out);
    if (in) doc = nlohmann::json::parse(in, nullptr, false);
    if (!doc.is_object()) doc = nlohmann::json::object();
  }
  if (!doc.contains("rows")) doc["rows"] = nlohmann::json::array();
  doc["heartbeat_timeout_ms"] = timeout_ms;
  doc["restart_bound_ms"] = restart_bound_ms;
  int failed = 0, passed = 0, pending = 0;
  for (const auto& r : rows) {
    nlohmann::json j = {{"launch", o.launch}, {"process", r.process}, {"fault", r.fault}, {"others_restarted", r.others_restarted},
                        {"status", r.status}, {"note", r.note}};
    j["detect_ms"] = r.detect_ms ? nlohmann::json(*r.detect_ms) : nlohmann::json();
    j["hang_start_ms"] = r.hang_start_ms ? nlohmann::json(*r.hang_start_ms) : nlohmann::json();
    j["restart_ms"] = r.restart_ms ? nlohmann::json(*r.restart_ms) : nlohmann::json();
    j["state_lost"] = r.state_lost ? nlohmann::json(*r.state_lost) : nlohmann::json();
    j["robot_stopped_ms"] = r.robot_stopped_ms ? nlohmann::json(*r.robot_stopped_ms) : nlohmann::json();
    j["max_other_gap_ms"] = r.max_other_gap_ms ? nlohmann::json(*r.max_other_gap_ms) : nlohmann::json();
    j["cmd_zero_ms"] = r.cmd_zero_ms ? nlohmann::json(*r.cmd_zero_ms) : nlohmann::json();
    j["drive_zero_ms"] = r.drive_zero_ms ? nlohmann::json(*r.drive_zero_ms) : nlohmann::json();
    j["drive_bound_ms"] = r.drive_bound_ms ? nlohmann::json(*r.drive_bound_ms) : nlohmann::json();
    j["brake_start_ms"] = r.brake_start_ms ? nlohmann::json(*r.brake_start_ms) : nlohmann::json();
    j["v_at_fault"] = r.v_at_fault ? nlohmann::json(*r.v_at_fault) : nlohmann::json();
    j["omega_at_fault"] = r.omega_at_fault ? nlohmann::json(*r.omega_at_fault) : nlohmann::json();
    if (r.stall_stop) j["stall_stop"] = *r.stall_stop;
    if (r.v_min_after) j["v_min_after"] = *r.v_min_after;
    doc["rows"].push_back(j);
    failed += r.status == "fail";
    passed += r.status == "pass";
    pending += r.status == "pending";
  }
  if (!out.empty()) std::ofstream(out) << doc.dump(2) << "\n";
  std::cout << passed << " passed, " << failed << " failed, " << pending << " pending, "
            << rows.size() - passed - failed - pending << " not applicable\n";
  return failed == 0 ? 0 : 1;
}
