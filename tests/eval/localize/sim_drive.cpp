#include "sim_drive.h"

#include <cmath>

#include "geometry/pose_track.h"
#include "sim/waypoint_follower.h"

namespace rgnav::localize_eval {

namespace {
geometry::Pose2 to_pose(const sim::Pose2& p) { return geometry::Pose2(p.x, p.y, p.theta); }
}  // namespace

DriveResult run_drive(sim::World world, sim::SimulatorOptions options, const DriveSpec& spec,
                      const std::function<void(const DriveStep&)>& on_scan,
                      const std::function<void(const OdometryStep&)>& on_odometry)
{
  DriveResult res;
  if (spec.route.empty()) return res;
  world.start = sim::Pose2{spec.route.front().x(), spec.route.front().y(), spec.start_heading};
  options.start_utime = spec.start_utime;
  options.seed = spec.seed;
  options.people_block_robot = false;
  sim::Simulator simulator(world, options);
  sim::WaypointFollower follower(spec.route, [&simulator] { return simulator.truth(); });
  simulator.set_command_source(&follower);
  geometry::PoseTrack odometry, truth;
  std::vector<sensors::LaserScan> pending;   // scans waiting for the odometry sample after them
  int64_t last_odometry = 0;
  double distance = 0;
  const std::chrono::microseconds chunk(static_cast<int64_t>(1e6 / options.laser.rate_hz()));
  while (!follower.done() && simulator.time_s() < spec.max_s) {
    auto out = simulator.step(chunk);
    for (const auto& o : out.odometry) {
      const geometry::Pose2 odom = spec.odom_offset * to_pose(o.odom_from_base);
      odometry.add(o.utime, odom);
      truth.add(o.utime, to_pose(o.world_from_base));
      last_odometry = o.utime;
      distance = o.true_distance;
      res.end_odom = odom;
      if (on_odometry) on_odometry({o.utime, odom, o.v, o.omega});
    }
    for (auto& s : out.scans) {
      s = sensors::with_message_precision(s);
      s.scan_id += 1;
      pending.push_back(std::move(s));
    }
    size_t done = 0;
    for (; done < pending.size() && pending[done].utime <= last_odometry; ++done) {
      const auto& s = pending[done];
      const auto odom = odometry.at(s.utime);
      const auto tru = truth.at(s.utime);
      if (!odom || !tru) continue;
      on_scan({s, *odom, *tru, distance, static_cast<double>(s.utime - spec.start_utime) * 1e-6});
    }
    pending.erase(pending.begin(), pending.begin() + static_cast<long>(done));
  }
  res.seconds = simulator.time_s();
  res.distance = distance;
  res.end_utime = simulator.now_utime();
  return res;
}

std::vector<sim::Vec2> route_from(const std::vector<sim::Vec2>& tour, size_t k, double s, double length)
{
  std::vector<sim::Vec2> out;
  if (tour.size() < 2) return out;
  k = std::min(k, tour.size() - 2);
  out.push_back(tour[k] + s * (tour[k + 1] - tour[k]));
  double total = 0;
  // The tour is closed (last = first): going on past its end starts it again.
  for (size_t i = k + 1; total < length; i = i + 1 < tour.size() ? i + 1 : 1) {
    total += (tour[i] - out.back()).norm();
    out.push_back(tour[i]);
    if (out.size() > 100000) break;
  }
  return out;
}

}  // namespace rgnav::localize_eval
