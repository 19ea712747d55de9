#include "planner/planner.h"

#include "planner/route_time.h"
#include "time/units.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace rgnav::planner {

using geometry::Pose2;

namespace {

using time::kUs;
// A goal with no route is planned again this often (a closed gateway's retry time may come,
// people may leave) besides on every map change.
constexpr double kNoPathRetryS = 10.0;
// [m] a turn on the spot's target lies this far out along the wanted heading: beyond collision
// avoidance's goal tolerance, near enough that it has barely set off when the heading is reached.
constexpr double kTurnTargetM = 0.5;
// [m] the robot's track keeps a place this far from the one before (a tenth of the robot's
// width: the straight pieces between follow where its body went) ...
constexpr double kTrackStep = 0.1;
// [m] ... and starts anew when the pose jumps this far between two updates (the localizer
// corrected itself or relocalized: the line between was never driven).
constexpr double kTrackJump = 0.5;

}  // namespace

const char* to_string(GoalStatus s)
{
  switch (s) {
    case GoalStatus::kNone: return "none";
    case GoalStatus::kActive: return "active";
    case GoalStatus::kNoPath: return "no_path";
    case GoalStatus::kReached: return "reached";
    case GoalStatus::kCancelled: return "cancelled";
  }
  return "?";
}

Planner::Planner(const PlannerOptions& options) : options_(options), global_(options) {}

void Planner::set_map(const rgmap::RgMap& map)
{
  const bool changed = !has_map_ || map.version != map_version_;
  global_.set_map(map);
  has_map_ = true;
  map_version_ = map.version;
  if (!goal_ || !changed) return;
  if (status_ == GoalStatus::kActive || status_ == GoalStatus::kNoPath) {
    // A goal given by name or in a region the map did not have yet may be plannable now.
    if (goal_region_ == 0) {
      resolve_goal();
      return;
    }
    replan_due_ = true;
    replan_reason_ = "the map changed";
  }
}

void Planner::name_region(int64_t region, const std::string& name)
{
  rgmap::RgMap map = global_.map();
  if (auto* r = map.region(map.resolve(region))) {
    r->name = name;
    global_.set_map(map);
  }
}

void Planner::set_goal(const NavGoal& goal, int64_t utime)
{
  // The same goal again (a sender repeating itself) changes nothing, unless it had no path.
  if (goal_ && goal_->goal_id == goal.goal_id && status_ != GoalStatus::kNoPath) return;
  goal_ = goal;
  route_ = {};
  leg_ = 0;
  along_ = 0;
  replans_ = 0;
  last_replan_utime_ = utime;
  strict_places_ = false;
  resolve_goal();
}

void Planner::resolve_goal()
{
  status_ = GoalStatus::kActive;
  reason_.clear();
  goal_region_ = 0;
  path_changed_ = true;
  if (!has_map_) {
    status_ = GoalStatus::kNoPath;
    reason_ = "no map yet";
    return;
  }
  const auto& map = global_.map();
  const NavGoal& goal = *goal_;
  const int64_t region = goal.region_id ? map.resolve(goal.region_id) : global_.region_named(goal.region_name);
  if (region == 0 || !map.region(region) || map.region(region)->state == rgmap::Region::State::kMerged) {
    status_ = GoalStatus::kNoPath;
    reason_ = goal.region_id ? "region " + std::to_string(goal.region_id) + " is not in the map"
                             : "no region is named '" + goal.region_name + "'";
    return;
  }
  if (goal.has_pose) {
    goal_point_ = goal.region_from_goal.translation();
  } else {
    const auto p = global_.region_goal_point(region);
    if (!p) {
      status_ = GoalStatus::kNoPath;
      reason_ = "region " + std::to_string(region) + " has no free place to go to";
      return;
    }
    goal_point_ = *p;
  }
  goal_region_ = region;
  replan_due_ = true;
  replan_reason_ = "new goal";
}

void Planner::cancel(int64_t goal_id, int64_t utime)
{
  if (goal_ && goal_->goal_id == goal_id && (status_ == GoalStatus::kActive || status_ == GoalStatus::kNoPath))
    finish(GoalStatus::kCancelled, "cancelled by the operator", utime);
}

void Planner::finish(GoalStatus status, const std::string& reason, int64_t utime)
{
  (void)utime;
  status_ = status;
  reason_ = reason;
  route_ = {};
  replan_due_ = false;
  path_changed_ = true;
  targets_due_ = true;   // an empty list: collision avoidance stops pursuing
}

void Planner::on_pose(const RobotPose& pose)
{
  pose_ = pose;
  record_track();
}

void Planner::record_track()
{
  if (!has_map_ || options_.execution.track_back_m <= 0) return;
  const auto& map = global_.map();
  const auto* here = map.region(map.resolve(pose_->region_id));
  if (!here) return;
  const Eigen::Vector2d in_map = here->map_from_region * pose_->region_from_base.translation();
  double step = 0;
  if (!track_.empty()) {
    const auto* last = map.region(map.resolve(track_.front().region));
    step = last ? (last->map_from_region * track_.front().point - in_map).norm() : kTrackJump + 1;
    if (step < kTrackStep) return;
    if (step > kTrackJump) {
      track_.clear();
      track_length_ = 0;
      step = 0;
    }
  }
  track_.push_front({pose_->region_id, pose_->region_from_base.translation(), step});
  track_length_ += step;
  while (track_.size() > 2 && track_length_ - track_[track_.size() - 2].step >= options_.execution.track_back_m) {
    track_.pop_back();
    track_length_ -= track_.back().step;
    track_.back().step = 0;
  }
}

std::vector<Eigen::Vector2d> Planner::track_in(int64_t region) const
{
  std::vector<Eigen::Vector2d> out;
  const auto& map = global_.map();
  const auto* to = map.region(map.resolve(region));
  if (!to) return out;
  const Pose2 region_from_map = to->map_from_region.inverse();
  for (const auto& place : track_) {
    if (place.region == region) {
      out.push_back(place.point);
      continue;
    }
    const auto* from = map.region(map.resolve(place.region));
    if (!from) break;   // a region gone from the map: the track ends there
    out.push_back(region_from_map * from->map_from_region * place.point);
  }
  return out;
}

void Planner::on_blocked(int64_t utime, bool blocked)
{
  if (blocked && !blocked_) blocked_since_ = utime;
  blocked_ = blocked;
}

bool Planner::track_progress()
{
  if (!pose_ || route_.empty()) return false;
  // The leg of the pose's region: the current one, or one further on (a gateway was crossed).
  size_t k = leg_;
  while (k < route_.legs.size() && route_.legs[k].region_id != pose_->region_id) ++k;
  Pose2 here = pose_->region_from_base;
  if (k == route_.legs.size()) {
    // The pose's region is not on the route: a route planned from the region beside a gateway
    // the robot stands in, before the localizer hands the pose over (GlobalPlanner::start_beside),
    // or a robot off the route. The pose in the current leg's region through the map frame.
    const auto there = pose_in_region(route_.legs[leg_].region_id);
    if (!there) return false;
    k = leg_;
    here = *there;
  }
  const int64_t now = pose_->utime;
  if (k > leg_) enter_leg(k, now);
  double distance = 0;
  along_ = project_onto_leg(route_.legs[leg_], here.translation(), along_, &distance);
  const RouteLeg& leg = route_.legs[leg_];
  // Progress: the robot got this much further along the route.
  constexpr double kProgressStep = 0.3;   // [m]
  const double arc = route_.leg_start(leg_) + along_;
  if (arc >= progress_arc_ + kProgressStep) {
    progress_arc_ = arc;
    progress_utime_ = now;
  }
  if (leg.exit_gateway && !gateway_reached_utime_ &&
      (leg.points.back() - here.translation()).norm() <= options_.execution.gateway_reach_m)
    gateway_reached_utime_ = now;
  return distance <= options_.execution.off_route_m;
}

void Planner::enter_leg(size_t k, int64_t now)
{
  // Gateways crossed: learn how long the crossing and the region before it took.
  for (size_t j = leg_; j < k; ++j) {
    const auto& leg = route_.legs[j];
    const auto* gw = global_.map().gateway(leg.exit_gateway);
    const int64_t reached = j == leg_ && gateway_reached_utime_ ? gateway_reached_utime_ : now;
    if (gw) global_.costs().gateway_passed(*gw, (now - reached) * kUs);
    if (j == leg_ && leg.entry_gateway && leg_entered_utime_)
      global_.costs().region_traversed(leg.region_id, leg.entry_gateway, leg.exit_gateway,
                                       (reached - leg_entered_utime_) * kUs);
  }
  leg_ = k;
  along_ = 0;
  leg_entered_utime_ = now;
  gateway_reached_utime_ = 0;
}

bool Planner::route_valid() const
{
  if (route_.empty()) return false;
  const auto& map = global_.map();
  for (const auto& leg : route_.legs) {
    const auto* r = map.region(leg.region_id);
    if (!r || r->state == rgmap::Region::State::kMerged) return false;
    if (leg.exit_gateway && !map.gateway(leg.exit_gateway)) return false;
  }
  return true;
}

bool Planner::goal_reached() const
{
  if (!pose_ || route_.empty()) return false;
  // The goal in the frame of the leg the robot is on.
  const size_t k = leg_;
  const auto here = pose_in_region(route_.legs[k].region_id);
  if (!here) return false;
  Pose2 here_from_goal_frame;
  for (size_t j = k; j + 1 < route_.legs.size(); ++j) here_from_goal_frame = here_from_goal_frame * route_.legs[j].this_from_next;
  const Eigen::Vector2d goal = here_from_goal_frame * goal_point_;
  if ((here->translation() - goal).norm() > goal_->position_tolerance) return false;
  if (goal_->heading_tolerance >= M_PI || !goal_->has_pose) return true;
  const double heading = goal_->region_from_goal.theta() + here_from_goal_frame.theta();
  return std::abs(geometry::normalize_angle(here->theta() - heading)) <= goal_->heading_tolerance;
}

std::optional<Pose2> Planner::pose_in_region(int64_t region) const
{
  if (!pose_) return std::nullopt;
  if (pose_->region_id == region) return pose_->region_from_base;
  // Neighbouring regions are placed consistently in the map frame (loop closures move far ones).
  const auto& map = global_.map();
  const auto* here = map.region(map.resolve(pose_->region_id));
  const auto* there = map.region(map.resolve(region));
  if (!here || !there) return std::nullopt;
  return there->map_from_region.inverse() * here->map_from_region * pose_->region_from_base;
}

PlanRequest Planner::request_from_pose(int64_t utime) const
{
  PlanRequest req;
  req.start_region = pose_->region_id;
  req.start = pose_->region_from_base.translation();
  req.goal_region = goal_region_;
  req.goal = goal_point_;
  req.has_goal_heading = goal_->has_pose && goal_->heading_tolerance < M_PI;
  req.goal_heading = goal_->region_from_goal.theta();
  if (goal_->beyond_known) req.goal_reach = options_.grid.beyond_known_reach;
  req.now_s = utime * kUs;
  req.track = track_in(pose_->region_id);
  req.strict_places = strict_places_;
  return req;
}

void Planner::handle_stuck(int64_t utime)
{
  // Stuck: collision avoidance reports it cannot pass and the robot has made no progress along
  // the route, both for blocked_after_s (squeezing through a door in reactive mode is progress).
  const auto& e = options_.execution;
  if (!blocked_) return;
  const double stuck_s = (utime - std::max(blocked_since_, progress_utime_)) * kUs;
  if (stuck_s < e.blocked_after_s || (utime - last_stuck_check_utime_) * kUs < e.min_replan_period_s) return;
  last_stuck_check_utime_ = utime;
  const RouteLeg& leg = route_.legs[leg_];
  const auto* gw = global_.map().gateway(leg.exit_gateway);
  const double to_gateway = (leg.points.back() - pose_->region_from_base.translation()).norm();
  if (!gw || to_gateway > e.gateway_reach_m) {
    // Away from gateways, collision avoidance cannot pass where the grid has a way (furniture
    // the line map holds too thinly, people standing about): the place just ahead on the route
    // is taken for an obstacle for closed_retry_s and the route planned round it. Planning again
    // on the same grid gave the same route, and the robot stood until the goal's sender gave up.
    // (Its edge a cell farther than the robot's radius: the robot's own cell stays free, or
    // the place would cut the robot off from its region's free space.)
    const auto& g = options_.grid;
    const double ahead = std::min(along_ + g.robot_radius + g.blocked_radius + g.resolution, leg.length);
    const Eigen::Vector2d at = point_along(leg, ahead);
    // Nothing ahead to block (a turn on the spot, the goal under the robot): the goal's sender decides.
    if ((at - pose_->region_from_base.translation()).norm() < options_.grid.robot_radius) return;
    if (options_.grid.blocked_radius <= 0) {
      // Places are not blocked (config): plan again from here, as it was before places were.
      replan_due_ = true;
      replan_reason_ = "blocked";
      return;
    }
    // This goal's routes keep off the place from now on: round it where there is a way, else
    // NO_PATH (mostly furniture the line map holds too thinly: it does not move, and waiting
    // there only costs time). Other goals may still be routed through it where they have no
    // other way (GlobalPlanner::plan).
    global_.block_place(leg.region_id, at, utime * kUs + options_.global.closed_retry_s);
    strict_places_ = true;
    replan_due_ = true;
    replan_reason_ = fmt::format("blocked at ({:.2f}, {:.2f}) in region {}", at.x(), at.y(), leg.region_id);
    return;
  }
  // Before the route's next gateway. With a way round that costs no more than waiting here
  // closed_after_s, it is left at once (marked closed for a while, its cost raised); else it
  // counts as closed only after closed_after_s, so that people in a doorway or a hallway's
  // opening are waited for rather than gone round across the building or reported as NO_PATH.
  PlanRequest around = request_from_pose(utime);
  around.avoid_gateway = gw->id;
  std::string why;
  const auto round = global_.plan(around, &why);
  const bool way_round = round && round->cost_s <= remaining_cost_s() + e.closed_after_s;
  if (way_round || stuck_s >= e.closed_after_s) {
    global_.costs().gateway_failed(*gw, utime * kUs);
    replan_due_ = true;
    replan_reason_ = "gateway " + std::to_string(gw->id) + (way_round ? " cannot be passed" : " is closed");
  }
}

double Planner::remaining_cost_s() const
{
  double left = 0;
  for (size_t j = leg_; j < route_.legs.size(); ++j) left += route_.legs[j].length;
  left = std::max(0.0, left - along_);
  return route_.length > 0 ? route_.cost_s * left / route_.length : 0.0;
}

std::optional<Route> Planner::turn_on_the_spot() const
{
  // Only the heading differs: nothing to plan (the round robot turns where it stands, whatever
  // the grid calls the cells round it), and a robot cut off from the region's free space can
  // still look round. The goal must be in the region the robot is in.
  if (!goal_ || !pose_ || !goal_->has_pose || goal_->heading_tolerance >= M_PI || goal_region_ != pose_->region_id)
    return std::nullopt;
  const Eigen::Vector2d here = pose_->region_from_base.translation();
  if ((goal_point_ - here).norm() > goal_->position_tolerance) return std::nullopt;
  const double heading = goal_->region_from_goal.theta();
  if (std::abs(geometry::normalize_angle(pose_->region_from_base.theta() - heading)) <= goal_->heading_tolerance)
    return std::nullopt;
  Route turn;
  RouteLeg leg;
  leg.region_id = goal_region_;
  leg.points = {here, here};
  turn.legs.push_back(leg);
  turn.has_goal_heading = true;
  turn.goal_heading = heading;
  // Collision avoidance takes positions: a target out along the heading, which it turns toward
  // on the spot before driving (its turn-first rule); the goal is reached, and the targets
  // withdrawn, once the heading is.
  const Eigen::Vector2d out = here + kTurnTargetM * Eigen::Vector2d(std::cos(heading), std::sin(heading));
  turn.targets.push_back({0, 0.0, Pose2(out, heading)});
  turn.map_version = map_version_;
  return turn;
}

bool Planner::replan(int64_t utime, const std::string& why)
{
  last_replan_utime_ = utime;
  replan_due_ = false;
  if (auto turn = turn_on_the_spot()) {
    ++replans_;
    status_ = GoalStatus::kActive;
    reason_ = "turning on the spot";
    route_ = std::move(*turn);
    leg_ = 0;
    along_ = 0;
    leg_entered_utime_ = utime;
    gateway_reached_utime_ = 0;
    blocked_since_ = utime;
    progress_utime_ = utime;
    progress_arc_ = 0;
    path_changed_ = true;
    targets_due_ = true;
    return true;
  }
  const PlanRequest req = request_from_pose(utime);
  std::string fail;
  auto route = global_.plan(req, &fail, &last_stats_);
  if (!route) {
    status_ = GoalStatus::kNoPath;
    reason_ = fail;
    route_ = {};
    path_changed_ = true;
    targets_due_ = true;
    return true;
  }
  // Keep a still valid route unless the new one is clearly cheaper (no oscillation).
  const bool keep_old = status_ == GoalStatus::kActive && route_valid() && why == "the map changed" &&
                        route->cost_s >= (1.0 - options_.execution.switch_gain) * remaining_cost_s();
  ++replans_;
  if (keep_old) return false;
  status_ = GoalStatus::kActive;
  reason_ = why;
  route_ = std::move(*route);
  route_.targets = cut_targets(route_, options_.execution.target_spacing_min, options_.execution.target_spacing_max);
  trajectory::Limits limits;
  limits.v_max = options_.execution.max_speed;
  limits.a_max = options_.execution.max_accel;
  limits.omega_max = options_.execution.max_omega;
  route_.expected_s = predicted_time(route_, limits);
  leg_ = 0;
  along_ = 0;
  leg_entered_utime_ = utime;
  gateway_reached_utime_ = 0;
  blocked_since_ = utime;   // blocked time counts afresh on the new route
  progress_utime_ = utime;
  progress_arc_ = 0;
  path_changed_ = true;
  targets_due_ = true;
  return true;
}

std::optional<TargetList> Planner::make_targets(int64_t utime) const
{
  TargetList t;
  t.utime = utime;
  t.goal_id = goal_ ? goal_->goal_id : 0;
  t.max_speed = options_.execution.max_speed;
  if (status_ != GoalStatus::kActive || route_.empty() || !pose_) return t;   // nothing to pursue
  const auto& e = options_.execution;
  // The route's fixed targets not yet passed (the robot within pass_distance before one passes
  // it), reaching targets_ahead_m past the robot, at least two while there are two.
  constexpr double kPassDistance = 0.3;
  const double progress = route_.leg_start(leg_) + along_;
  // Leg frame -> odometry frame through the pose (both at the pose's time). The pose may be in
  // another region than the leg's while a replan is due (the map's current region changed, or
  // the robot left the route): then through the map frame, where both regions are placed.
  Pose2 odom_from_leg = pose_->odom_from_base * pose_->region_from_base.inverse();
  const int64_t leg_region = route_.legs[leg_].region_id;
  if (pose_->region_id != leg_region) {
    const auto& map = global_.map();
    const auto* here = map.region(map.resolve(pose_->region_id));
    const auto* there = map.region(map.resolve(leg_region));
    if (!here || !there) return t;   // a region gone from the map: nothing sensible until the replan
    odom_from_leg = odom_from_leg * here->map_from_region.inverse() * there->map_from_region;
  }
  for (size_t i = 0; i < route_.targets.size(); ++i) {
    const RouteTarget& rt = route_.targets[i];
    if (rt.arc <= progress + kPassDistance && i + 1 < route_.targets.size()) continue;
    if (rt.arc > progress + e.targets_ahead_m && t.odom_from_target.size() >= 2) break;
    const Pose2 leg_from_target = rt.leg >= leg_ ? route_.frame_of(leg_, rt.leg) * rt.pose
                                                 : route_.frame_of(rt.leg, leg_).inverse() * rt.pose;
    t.odom_from_target.push_back(odom_from_leg * leg_from_target);
    t.final_is_goal = i + 1 == route_.targets.size();
  }
  return t;
}

Planner::Output Planner::update(int64_t utime)
{
  Output out;
  const auto& e = options_.execution;
  const bool pursuing = goal_ && (status_ == GoalStatus::kActive || status_ == GoalStatus::kNoPath) && goal_region_ != 0;
  const bool pose_fresh = pose_ && (utime - pose_->utime) * kUs <= e.pose_timeout_s;
  if (pursuing && pose_fresh) {
    if (status_ == GoalStatus::kActive && !route_.empty()) {
      if (!track_progress() && !replan_due_) {
        replan_due_ = true;
        replan_reason_ = "off the route";
      }
      if (goal_reached()) {
        finish(GoalStatus::kReached, "reached", utime);
      } else if (!replan_due_) {
        handle_stuck(utime);
      }
    }
    if (status_ == GoalStatus::kActive || status_ == GoalStatus::kNoPath) {
      const double since = (utime - last_replan_utime_) * kUs;
      const bool first = route_.empty() && status_ == GoalStatus::kActive;
      if (status_ == GoalStatus::kNoPath && since >= kNoPathRetryS) {
        replan_due_ = true;
        replan_reason_ = "retry";
      }
      if (replan_due_ && (first || since >= e.min_replan_period_s)) replan(utime, first ? "new goal" : replan_reason_);
    }
  }
  if (goal_ && (path_changed_ || targets_due_ || (status_ == GoalStatus::kActive && pose_fresh &&
                                                  (utime - last_targets_utime_) * kUs >= e.resend_period_s))) {
    if (status_ == GoalStatus::kActive && !pose_fresh && !targets_due_) {
      // No pose: nothing sensible to send.
    } else {
      out.targets = make_targets(utime);
      last_targets_utime_ = utime;
      targets_due_ = false;
    }
  }
  if (path_changed_ && goal_) {
    PathReport r;
    r.utime = utime;
    r.goal_id = goal_->goal_id;
    r.status = status_;
    r.reason = reason_;
    r.route = route_;
    r.replans = replans_;
    double left = 0;
    for (size_t j = leg_; j < route_.legs.size(); ++j) left += route_.legs[j].length;
    left = std::max(0.0, left - along_);
    r.remaining_s = route_.length > 0 ? route_.expected_s * left / route_.length : 0.0;
    out.path = r;
    path_changed_ = false;
  }
  return out;
}

}  // namespace rgnav::planner
