#include "sim_mapping.h"

#include <Eigen/LU>

#include <ctime>
#include <stdexcept>

#include "geometry/pose_track.h"
#include "geometry/symmetric_eigen2.h"
#include "offline_mapping.h"
#include "sim/step_order.h"
#include "sim/tour_planner.h"
#include "sim/waypoint_follower.h"
#include "sim/world_yaml.h"

namespace rgnav::scan_mapper {
namespace {

Pose2 to_pose(const sim::Pose2& p) { return Pose2{p.x, p.y, normalize_angle(p.theta)}; }

// The simulated scan as the mapper would get it from LASER_FRONT: header rounded to float.
sensors::LaserScan to_scan(const sensors::LaserScan& s)
{
  sensors::LaserScan out = sensors::with_message_precision(s);
  out.scan_id = s.scan_id + 1;  // ids start at 1 like LASER_FRONT's
  return out;
}

}  // namespace

SimMappingResult run_sim_mapping(const std::string& world_path, const sim::SimulatorOptions& sim_options_in,
                                 ScanMapperOptions mapper_options, const SimMappingOptions& options)
{
  SimMappingResult res;
  sim::World world = sim::load_world(world_path);
  // The bench's plain tour follower neither waits for nor passes people (a person ahead stalls
  // it until the time cap): people stay out, or walk where the robot's body passes through them.
  sim::SimulatorOptions sim_options = sim_options_in;
  if (options.keep_people) {
    res.people_walking = static_cast<int>(world.people.size());
    sim_options.people_block_robot = false;
  } else {
    res.people_removed = static_cast<int>(world.people.size());
    world.people.clear();
  }
  res.world = world.name;
  const sim::Tour tour = sim::plan_tour(world, sim_options.robot);
  if (tour.waypoints.size() < 2) throw std::runtime_error(world_path + ": no tour through this world");
  res.tour_length_m = tour.length;
  res.laps = options.laps;
  const std::vector<sim::Vec2> route = sim::laps_route(tour, options.laps);

  // The laser mounting pose is the simulated robot's, as for a real robot's log.
  const auto& l = sim_options.laser;
  mapper_options.base_from_laser = Pose2{l.mount_x, l.mount_y, normalize_angle(l.mount_yaw)};
  ScanMapper mapper(mapper_options);
  sim::Simulator simulator(world, sim_options);
  sim::WaypointFollower follower(route, [&simulator] { return simulator.truth(); });
  simulator.set_command_source(&follower);

  geometry::PoseTrack truth;   // from the simulator's odometry samples, which carry the truth
  std::vector<Pose2> truth_at_node, odom_at_node;
  const std::chrono::microseconds chunk(static_cast<int64_t>(1e6 / l.rate_hz()));
  double last_truth_distance = 0.0;
  while (!follower.done()) {
    if (simulator.time_s() >= options.max_sim_s) {
      res.capped = true;
      break;
    }
    const double c0 = thread_cpu_seconds();
    const auto out = simulator.step(chunk);
    const double c1 = thread_cpu_seconds();
    res.sim_cpu_seconds += c1 - c0;
    for (const auto& o : out.odometry) {
      truth.add(o.utime, to_pose(o.world_from_base));
      last_truth_distance = o.true_distance;
    }
    sim::in_time_order(
        out, [&](const sim::OdometrySample& o) { mapper.add_odometry({o.utime, to_pose(o.odom_from_base)}); },
        [&](const sensors::LaserScan& s) {
          const auto up = mapper.add_scan(to_scan(s));
          if (up.accepted) {
            const auto t = truth.at(s.utime);
            if (!t) throw std::runtime_error("no ground truth at a scan");
            truth_at_node.push_back(*t);
            odom_at_node.push_back(mapper.nodes().back().odom_from_base);
            res.online.push_back(mapper.nodes().back().map_from_base);
          }
          if (up.loop_closed) res.loop_closed_at.push_back(static_cast<int>(mapper.nodes().size()) - 1);
        });
    res.mapping_cpu_seconds += thread_cpu_seconds() - c1;
  }
  res.sim_seconds = simulator.time_s();
  res.driven_m = last_truth_distance;
  res.collisions = simulator.collisions();
  res.stats = mapper.stats();
  res.nodes = mapper.nodes();

  std::vector<Pose2> est;
  std::vector<TimedPose> timed;
  for (size_t k = 0; k < res.nodes.size(); ++k) {
    est.push_back(res.nodes[k].map_from_base);
    timed.push_back({res.nodes[k].scan.utime, truth_at_node[k]});
  }
  res.relations = relation_error(est, truth_at_node, select_relations(timed));
  res.truth = truth_at_node;
  res.ate_rmse_m = ate_rmse(est, truth_at_node);
  res.odometry_ate_rmse_m = ate_rmse(odom_at_node, truth_at_node);
  for (const auto& e : mapper.graph().edges()) {
    if (!e.robust) continue;   // robust edges are the loop closures (scan_mapper.cpp)
    const Pose2 truth_rel = between(truth_at_node[static_cast<size_t>(e.from)], truth_at_node[static_cast<size_t>(e.to)]);
    if ((truth_rel.translation() - e.from_from_to.translation()).norm() > 0.1) ++res.loop_closures_wrong;
    // Off by what its own information says matters (a hallway closure is free along the axis).
    const Eigen::Vector3d r = edge_error(truth_at_node[static_cast<size_t>(e.from)], truth_at_node[static_cast<size_t>(e.to)],
                                         e.from_from_to);
    const double chi2 = r.dot(e.information * r);
    if (chi2 > mapper_options.loop.max_residual_chi2) ++res.loop_closures_inconsistent;
    const Eigen::Matrix2d cov = e.information.inverse().topLeftCorner<2, 2>();
    res.closures.push_back({e.from, e.to, r, chi2, std::sqrt(geometry::symmetric_eigen(cov).values.maxCoeff())});
  }
  return res;
}

}  // namespace rgnav::scan_mapper
