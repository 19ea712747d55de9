#include "viewer/viewer_options.h"

#include <boost/asio/ip/address.hpp>

#include <cmath>

#include "config/config.h"
#include "config/robot_description.h"
#include "config/string_fields.h"

namespace rgnav::viewer {

ViewerOptions load_viewer_options(const config::Config& cfg, const config::RobotDescription& robot,
                                  const std::string& default_web_root)
{
  ViewerOptions o;
  auto& c = o.channels;
  config::read_strings(cfg.section("channels"), {{"rg_map", &c.rg_map},
                                                 {"rg_region", &c.rg_region},
                                                 {"rg_graph", &c.rg_graph},
                                                 {"pose", &c.pose},
                                                 {"slam_pose", &c.slam_pose},
                                                 {"laser", &c.laser},
                                                 {"targets", &c.targets},
                                                 {"trajectory", &c.trajectory},
                                                 {"global_path", &c.global_path},
                                                 {"objects3d", &c.objects3d},
                                                 {"supervisor_status", &c.supervisor_status},
                                                 {"heartbeat", &c.heartbeat},
                                                 {"nav_goal", &c.nav_goal}});

  const auto http = cfg.section("http");
  o.server.address = http.string("address", o.server.address);
  boost::system::error_code ec;
  boost::asio::ip::make_address(o.server.address, ec);
  if (ec) http.fail("address", "'" + o.server.address + "' is not an IP address (127.0.0.1: this host only, 0.0.0.0: every interface)");
  o.server.port = static_cast<uint16_t>(http.integer("port", o.server.port, 0, 65535));
  o.server.web_root = http.string("web_root", "");
  if (o.server.web_root.empty()) o.server.web_root = default_web_root;
  o.server.goal_token = http.string("goal_token", "");
  if (!o.server.goal_token.empty() && o.server.goal_token.size() < 16)
    http.fail("goal_token", "a token shorter than 16 characters is guessable ('' turns goals from other hosts off)");
  o.server.max_clients = static_cast<size_t>(http.integer("max_clients", static_cast<int64_t>(o.server.max_clients), 1, 1000));
  o.server.queue_frames = static_cast<size_t>(http.integer("queue_frames", static_cast<int64_t>(o.server.queue_frames), 12, 1000));
  o.server.max_input_bytes = static_cast<size_t>(http.integer("max_input_bytes", static_cast<int64_t>(o.server.max_input_bytes), 256, 65536));

  const auto rates = cfg.section("rates");
  o.frame_hz = rates.number("frame_hz", o.frame_hz, 1.0, 100.0);
  o.scan_hz = rates.number("scan_hz", o.scan_hz, 0.1, 50.0);
  o.scan_max_points = static_cast<int>(rates.integer("scan_max_points", o.scan_max_points, 10, 2000));
  const double map_hz = rates.number("map_hz", 1.0, 0.05, 20.0);
  o.scene.map_period = std::chrono::milliseconds(static_cast<int64_t>(std::lround(1000.0 / map_hz)));
  const double status_hz = rates.number("status_hz", 1.0, 0.1, 10.0);
  o.scene.status_period = std::chrono::milliseconds(static_cast<int64_t>(std::lround(1000.0 / status_hz)));

  const auto view = cfg.section("view");
  o.pose_fresh_s = view.number("pose_fresh_s", o.pose_fresh_s, 0.05, 60.0);
  o.trajectory_step_m = view.number("trajectory_step_m", o.trajectory_step_m, 0.01, 2.0);
  o.scene.heartbeat_alert_s = view.number("heartbeat_alert_s", o.scene.heartbeat_alert_s, 0.2, 600.0);
  o.goal_position_tolerance = view.number("goal_position_tolerance_m", o.goal_position_tolerance, 0.05, 10.0);
  o.scene.robot_radius = robot.radius;
  return o;
}

}  // namespace rgnav::viewer
