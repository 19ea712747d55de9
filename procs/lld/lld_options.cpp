#include "lld/lld_options.h"

#include "config/string_fields.h"

namespace rgnav::lld {

LldOptions load_lld_options(const config::Config& root, const config::RobotDescription& robot)
{
  LldOptions o;
  auto& ch = o.channels;
  config::read_strings(root.section("channels"), {{"trajectory", &ch.trajectory},
                                                  {"odometry", &ch.odometry},
                                                  {"command", &ch.command},
                                                  {"status", &ch.status}});

  const auto loop = root.section("loop");
  o.loop.rate_hz = loop.number("rate_hz", o.loop.rate_hz, 1.0, 200.0);
  o.loop.realtime_priority = static_cast<int>(loop.integer("realtime_priority", o.loop.realtime_priority, 0, 99));
  o.loop.lock_memory = loop.boolean("lock_memory", o.loop.lock_memory);
  o.loop.command_deadline_ms =
      static_cast<int>(loop.integer("command_deadline_ms", o.loop.command_deadline_ms, 10, 2000));
  o.loop.idle_commands = static_cast<int>(loop.integer("idle_commands", o.loop.idle_commands, 0, 1000));
  if (o.loop.command_deadline_ms < 1000.0 / o.loop.rate_hz)
    loop.fail("command_deadline_ms", "must be at least one control period");

  auto& g = o.follower.gains;
  const auto tr = root.section("tracking");
  // Kanayama's stability conditions: every gain strictly positive.
  g.k_x = tr.number("k_x", g.k_x, 1e-3, 50.0);
  g.k_y = tr.number("k_y", g.k_y, 1e-3, 1000.0);
  g.k_theta = tr.number("k_theta", g.k_theta, 1e-3, 100.0);
  g.k_turn = tr.number("k_turn", g.k_turn, 1e-3, 50.0);
  o.follower.wait_error_start = tr.number("wait_error_start_m", o.follower.wait_error_start, 0.01, 2.0);
  o.follower.wait_error_full = tr.number("wait_error_full_m", o.follower.wait_error_full, 0.02, 5.0);
  if (o.follower.wait_error_full <= o.follower.wait_error_start)
    tr.fail("wait_error_full_m", "must exceed wait_error_start_m");
  o.follower.profile_ds = tr.number("profile_ds_m", o.follower.profile_ds, 0.001, 0.2);
  o.follower.feedforward_lead = tr.number("feedforward_lead_s", o.follower.feedforward_lead, 0.0, 1.0);
  o.follower.end_tolerance = tr.number("end_tolerance_m", o.follower.end_tolerance, 0.001, 0.5);
  o.follower.end_settle_timeout = tr.number("end_settle_timeout_s", o.follower.end_settle_timeout, 0.0, 30.0);

  // The drive's accelerations are the robot's; the speeds the lld drives at are its own, within
  // the robot's.
  auto& l = o.follower.limits;
  const auto lim = root.section("limits");
  const auto& drive = robot.drive;
  l.v_max = lim.number("v_max_mps", l.v_max, 0.01, drive.max_v);
  l.a_max = drive.max_accel;
  l.a_lat_max = lim.number("a_lat_max_mps2", l.a_lat_max, 0.01, 5.0);
  l.omega_max = lim.number("omega_max_radps", l.omega_max, 0.01, drive.max_omega);
  l.alpha_max = drive.max_alpha;
  l.omega_jump_max = lim.number("omega_jump_max_radps", l.omega_jump_max, 0.0, 2.0);
  o.follower.profile_fraction = lim.number("profile_fraction", o.follower.profile_fraction, 0.3, 1.0);
  o.follower.stop_decel = lim.number("stop_decel_mps2", o.follower.stop_decel, 0.01, drive.max_accel);

  const auto to = root.section("timeouts");
  o.follower.odometry_timeout = to.number("odometry_s", o.follower.odometry_timeout, 0.02, 5.0);
  o.follower.trajectory_timeout = to.number("trajectory_s", o.follower.trajectory_timeout, 0.1, 60.0);
  o.stall_excuse_max_s = to.number("stall_excuse_max_s", o.stall_excuse_max_s, 0.0, 5.0);
  return o;
}

}  // namespace rgnav::lld
