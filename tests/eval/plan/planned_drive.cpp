#include "planned_drive.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

#include "bench_stats.h"
#include "geometry/segment2.h"

namespace rgnav::plan_eval {

using geometry::Pose2;
using localize_eval::BenchWorld;

namespace {

// The localizer's hand-over (config/localizer.yaml's defaults).
constexpr double kHandoverReach = 1.5;   // [m] a gateway this near
constexpr double kBboxMargin = 0.3;      // [m] beyond the region's measurement rectangle

}  // namespace

collision_avoidance::Targets to_ca_targets(const planner::TargetList& targets)
{
  collision_avoidance::Targets t;
  t.goal_id = targets.goal_id;
  t.poses = targets.odom_from_target;
  t.max_speed = targets.max_speed;
  t.final_is_goal = targets.final_is_goal;
  return t;
}

PlannedDrive::PlannedDrive(const sim::World& world, const sim::SimulatorOptions& sim_options, const BenchWorld& w,
                           const ClosedLoopSetup& setup)
    : w_(w), setup_(setup), loop_(world, sim_options, setup.lld, setup.ca), planner_(setup.planner)
{
  planner_.set_map(w.map);
  region_ = w_.frames.region_at(loop_.truth());
}

void PlannedDrive::step()
{
  loop_.sense();
  if (!loop_.ready()) return;
  const int64_t utime = loop_.sim().now_utime();
  const Pose2& truth = loop_.truth();
  if (const int64_t r = region_of(truth)) region_ = r;
  const double c0 = localize_eval::thread_cpu();
  if (region_ != 0)
    planner_.on_pose({loop_.truth_utime(), region_, w_.frames.in_region(region_, truth), loop_.odometry().pose});
  planner_.on_blocked(utime, loop_.cannot_pass());
  const auto o = planner_.update(utime);
  planner_cpu_s_ += localize_eval::thread_cpu() - c0;
  if (o.path && o.path->reason != last_reason_) {
    last_reason_ = o.path->reason;
    if (reasons_.size() < 12) reasons_.insert(std::string(planner::to_string(o.path->status)) + ": " + o.path->reason);
  }
  if (o.targets) {
    last_targets_ = *o.targets;
    loop_.set_targets(to_ca_targets(*o.targets));
  }
  loop_.act();
}

int64_t PlannedDrive::region_of(const Pose2& truth) const
{
  // As the localizer hands a particle over (Localizer::hand_over): it stays in its region while
  // on the region's freespace and within its measurement rectangle (+ kBboxMargin); leaving, it
  // goes to the neighbour beyond a gateway within kHandoverReach that holds the place the same
  // way (the nearest such gateway here); else to any region whose freespace holds it; else it stays.
  const auto& map = w_.map;
  const auto holds = [&](int64_t id) {
    const auto* r = map.region(id);
    if (!r || !w_.frames.world_from_region.count(id)) return false;
    const Eigen::Vector2d p = w_.frames.in_region(id, truth).translation();
    const Eigen::Vector2d m = Eigen::Vector2d::Constant(kBboxMargin);
    return r->freespace.is_free(p) && (p.array() >= (r->bbox_min - m).array()).all() &&
           (p.array() <= (r->bbox_max + m).array()).all();
  };
  if (region_ == 0) return w_.frames.region_at(truth);
  if (holds(region_)) return region_;
  int64_t best = 0;
  double best_d = kHandoverReach;
  for (const auto& [id, g] : map.gateways()) {
    if (g.neutralized || g.region_b == 0) continue;
    const int64_t a = map.resolve(g.region_a), b = map.resolve(g.region_b);
    if ((region_ != a && region_ != b) || !w_.frames.world_from_region.count(a)) continue;
    const int64_t other = region_ == a ? b : a;
    // The gateway's lines, in the world through region a.
    const Pose2& world_from_a = w_.frames.world_from_region.at(a);
    double d = std::numeric_limits<double>::infinity();
    for (const auto& [pa, pb] : rgmap::gateway_edges(g.gateway_points))
      d = std::min(d, geometry::point_segment_distance(truth.translation(), world_from_a * pa, world_from_a * pb));
    if (d <= best_d && holds(other)) {
      best_d = d;
      best = other;
    }
  }
  if (best) return best;
  // No neighbour holds the place either (the robot is between the region's freespace and the
  // neighbour's, or went on past a small crossing into the region beyond): a perfect localizer
  // knows the region that holds it (the real one relocalizes when its particles lose the map).
  const int64_t at = w_.frames.region_at(truth, region_);
  return at ? at : region_;
}

std::string PlannedDrive::targets_text(size_t n) const
{
  std::ostringstream out;
  out << std::fixed << std::setprecision(2);
  const Pose2 world_from_odom = loop_.truth() * loop_.odometry().pose.inverse();
  for (size_t k = 0; k < last_targets_.odom_from_target.size() && k < n; ++k) {
    const Pose2 t = world_from_odom * last_targets_.odom_from_target[k];
    out << " (" << t.x() << "," << t.y() << ")";
  }
  return out.str();
}

}  // namespace rgnav::plan_eval
