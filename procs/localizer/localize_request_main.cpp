// rgnav_localize: the operator tells the localizer where the robot is, or to forget its pose
// and localize globally (./rgnav localize). Publishes one localize_request_t on
// LOCALIZE_REQUEST and exits; the localizer's log and heartbeat status say what it made of it.
//   rgnav_localize --region NAME|ID --pose X Y THETA_DEG [--sigma-xy M] [--sigma-theta DEG]
//   rgnav_localize --global
#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "rgnav/localize_request_t.hpp"
#include "time/message_time.h"

int main(int argc, char** argv)
{
  CLI::App app{"Tell the localizer the robot's pose in a region of the RG map, or start global localization"};
  std::string region;
  std::vector<double> pose;
  double sigma_xy = 0, sigma_theta_deg = 0;
  bool global = false;
  std::string url, channel = "LOCALIZE_REQUEST";
  auto* region_opt = app.add_option("--region", region, "region name, or its id (a number)");
  auto* pose_opt = app.add_option("--pose", pose, "X Y THETA: [m] [m] [deg] in the region's frame")->expected(3);
  app.add_option("--sigma-xy", sigma_xy, "[m] spread of the position (default: the localizer's initial_xy_m)")
      ->check(CLI::Range(0.0, 100.0));
  app.add_option("--sigma-theta", sigma_theta_deg, "[deg] spread of the heading (default: the localizer's initial_theta_deg)")
      ->check(CLI::Range(0.0, 360.0));
  auto* global_opt = app.add_flag("--global", global, "forget the pose: global localization from the next scan");
  app.add_option("--lcm-url", url, "LCM URL (default: LCM_DEFAULT_URL or LCM's default)");
  app.add_option("--channel", channel, "request channel (the localizer's channels.request)");
  global_opt->excludes(region_opt)->excludes(pose_opt);
  region_opt->needs(pose_opt);
  pose_opt->needs(region_opt);
  CLI11_PARSE(app, argc, argv);
  if (!global && region.empty()) {
    std::cerr << "rgnav localize: give --region and --pose, or --global\n" << app.help();
    return 2;
  }

  rgnav::localize_request_t m{};
  m.utime = rgnav::time::wall_utime();
  m.region_from_base = {};
  if (global) {
    m.mode = rgnav::localize_request_t::MODE_GLOBAL;
  } else {
    m.mode = rgnav::localize_request_t::MODE_POSE;
    const bool numeric = region.find_first_not_of("0123456789") == std::string::npos;
    if (numeric) {
      try {
        m.region_id = std::stoll(region);
      } catch (const std::exception&) {
        std::cerr << "rgnav localize: region id " << region << " out of range\n";
        return 2;
      }
    } else {
      m.region_name = region;
    }
    m.region_from_base.x = pose[0];
    m.region_from_base.y = pose[1];
    m.region_from_base.theta = std::remainder(pose[2] * M_PI / 180.0, 2.0 * M_PI);
    m.sigma_xy = sigma_xy;
    m.sigma_theta = sigma_theta_deg * M_PI / 180.0;
  }
  try {
    rgnav::bus::LcmBus bus(url);
    // bus::publish checks what it sends as the localizer will: a NaN or an empty region is refused here.
    if (!rgnav::bus::publish(bus, channel, m)) {
      std::cerr << "rgnav localize: request refused (see the message above)\n";
      return 2;
    }
  } catch (const std::exception& e) {
    std::cerr << "rgnav localize: " << e.what() << "\n";
    return 1;
  }
  if (global)
    std::cout << "sent on " << channel << ": global localization\n";
  else
    std::cout << "sent on " << channel << ": region " << region << " at (" << pose[0] << ", " << pose[1] << ", " << pose[2]
              << " deg)\n";
  return 0;
}
