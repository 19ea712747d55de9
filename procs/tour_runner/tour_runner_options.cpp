#include "procs/tour_runner/tour_runner_options.h"

#include <cmath>

namespace rgnav::tour_runner {

TourRunnerOptions load_options(const config::Config& t, const config::Config& f, const config::RobotDescription& robot,
                               const std::string& config_dir)
{
  TourRunnerOptions o;
  o.tour_file = t.required_string("file");
  if (!o.tour_file.empty() && o.tour_file[0] != '/') o.tour_file = config_dir + "/" + o.tour_file;
  o.max_spacing = t.number("max_spacing_m", o.max_spacing, 0.5, 2.0);
  o.sequencer.reach_radius = t.number("reach_radius_m", o.sequencer.reach_radius, 0.05, 2.0);
  o.sequencer.lookahead = static_cast<int>(t.integer("lookahead", o.sequencer.lookahead, 1, 20));
  o.output = t.choice("output", "base_cmd", {"base_cmd", "targets"}) == "targets" ? TourRunnerOptions::Output::kTargets
                                                                               : TourRunnerOptions::Output::kBaseCmd;
  o.exit_when_done = t.boolean("exit_when_done", o.exit_when_done);
  o.max_speed = t.number("max_speed_mps", o.max_speed, 0.05, 2.0);
  o.scan_stale_s = t.number("scan_stale_s", o.scan_stale_s, 0.05, 5.0);
  o.cmd_deadline_us = static_cast<int32_t>(t.integer("cmd_deadline_us", o.cmd_deadline_us, 10'000, 1'000'000));
  o.base_from_laser = robot.laser_front.base_from_laser;
  o.follower.max_v = f.number("max_v_mps", o.follower.max_v, 0.05, 1.5);
  o.follower.max_omega = f.number("max_omega_radps", o.follower.max_omega, 0.1, 3.0);
  o.follower.turn_in_place_angle = f.number("turn_in_place_rad", o.follower.turn_in_place_angle, 0.1, M_PI);
  o.follower.robot_radius = robot.radius;
  o.follower.stop_distance = f.number("stop_distance_m", o.follower.stop_distance, 0.0, 2.0);
  o.follower.slow_distance = f.number("slow_distance_m", o.follower.slow_distance, 0.05, 5.0);
  if (o.follower.slow_distance <= o.follower.stop_distance) f.fail("slow_distance_m", "must exceed stop_distance_m");
  return o;
}

}  // namespace rgnav::tour_runner
