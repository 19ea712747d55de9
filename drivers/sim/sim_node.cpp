#include "sim/sim_node.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "config/string_fields.h"
#include "msg/conversions.h"
#include "rgnav/heartbeat_t.hpp"
#include "runtime/realtime.h"
#include "sim/sim_conversions.h"
#include "time/message_time.h"

namespace rgnav::sim {

SimChannels load_channels(const config::Config& c)
{
  SimChannels ch;
  config::read_strings(c, {{"laser", &ch.laser}, {"odometry", &ch.odometry}, {"truth", &ch.truth},
                           {"command", &ch.command}});
  return ch;
}

SimNode::SimNode(runtime::Node& node, std::unique_ptr<Simulator> sim, const ProcessOptions& options,
                 const SimChannels& channels, bool manual, const HardwareFactory& make_hardware)
    : node_(node), sim_(std::move(sim)), options_(options), channels_(channels),
      wall_start_(std::chrono::steady_clock::now())
{
  if (make_hardware) {
    hardware_ = make_hardware(*sim_);
    // The real drivers stamp with the wall clock: simulated time 0 is the wall time the
    // simulator was created at (start_utime), so the first tick catches up what loading took.
    const int64_t behind_us = std::max<int64_t>(0, time::wall_utime() - sim_->now_utime());
    wall_start_ = std::chrono::steady_clock::now() - std::chrono::microseconds(behind_us);
  } else {
    sim_->set_command_source(&commands_);
    node_.subscribe<velocity_cmd_t>(channels_.command, [this](const velocity_cmd_t& m) { on_command(m); });
  }
  if (manual) return;
  if (options_.clock == ClockMode::kRealtime && options_.realtime_priority > 0) {
    // Never in fast mode: its loop never sleeps and would starve the machine.
    runtime::request_realtime_logged("rgnav_sim stepping thread", options_.realtime_priority, false);
  }
  if (options_.clock == ClockMode::kRealtime)
    node_.every(std::chrono::duration_cast<std::chrono::microseconds>(options_.tick), [this] { on_tick(); });
  else
    node_.every(std::chrono::microseconds(1), [this] { advance(options_.fast_chunk); });
}

void SimNode::on_command(const velocity_cmd_t& cmd)
{
  commands_.set(cmd.utime, to_drive_command(cmd), cmd.deadline_us);
}

void SimNode::on_tick()
{
  // Simulated time follows wall time (scaled); a late tick catches up in one step, so the
  // simulation never drifts behind the clock.
  const auto wall = std::chrono::steady_clock::now() - wall_start_;
  const auto target = std::chrono::duration_cast<std::chrono::microseconds>(wall * options_.time_scale);
  const auto now = std::chrono::microseconds(static_cast<int64_t>(sim_->time_s() * 1e6 + 0.5));
  if (target > now) advance(target - now);
}

void SimNode::advance(std::chrono::microseconds dt)
{
  const StepOutput out = hardware_ ? hardware_->advance(dt) : sim_->step(dt);
  for (const auto& scan : out.scans) node_.publish(channels_.laser, msg::to_msg(scan));
  for (const auto& s : out.odometry) {
    if (!hardware_) node_.publish(channels_.odometry, to_odometry_msg(s));
    node_.publish(channels_.truth, to_truth_msg(s));
  }
  for (const auto& c : out.collisions) {
    spdlog::warn("collision with {} at ({:.3f}, {:.3f}); the robot stopped", c.with, c.world_from_base.x,
                 c.world_from_base.y);
    node_.set_status(heartbeat_t::STATE_DEGRADED, "collision with " + c.with);
    last_collision_us_ = c.utime;
  }
  // The collision status holds for 2 s of simulated time after the last contact.
  if (last_collision_us_ >= 0 && sim_->now_utime() - last_collision_us_ > 2'000'000) {
    node_.clear_status();
    last_collision_us_ = -1;
  }
}

}  // namespace rgnav::sim
