// rgnav_goto: the operator sends the robot somewhere (./rgnav goto). Publishes a nav_goal_t on
// NAV_GOAL (again every second until the planner answers on GLOBAL_PATH, --answer-timeout), then
// prints the goal's progress from GLOBAL_PATH until it is reached, cancelled or has no path
// (--no-wait: returns once the planner has it). Ctrl-C (and --timeout) cancel the goal. A goal
// with no path is cancelled too (the planner would plan it again when the map changes, and the
// robot should not set off later with nobody watching), unless --keep-trying, or only gateways
// taken for closed or places collision avoidance could not pass are in the way: the planner tries
// those again after their hold (a door is tried again later), and the tool waits for it.
//   rgnav_goto NAME|ID [X Y THETA_DEG] [--tolerance M] [--heading-tolerance DEG] [--timeout S]
// Exit codes: 0 reached, 3 cancelled (Ctrl-C, --timeout, or by someone else), 4 no path,
// 2 bad arguments or a goal the bus checks refuse, 1 no planner answered or a bus failure.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "planner/no_path_reason.h"
#include "rgnav/global_path_t.hpp"
#include "rgnav/nav_goal_t.hpp"
#include "runtime/signal_watcher.h"
#include "time/message_time.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kReached = 0, kFailure = 1, kBadArguments = 2, kCancelled = 3, kNoPath = 4;

const char* status_name(int8_t s)
{
  switch (s) {
    case rgnav::global_path_t::STATUS_OK: return "on the way";
    case rgnav::global_path_t::STATUS_NO_PATH: return "no path";
    case rgnav::global_path_t::STATUS_GOAL_REACHED: return "reached";
    case rgnav::global_path_t::STATUS_CANCELLED: return "cancelled";
  }
  return "?";
}

// "regions 1 > 2 > 5 through gateways 3, 4" from the waypoints.
std::string route_summary(const rgnav::global_path_t& p)
{
  std::vector<int64_t> regions, gateways;
  for (const auto& w : p.waypoints) {
    if (regions.empty() || regions.back() != w.region_id) regions.push_back(w.region_id);
    if (w.gateway_id != 0 && (gateways.empty() || gateways.back() != w.gateway_id)) gateways.push_back(w.gateway_id);
  }
  std::ostringstream s;
  if (regions.empty()) return "no route yet";
  s << "region" << (regions.size() > 1 ? "s " : " ");
  for (size_t i = 0; i < regions.size(); ++i) s << (i ? " > " : "") << regions[i];
  if (!gateways.empty()) {
    s << " through gateway" << (gateways.size() > 1 ? "s " : " ");
    for (size_t i = 0; i < gateways.size(); ++i) s << (i ? ", " : "") << gateways[i];
  }
  return s.str();
}

// A no-path that holds for a while only: a gateway taken for closed, a place collision avoidance
// could not pass (the planner plans the goal again once it is let go).
bool held_for_a_while(rgnav::planner::NoPathCause cause)
{
  return cause == rgnav::planner::NoPathCause::kClosedGateway || cause == rgnav::planner::NoPathCause::kBlockedPlace;
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Send the robot to a region (NAME or ID), optionally to a pose in it, and follow its progress.\n"
               "Exit codes: 0 reached, 3 cancelled (Ctrl-C, --timeout, or by someone else), 4 no path,\n"
               "2 bad arguments, 1 no planner answered or a bus failure."};
  std::string region;
  std::vector<double> pose;
  double tolerance = 0.3, heading_tolerance_deg = 0, timeout_s = 0, answer_timeout_s = 5.0;
  int64_t goal_id = 0;
  bool no_wait = false, keep_trying = false;
  std::string url, goal_channel = "NAV_GOAL", path_channel = "GLOBAL_PATH";
  app.add_option("region", region, "goal region: its name, or its id (a number)")->required();
  app.add_option("pose", pose, "X Y THETA: [m] [m] [deg] in the region's frame (default: anywhere suitable in it)")
      ->expected(0, 3)
      ->type_name("X Y THETA");
  app.add_option("--tolerance", tolerance, "[m] how near the goal counts as reached")->check(CLI::Range(0.01, 100.0));
  app.add_option("--heading-tolerance", heading_tolerance_deg, "[deg] how near the heading must be (default: any heading)")
      ->check(CLI::Range(0.1, 180.0));
  app.add_option("--timeout", timeout_s, "[s] cancel the goal if not reached by then (default: wait)")->check(CLI::Range(0.0, 1e6));
  app.add_option("--goal-id", goal_id, "goal id (default: from the clock, unique per send)")->check(CLI::Range(int64_t{1}, INT64_MAX));
  app.add_flag("--no-wait", no_wait, "exit 0 as soon as the planner has the goal (its first GLOBAL_PATH for it); the rest is the planner's");
  app.add_option("--answer-timeout", answer_timeout_s, "[s] the goal is re-sent every second until the planner answers, this long")
      ->check(CLI::Range(0.5, 600.0));
  app.add_flag("--keep-trying", keep_trying, "on any no path, keep the goal and wait (until reached, cancelled or --timeout); behind a closed gateway or a blocked place it waits anyway");
  app.add_option("--lcm-url", url, "LCM URL (default: LCM_DEFAULT_URL or LCM's default)");
  app.add_option("--goal-channel", goal_channel, "the planner's channels.nav_goal");
  app.add_option("--path-channel", path_channel, "the planner's channels.global_path");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;   // --help is 0; anything CLI11 refuses is a bad argument
  }
  if (!pose.empty() && pose.size() != 3) {
    std::cerr << "rgnav goto: a pose is X Y THETA (three numbers)\n";
    return kBadArguments;
  }

  rgnav::nav_goal_t goal{};
  goal.utime = rgnav::time::wall_utime();
  goal.goal_id = goal_id > 0 ? goal_id : goal.utime / 1000;   // [ms]: unique per send from one machine
  const bool numeric = region.find_first_not_of("0123456789") == std::string::npos;
  if (numeric) {
    try {
      goal.region_id = std::stoll(region);
    } catch (const std::exception&) {
      std::cerr << "rgnav goto: region id " << region << " out of range\n";
      return kBadArguments;
    }
  } else {
    goal.region_name = region;
  }
  goal.has_pose = !pose.empty();
  goal.region_from_goal = {};
  if (goal.has_pose) {
    goal.region_from_goal.x = pose[0];
    goal.region_from_goal.y = pose[1];
    goal.region_from_goal.theta = std::remainder(pose[2] * M_PI / 180.0, 2.0 * M_PI);
  }
  goal.position_tolerance = tolerance;
  goal.heading_tolerance = heading_tolerance_deg > 0 ? heading_tolerance_deg * M_PI / 180.0 : M_PI;
  goal.cancel = false;
  rgnav::nav_goal_t cancel = goal;
  cancel.cancel = true;

  try {
    // Before the bus: LCM's threads inherit the blocked SIGINT, which then arrives here.
    rgnav::runtime::SignalWatcher signals;
    rgnav::bus::LcmBus bus(url);
    rgnav::bus::DropCounter drops;
    std::optional<rgnav::global_path_t> latest;
    rgnav::bus::subscribe<rgnav::global_path_t>(
        bus, path_channel,
        [&](const rgnav::global_path_t& p, const rgnav::bus::RawMessage&) {
          if (p.goal_id == goal.goal_id) latest = p;
        },
        &drops);
    // bus::publish checks what it sends as the planner will: a NaN or an oversized name is refused here.
    if (!rgnav::bus::publish(bus, goal_channel, goal)) {
      std::cerr << "rgnav goto: goal refused (see the message above)\n";
      return kBadArguments;
    }
    std::cout << "goal " << goal.goal_id << " sent on " << goal_channel << ": "
              << (numeric ? "region " + region : "'" + region + "'");
    if (goal.has_pose) std::cout << " at (" << pose[0] << ", " << pose[1] << ", " << pose[2] << " deg)";
    std::cout << std::endl;

    const auto start = Clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    auto send_cancel = [&](const std::string& why, int code) {
      cancel.utime = rgnav::time::wall_utime();
      rgnav::bus::publish(bus, goal_channel, cancel);
      std::cout << why << ": goal " << goal.goal_id << " cancelled" << std::endl;
      // The planner's CANCELLED confirms it; a second cancel covers a lost datagram.
      const auto until = Clock::now() + std::chrono::seconds(2);
      while (Clock::now() < until && !(latest && latest->status == rgnav::global_path_t::STATUS_CANCELLED)) {
        bus.handle(std::chrono::milliseconds(100));
        if (Clock::now() > until - std::chrono::seconds(1)) rgnav::bus::publish(bus, goal_channel, cancel);
      }
      return code;
    };
    auto last_send = Clock::now();
    int8_t last_status = -1;
    std::string last_line;
    auto last_print = Clock::now() - std::chrono::seconds(10);
    while (true) {
      if (bus.handle(std::chrono::milliseconds(100)) < 0) {
        std::cerr << "rgnav goto: bus error\n";
        return kFailure;
      }
      if (signals.take() != 0) return send_cancel("interrupted", kCancelled);
      if (timeout_s > 0 && seconds() > timeout_s) return send_cancel("timed out after " + std::to_string(static_cast<int>(timeout_s)) + " s", kCancelled);
      if (!latest) {
        if (seconds() >= answer_timeout_s) {
          std::cerr << "rgnav goto: no planner answered on " << path_channel << " within " << answer_timeout_s << " s\n";
          return kFailure;
        }
        if (Clock::now() - last_send >= std::chrono::seconds(1)) {
          goal.utime = rgnav::time::wall_utime();
          rgnav::bus::publish(bus, goal_channel, goal);
          last_send = Clock::now();
        }
        continue;
      }
      if (no_wait) {
        std::cout << "the planner has goal " << goal.goal_id << ": " << status_name(latest->status) << std::endl;
        return kReached;
      }
      const auto& p = *latest;
      std::ostringstream line;
      line << status_name(p.status);
      if (p.status == rgnav::global_path_t::STATUS_OK) line << ": " << route_summary(p) << ", about " << std::lround(p.cost) << " s left";
      if (!p.reason.empty()) line << " (" << p.reason << ")";
      // A line per change of status or route, else one every 5 s.
      if (p.status != last_status || (line.str() != last_line && Clock::now() - last_print >= std::chrono::seconds(5))) {
        std::cout << "[" << std::lround(seconds()) << " s] " << line.str() << std::endl;
        last_line = line.str();
        last_print = Clock::now();
      }
      last_status = p.status;
      switch (p.status) {
        case rgnav::global_path_t::STATUS_GOAL_REACHED: return kReached;
        case rgnav::global_path_t::STATUS_CANCELLED: return kCancelled;
        case rgnav::global_path_t::STATUS_NO_PATH:
          // Behind a gateway held closed or a place blocked a moment ago, the goal is waited for
          // (until --timeout): the planner plans it again once the hold is over.
          if (!keep_trying && !held_for_a_while(rgnav::planner::no_path_cause(p.reason)))
            return send_cancel("no path", kNoPath);
          break;
        default: break;
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "rgnav goto: " << e.what() << "\n";
    return kFailure;
  }
}
