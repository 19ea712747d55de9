#include "explorer/explorer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "explorer/opening.h"
#include "explorer/view_gain.h"
#include "explorer/view_point.h"
#include "planner/no_path_reason.h"

namespace rgnav::explorer {

using Eigen::Vector2d;

namespace {

constexpr double kSamePlace = 0.5;   // [m] a newly chosen goal whose frontier is this near the running one's is the same goal
constexpr double kMovedSinceFailure = 0.5;   // [m] the robot this far from the last failure's place is elsewhere
constexpr double kTrackStep = 0.2;           // [m] the robot's track keeps a place every this far ...
constexpr size_t kTrackPlaces = 100;         // ... the newest this many (20 m)
constexpr double kLaneMargin = 0.05;         // [m] a lane through an opening is the robot's width and this each side
constexpr double kNoViewAfter = 1e4;         // [m] a frontier without a view point counts as this much farther
// How a goal ended (ExplorerStatus, last_end()).
constexpr const char* kExplored = "explored";       // its frontier is gone from the map
constexpr const char* kNoProgress = "no progress";  // the robot got no nearer in progress_timeout_s
constexpr const char* kTimedOut = "timed out";
constexpr const char* kNoOpening = "no opening: the map's lines close it to the robot";

nlohmann::json point_json(const Vector2d& p) { return {p.x(), p.y()}; }

planner::PlannerOptions grid_only(const planner::GridOptions& grid)
{
  planner::PlannerOptions o;
  o.grid = grid;
  return o;
}

Vector2d point_from(const nlohmann::json& j)
{
  if (!j.is_array() || j.size() != 2) throw std::invalid_argument("a point is not [x, y]");
  const Vector2d p(j[0].get<double>(), j[1].get<double>());
  if (!p.allFinite()) throw std::invalid_argument("a point is not finite");
  return p;
}

}  // namespace

const char* to_string(ExploreGoal::Kind k)
{
  switch (k) {
    case ExploreGoal::Kind::kFrontier: return "frontier";
    case ExploreGoal::Kind::kGateway: return "gateway";
    case ExploreGoal::Kind::kRegion: return "region";
    case ExploreGoal::Kind::kLook: return "look";
    case ExploreGoal::Kind::kStep: return "step";
  }
  return "?";
}

const char* to_string(Phase p)
{
  switch (p) {
    case Phase::kWaiting: return "waiting";
    case Phase::kExploring: return "exploring";
    case Phase::kDone: return "done";
  }
  return "waiting";
}

Explorer::Explorer(ExplorerOptions options)
    : options_(options), grids_(grid_only(options.grid)), stack_(options.stack)
{
}

void Explorer::set_map(std::shared_ptr<const rgmap::RgMap> map)
{
  map_ = std::move(map);
  if (map_) grids_.set_map(*map_);
}

void Explorer::set_pose(const RobotPose& pose)
{
  pose_ = pose;
  const Vector2d at = pose.map_from_base.translation();
  if (track_.empty() || (at - track_.back()).norm() >= kTrackStep) track_.push_back(at);
  if (track_.size() > kTrackPlaces) track_.erase(track_.begin());
}

void Explorer::add_sightings(const std::vector<GatewaySighting>& sightings, int64_t utime)
{
  if (!map_ || map_->current_region == 0 || phase_ == Phase::kDone) return;
  const int64_t region = map_->resolve(map_->current_region);
  for (const auto& s : sightings) stack_.add(s, region, utime, *map_);
}

void Explorer::goal_report(int64_t goal_id, GoalOutcome outcome, const std::string& reason, int64_t utime)
{
  if (!goal_ || goal_id != goal_->goal_id) return;
  switch (outcome) {
    case GoalOutcome::kActive: return;
    case GoalOutcome::kReached: end_goal(true, "reached", utime); return;
    case GoalOutcome::kNoPath: {
      const auto cause = planner::no_path_cause(reason);
      end_goal(false, reason.empty() ? "no path" : "no path: " + reason, utime, cause == planner::NoPathCause::kStartCutOff,
               cause == planner::NoPathCause::kClosedGateway);
      return;
    }
    case GoalOutcome::kCancelled: end_goal(false, "cancelled", utime); return;
  }
}

bool Explorer::visited(const Vector2d& map_point) const
{
  return std::any_of(visited_.begin(), visited_.end(),
                     [&](const Vector2d& v) { return (v - map_point).norm() < options_.visited_radius; });
}

bool Explorer::failed_here(const Vector2d& map_point, int64_t utime) const
{
  return std::any_of(failed_.begin(), failed_.end(), [&](const FailedPlace& f) {
    return (f.map_point - map_point).norm() < options_.visited_radius &&
           (f.attempts >= options_.max_attempts || utime < f.retry_utime);
  });
}

bool Explorer::failed_before(const Vector2d& map_point) const
{
  return std::any_of(failed_.begin(), failed_.end(),
                     [&](const FailedPlace& f) { return (f.map_point - map_point).norm() < options_.visited_radius; });
}

std::vector<Frontier> Explorer::open_frontiers(int64_t region_id) const
{
  std::vector<Frontier> open;
  const rgmap::Region* r = map_->region(region_id);
  if (!r) return open;
  const GainOptions& gain = options_.frontier.gain;
  const bool left = region_id != map_->resolve(map_->current_region);
  const double min_gain = left ? std::max(gain.min_m2, gain.left_min_m2) : gain.min_m2;
  for (auto& f : find_frontiers(*map_, region_id, options_.frontier).frontiers) {
    // The opening of a gateway waiting on the stack is the stack's, not the region's: it is taken
    // when the region is complete. One gone through or set aside is a frontier like any other if a
    // look past it still shows something: a hallway goes on past a junction whose branch the
    // robot took for a metre, a gap taken for a door may show the room beyond. (Without the gain
    // rule every entry claims its opening: the scraps of freespace edge a gateway gone through
    // leaves would be goals.)
    const Vector2d at = r->map_from_region * f.goal;
    const bool stacked = std::any_of(stack_.entries().begin(), stack_.entries().end(), [&](const StackEntry& e) {
      return (e.state == StackEntry::State::kPending || gain.min_m2 <= 0.0) &&
             (e.crossing - at).norm() < options_.stack.merge_distance;
    });
    if (stacked) continue;
    // Nothing left to see past it: no goal (the region counts as complete there).
    if (min_gain > 0.0 && unknown_area_beyond(*map_, at, r->map_from_region.rotation() * f.outward, gain) < min_gain)
      continue;
    open.push_back(std::move(f));
  }
  return open;
}

std::vector<int32_t> Explorer::reachable_pieces(int64_t region_id, const planner::RegionGrid& grid) const
{
  std::vector<int32_t> pieces{grid.main_component()};
  if (map_->resolve(map_->current_region) == region_id) {
    const rgmap::Region* r = map_->region(region_id);
    const Vector2d here = r->map_from_region.inverse() * pose_->map_from_base.translation();
    if (const auto c = grid.nearest_free(grid.cell_of(here))) pieces.push_back(grid.component(*c));
  }
  return pieces;
}

std::optional<ExploreGoal> Explorer::frontier_goal(int64_t region_id, int64_t utime, bool untried_only)
{
  const rgmap::Region* r = map_->region(region_id);
  const planner::RegionPlanner* rp = r ? grids_.region_planner(region_id) : nullptr;
  if (!rp) return std::nullopt;
  const std::vector<int32_t> pieces = reachable_pieces(region_id, rp->grid());
  const double wanted = options_.grid.robot_radius + options_.grid.clearance_margin;
  const Vector2d robot = pose_->map_from_base.translation();
  std::optional<ExploreGoal> best;
  double best_d = std::numeric_limits<double>::infinity();
  for (const Frontier& f : open_frontiers(region_id)) {
    const Vector2d at = r->map_from_region * f.goal;
    if (visited(at)) {
      // The robot looked at it and the region's freespace still ends in the unknown there: the
      // region's map does not take in what lies beyond (the RG kernel ends a region's freespace
      // at a narrow passage), so it is a way out of the region — the stack's, to be gone through.
      GatewaySighting s;
      s.crossing = at;
      const Vector2d out = r->map_from_region.rotation() * f.outward;
      s.headings = {std::atan2(out.y(), out.x())};
      s.observations = options_.stack.min_observations;
      stack_.add(s, region_id, utime, *map_);
      continue;
    }
    if (failed_here(at, utime) || (untried_only && failed_before(at))) continue;
    // No view point: nowhere the planner's grid has room for the robot sees it. The frontier
    // itself is still a goal, after every one with a view point (the planner tries the region's
    // other pieces and beyond; its NO_PATH counts as an attempt): skipping it would end
    // exploring while a region may be unexplored behind it.
    const auto view = view_point(*rp, pieces, f.goal, f.outward, wanted, options_.view);
    const Vector2d view_at = r->map_from_region * (view ? view->point : f.goal);
    const double d = (view_at - robot).norm() + (view ? 0.0 : kNoViewAfter);
    if (d >= best_d) continue;
    best_d = d;
    ExploreGoal g;
    g.kind = ExploreGoal::Kind::kFrontier;
    g.region_id = region_id;
    g.region_point = view ? view->point : f.goal;
    g.heading = view ? view->heading : std::atan2(f.outward.y(), f.outward.x());
    g.heading_tolerance = view ? options_.view.heading_tolerance : ExploreGoal{}.heading_tolerance;
    g.tolerance = options_.goal_tolerance;
    g.map_point = view_at;
    g.frontier_point = at;
    best = g;
  }
  return best;
}

std::optional<ExploreGoal> Explorer::gateway_goal(int64_t utime)
{
  const Vector2d robot = pose_->map_from_base.translation();
  for (const StackEntry* e : stack_.order(*map_, start_region_, robot, utime)) {
    const int64_t rid = map_->resolve(e->region_id);
    const rgmap::Region* r = map_->region(rid);
    if (!r || r->state == rgmap::Region::State::kMerged) continue;
    ExploreGoal g;
    g.kind = ExploreGoal::Kind::kGateway;
    g.region_id = rid;
    // Through the opening the map shows beside the detector's crossing point (opening.h).
    const Vector2d crossing = opening_of(*e).value_or(e->crossing);
    g.map_point = crossing + options_.stack.beyond_m * Vector2d(std::cos(e->heading), std::sin(e->heading));
    g.region_point = r->map_from_region.inverse() * g.map_point;
    g.heading = geometry::normalize_angle(e->heading - r->map_from_region.theta());
    g.tolerance = options_.gateway_goal_tolerance;
    g.beyond_known = true;
    g.entry_id = e->id;
    g.frontier_point = g.map_point;
    return g;
  }
  return std::nullopt;
}

std::optional<Vector2d> Explorer::opening_of(const StackEntry& e) const
{
  OpeningOptions aim;
  aim.search_m = options_.stack.aim_search_m;
  // As far past the crossing as the robot must go to have gone through, as wide as it is.
  return aim_through_opening(*map_, e.crossing, e.heading, options_.stack.beyond_m + options_.stack.passed_m,
                             2.0 * (options_.robot_radius + kLaneMargin), aim);
}

void Explorer::set_aside_closed_entries(int64_t utime)
{
  if (options_.stack.aim_search_m <= 0.0) return;
  for (const StackEntry& e : stack_.entries()) {
    // Pending, or due again (its retry time come, or the map near it changed since it was set
    // aside for good: most such changes open nothing, and trying costs a goal's progress bound).
    const bool due = e.state == StackEntry::State::kPending || (e.state == StackEntry::State::kSetAside && e.retry_utime > 0);
    if (!due || opening_of(e)) continue;
    // For good (no attempt would get through); looked at again once the map near it changes, as
    // for a door that opens or a person who stood in a doorway and walked on.
    stack_.failed(e.id, kNoOpening, utime, 0, 1, static_cast<int64_t>(map_->regions().size()),
                  view_of_place(*map_, e.crossing, options_.changed));
  }
}

std::optional<ExploreGoal> Explorer::other_region_goal(int64_t current, int64_t utime, bool untried_only)
{
  std::optional<ExploreGoal> best;
  const Vector2d robot = pose_->map_from_base.translation();
  for (const auto& [id, r] : map_->regions()) {
    if (id == current || r.state == rgmap::Region::State::kMerged) continue;
    auto g = frontier_goal(id, utime, untried_only);
    if (g && (!best || (g->map_point - robot).norm() < (best->map_point - robot).norm())) best = g;
  }
  if (best) best->kind = ExploreGoal::Kind::kRegion;
  return best;
}

std::optional<ExploreGoal> Explorer::choose(int64_t utime)
{
  const int64_t cur = map_->resolve(map_->current_region);
  // Region by region: the current region until it is complete ...
  if (auto g = frontier_goal(cur, utime, true)) return g;
  // ... and the others entered before (the map's current region changes as the robot stands in
  // a doorway or a junction: the hallway it explored a moment ago is still unfinished) ...
  if (options_.stack.after_regions)
    if (auto g = other_region_goal(cur, utime, true)) return g;
  // ... then the next gateway not gone through ...
  if (auto g = gateway_goal(utime)) return g;
  // ... and, with none left, the frontiers that failed before, the current region's first. Tried
  // again before the stack, a frontier the robot cannot get at (behind furniture, in a gap it
  // does not fit through) held it in one room while the rest of the building waited, and taken
  // in another region before the stack, the robot would cross the building to and fro.
  if (auto g = frontier_goal(cur, utime)) return g;
  return other_region_goal(cur, utime, false);
}

bool Explorer::goal_still_open() const
{
  if (is_recovery(*goal_)) return true;
  if (goal_->kind == ExploreGoal::Kind::kGateway) {
    const StackEntry* e = stack_.entry(goal_->entry_id);
    return e && e->state != StackEntry::State::kDone;
  }
  const rgmap::Region* r = map_->region(map_->resolve(goal_->region_id));
  if (!r) return false;
  for (const Frontier& f : open_frontiers(r->id))
    if ((r->map_from_region * f.goal - goal_->frontier_point).norm() < options_.visited_radius) return true;
  return false;
}

void Explorer::end_goal(bool reached, const std::string& reason, int64_t utime, bool start_cut_off, bool behind_closed)
{
  if (!goal_) return;
  if (reached) ++goals_reached_;
  else ++goals_failed_;
  last_end_ = reason;
  if (is_recovery(*goal_)) {
    // A look or a step ended (done or not): the goals are chosen anew from the new view.
    goal_.reset();
    decide_now_ = true;
    return;
  }
  if (!reached && start_cut_off && pose_) {
    // Not the goal's fault: the robot's place joins nothing, and standing there nothing changes.
    // It looks behind; still cut off there, it steps back along its track; cut off after both,
    // the goal fails as any other (tried again when the robot moved or the map changed).
    recovery_due_ = recovery_from(pose_->map_from_base.translation());
    if (recovery_due_ != Recovery::kNone) {
      goal_.reset();
      decide_now_ = true;
      return;
    }
  }
  // A failure counts toward max_attempts only when something could have made it come out
  // otherwise since the goal's last one: the robot got elsewhere or the map changed
  // (last_failure.h). Failing again from the same place on the same map says nothing new (the
  // planner's answer then is the same), and counting it would set everything aside while the
  // robot stands still, and end exploring early.
  std::optional<LastFailure> now;
  if (!reached && map_ && pose_) now = LastFailure{pose_->map_from_base.translation(), map_->version};
  if (now) last_failure_ = now;
  FailedPlace* place = nullptr;
  const StackEntry* entry = goal_->kind == ExploreGoal::Kind::kGateway ? stack_.entry(goal_->entry_id) : nullptr;
  if (!reached && goal_->kind != ExploreGoal::Kind::kGateway) {
    auto it = std::find_if(failed_.begin(), failed_.end(), [&](const FailedPlace& f) {
      return (f.map_point - goal_->frontier_point).norm() < options_.visited_radius;
    });
    if (it == failed_.end()) {
      FailedPlace fresh;
      fresh.map_point = goal_->frontier_point;
      it = failed_.insert(failed_.end(), fresh);
    }
    place = &*it;
  }
  const std::optional<LastFailure> before = entry ? entry->failed_from : place ? place->failed_from : std::nullopt;
  bool counts = !now || tells_more(before, *now, kMovedSinceFailure);
  // A goal the robot got no nearer to (or not to in time) while the planner had a way: blamed on
  // the goal only if the robot arrived somewhere since the last such failure. A robot held where
  // it stands (wedged among furniture, its collision avoidance finding no way on) fails every goal
  // in turn, and counting those set the whole building aside and ended exploring after two rooms.
  const bool could_not_get_on = reason == kNoProgress || reason == kTimedOut;
  if (!reached && could_not_get_on) {
    counts = counts && arrived_since_failure_;
    if (counts) arrived_since_failure_ = false;
  }
  // Evidence the robot can drive: it arrived at a goal (not a frontier the map filled in while it
  // stood, nor a turn on the spot).
  if (reached && reason != kExplored && goal_->kind != ExploreGoal::Kind::kLook) arrived_since_failure_ = true;
  // A gateway taken for closed for a while: the goal is due again later, no attempt of its own
  // (but a bounded number of such failures, each waiting twice as long as the one before).
  if (behind_closed) counts = false;
  const auto retry_after_us = static_cast<int64_t>(options_.retry_after_s * 1e6);
  if (goal_->kind == ExploreGoal::Kind::kGateway) {
    const StackEntry* e = stack_.entry(goal_->entry_id);
    if (reached) {
      if (e && e->state != StackEntry::State::kDone) stack_.done(goal_->entry_id, reason);
    } else {
      const PlaceView view = e && map_ ? view_of_place(*map_, e->crossing, options_.changed) : PlaceView{};
      const int64_t wait = behind_closed && e ? closed_retry_wait_us(e->closed_failures + 1) : retry_after_us;
      stack_.failed(goal_->entry_id, reason, utime, utime + wait, options_.max_attempts,
                    static_cast<int64_t>(map_ ? map_->regions().size() : 0), view, counts,
                    behind_closed ? options_.max_closed_retries : 0, now);
    }
  } else if (reached) {
    visited_.push_back(goal_->frontier_point);
  } else {
    if (behind_closed) {
      ++place->closed_failures;
      place->retry_utime = utime + closed_retry_wait_us(place->closed_failures);
      if (place->closed_failures >= options_.max_closed_retries) place->attempts = std::max(place->attempts, options_.max_attempts);
    } else {
      if (counts) ++place->attempts;
      place->retry_utime = utime + retry_after_us;
    }
    place->failed_utime = utime;
    place->failed_from = now;
    if (map_) place->view_at_failure = view_of_place(*map_, place->map_point, options_.changed);
  }
  goal_.reset();
  decide_now_ = true;
}

int64_t Explorer::closed_retry_wait_us(int k) const
{
  // Capped at a day: a wait past any run, and no overflow.
  return static_cast<int64_t>(std::min(86400.0, options_.retry_after_s * std::pow(2.0, std::max(0, k - 1))) * 1e6);
}

Explorer::Recovery Explorer::recovery_from(const Vector2d& here) const
{
  const auto new_place = [&](const std::optional<Vector2d>& p) { return !p || (here - *p).norm() >= kMovedSinceFailure; };
  return new_place(looked_at_) ? Recovery::kLook : new_place(stepped_from_) ? Recovery::kStep : Recovery::kNone;
}

std::optional<ExploreGoal> Explorer::recovery_goal() const
{
  const int64_t cur = map_->resolve(map_->current_region);
  const rgmap::Region* r = map_->region(cur);
  if (!r) return std::nullopt;
  const geometry::Pose2 region_from_base = r->map_from_region.inverse() * pose_->map_from_base;
  const Vector2d robot = pose_->map_from_base.translation();
  ExploreGoal g;
  g.region_id = cur;
  if (recovery_due_ == Recovery::kLook) {
    // Face away from where the robot looked: the laser sees the half ahead of it.
    g.kind = ExploreGoal::Kind::kLook;
    g.region_point = region_from_base.translation();
    g.map_point = robot;
    g.heading = geometry::normalize_angle(region_from_base.theta() + M_PI);
    g.heading_tolerance = options_.recovery.heading_tolerance;
    g.tolerance = options_.goal_tolerance;
    g.frontier_point = g.map_point;
    return g;
  }
  // Back along the way it came: its body was there, so the place is free and joins where it came from.
  for (auto it = track_.rbegin(); it != track_.rend(); ++it) {
    if ((*it - robot).norm() < options_.recovery.step_m) continue;
    g.kind = ExploreGoal::Kind::kStep;
    g.map_point = *it;
    g.region_point = r->map_from_region.inverse() * *it;
    const Vector2d d = g.region_point - region_from_base.translation();
    g.heading = std::atan2(d.y(), d.x());
    g.tolerance = 0.5 * options_.recovery.step_m;
    g.frontier_point = g.map_point;
    return g;
  }
  return std::nullopt;
}

bool Explorer::waiting_to_retry(int64_t utime) const
{
  for (const auto& e : stack_.entries())
    if (e.state == StackEntry::State::kSetAside && e.retry_utime > 0) return true;
  return std::any_of(failed_.begin(), failed_.end(), [&](const FailedPlace& f) {
    return f.attempts < options_.max_attempts && utime < f.retry_utime;
  });
}

void Explorer::release_changed(int64_t utime)
{
  const auto min_age = static_cast<int64_t>(options_.retry_after_s * 1e6);
  stack_.release_changed(*map_, options_.changed, utime, min_age, options_.max_attempts);
  for (auto& f : failed_) {
    if (f.attempts < options_.max_attempts || utime - f.failed_utime < min_age) continue;
    if (!place_changed(f.view_at_failure, view_of_place(*map_, f.map_point, options_.changed), options_.changed))
      continue;
    f.attempts = options_.max_attempts - 1;
    f.retry_utime = utime;
  }
}

Command Explorer::step(int64_t utime)
{
  Command cmd;
  if (phase_ == Phase::kDone) return cmd;
  if (!map_ || !pose_ || map_->current_region == 0 || !map_->region(map_->resolve(map_->current_region))) {
    activity_ = "waiting for the RG map and the robot's pose";
    return cmd;
  }
  phase_ = Phase::kExploring;
  const int64_t cur = map_->resolve(map_->current_region);
  if (start_region_ == 0) {
    start_region_ = cur;
    // What the robot saw so far lies ahead of it: it looks behind before it chooses.
    if (options_.recovery.look_at_start) recovery_due_ = Recovery::kLook;
  }
  const Vector2d robot = pose_->map_from_base.translation();
  stack_.update(robot, *map_);

  // A region left with no frontier open is finished (and can be named).
  if (last_region_ != 0 && map_->resolve(last_region_) != cur) {
    const int64_t left = map_->resolve(last_region_);
    if (map_->region(left) && open_frontiers(left).empty()) finished_regions_.insert(left);
  }
  last_region_ = cur;

  if (goal_ && is_recovery(*goal_)) {
    // A look ends when the planner says the heading is reached (the robot stands at its goal
    // from the start); a step when the robot is there.
    if (goal_->kind == ExploreGoal::Kind::kStep && (robot - goal_->map_point).norm() <= goal_->tolerance)
      end_goal(true, "reached", utime);
    else if (utime - goal_sent_utime_ > static_cast<int64_t>(options_.recovery.timeout_s * 1e6))
      end_goal(false, kTimedOut, utime);
  } else if (goal_) {
    const double d = (robot - goal_->map_point).norm();
    if (d < goal_best_distance_ - options_.progress_m) {
      goal_best_distance_ = d;
      goal_progress_utime_ = utime;
    }
    if (!goal_still_open()) end_goal(true, goal_->kind == ExploreGoal::Kind::kGateway ? "gone through" : kExplored, utime);
    else if (d <= goal_->tolerance) end_goal(true, "reached", utime);
    else if (utime - goal_sent_utime_ > static_cast<int64_t>(options_.goal_timeout_s * 1e6)) end_goal(false, kTimedOut, utime);
    else if (utime - goal_progress_utime_ > static_cast<int64_t>(options_.progress_timeout_s * 1e6))
      end_goal(false, kNoProgress, utime);
  }
  if (!decide_now_ && utime - last_decision_utime_ < static_cast<int64_t>(options_.decide_period_s * 1e6)) return cmd;
  last_decision_utime_ = utime;
  decide_now_ = false;

  if (recovery_due_ != Recovery::kNone && !goal_) {
    std::optional<ExploreGoal> g = recovery_goal();
    // Tried from here, whether or not there was a way to try it (no track to step back along).
    (recovery_due_ == Recovery::kLook ? looked_at_ : stepped_from_) = robot;
    recovery_due_ = Recovery::kNone;
    if (g) {
      start_goal(&*g, utime);
      activity_ = fmt::format("goal {}: {} to change the view", g->goal_id,
                              g->kind == ExploreGoal::Kind::kLook ? "looking behind" : "a step back along the track");
      cmd.goal = g;
      return cmd;
    }
  }

  release_changed(utime);
  set_aside_closed_entries(utime);
  std::optional<ExploreGoal> next = choose(utime);
  if (goal_) {
    // A gateway goal runs until it ends; a frontier goal gives way to a better choice: a region
    // that became current, or a frontier much nearer than the one driven to (another region's
    // only so: the current region changes back and forth in a doorway); never to the stack's next
    // gateway (a frontier tried again while nothing on the stack was due was dropped half-way
    // whenever an entry came due, and tried again after it, over and over).
    if (goal_->kind == ExploreGoal::Kind::kGateway || is_recovery(*goal_) || !next) return cmd;
    if (next->kind == ExploreGoal::Kind::kGateway) return cmd;
    if ((next->frontier_point - goal_->frontier_point).norm() < kSamePlace) return cmd;
    if ((next->region_id == goal_->region_id && next->kind == goal_->kind) || next->kind == ExploreGoal::Kind::kRegion) {
      const double dn = (next->map_point - robot).norm(), dc = (goal_->map_point - robot).norm();
      if (dn > (1.0 - options_.switch_gain) * dc) return cmd;
    }
  }
  if (!next) {
    if (waiting_to_retry(utime)) {
      // Everything left failed from here: the place may be what is wrong (a scrap of free space
      // that joins no way on, as for "start cut off"), and standing there nothing changes. The
      // robot looks behind, then steps back along its track, before it waits.
      const bool failed_here = last_failure_ && (robot - last_failure_->robot).norm() < kMovedSinceFailure;
      if (failed_here) {
        recovery_due_ = recovery_from(robot);
        if (recovery_due_ != Recovery::kNone) {
          decide_now_ = true;
          activity_ = "nothing reachable from here: changing the view";
          return cmd;
        }
      }
      activity_ = "waiting to try again what could not be reached";
      return cmd;
    }
    phase_ = Phase::kDone;
    activity_ = fmt::format("done: {} regions, {} gateways gone through, {} set aside", map_->regions().size(),
                            stack_.count(StackEntry::State::kDone), stack_.count(StackEntry::State::kSetAside));
    for (const auto& [id, r] : map_->regions())
      if (r.state != rgmap::Region::State::kMerged) finished_regions_.insert(id);
    return cmd;
  }
  start_goal(&*next, utime);
  const char* kind = next->kind == ExploreGoal::Kind::kGateway  ? "through a gateway"
                     : next->kind == ExploreGoal::Kind::kRegion ? "back to a frontier of"
                                                                : "to a frontier of";
  activity_ = fmt::format("goal {}: {} region {} at ({:.2f}, {:.2f})", next->goal_id, kind, next->region_id,
                          next->map_point.x(), next->map_point.y());
  cmd.goal = next;
  return cmd;
}

void Explorer::start_goal(ExploreGoal* g, int64_t utime)
{
  g->goal_id = next_goal_id_++;
  goal_ = *g;
  goal_sent_utime_ = utime;
  goal_best_distance_ = (pose_->map_from_base.translation() - g->map_point).norm();
  goal_progress_utime_ = utime;
  ++goals_sent_;
}

ExplorerStatus Explorer::status() const
{
  ExplorerStatus s;
  s.phase = phase_;
  s.activity = activity_;
  s.goal = goal_;
  s.goals_sent = goals_sent_;
  s.goals_reached = goals_reached_;
  s.goals_failed = goals_failed_;
  s.stack_pending = stack_.count(StackEntry::State::kPending);
  s.stack_done = stack_.count(StackEntry::State::kDone);
  s.stack_set_aside = stack_.count(StackEntry::State::kSetAside);
  if (!map_) return s;
  s.current_region = map_->current_region ? map_->resolve(map_->current_region) : 0;
  for (const auto& [id, r] : map_->regions()) {
    if (r.state == rgmap::Region::State::kMerged) continue;
    ++s.regions;
    if (open_frontiers(id).empty()) ++s.complete_regions;
  }
  if (s.current_region) s.current_completeness = find_frontiers(*map_, s.current_region, options_.frontier).completeness();
  return s;
}

std::vector<int64_t> Explorer::take_finished_regions()
{
  std::vector<int64_t> out;
  for (const int64_t id : finished_regions_)
    if (offered_regions_.insert(id).second) out.push_back(id);
  return out;
}

nlohmann::json Explorer::save() const
{
  nlohmann::json visited = nlohmann::json::array(), failed = nlohmann::json::array();
  for (const auto& v : visited_) visited.push_back(point_json(v));
  for (const auto& f : failed_) {
    failed.push_back({{"at", point_json(f.map_point)},
                      {"retry_utime", f.retry_utime},
                      {"attempts", f.attempts},
                      {"closed_failures", f.closed_failures},
                      {"failed_utime", f.failed_utime},
                      {"view_at_failure", place_view_json(f.view_at_failure)}});
    if (f.failed_from) failed.back()["failed_from"] = last_failure_json(*f.failed_from);
  }
  return {{"phase", to_string(phase_)},
          {"start_region", start_region_},
          {"next_goal_id", next_goal_id_},
          {"stack", stack_.to_json()},
          {"visited", visited},
          {"failed", failed},
          {"offered_regions", offered_regions_},
          {"goals", {goals_sent_, goals_reached_, goals_failed_}}};
}

void Explorer::restore(const nlohmann::json& j)
{
  const std::string phase = j.at("phase").get<std::string>();
  Phase p = Phase::kWaiting;
  if (phase == "exploring") p = Phase::kExploring;
  else if (phase == "done") p = Phase::kDone;
  else if (phase != "waiting") throw std::invalid_argument("phase '" + phase + "' is not waiting, exploring or done");
  const int64_t next_goal_id = j.at("next_goal_id").get<int64_t>();
  if (next_goal_id < 1) throw std::invalid_argument("next_goal_id < 1");
  GatewayStack stack(options_.stack);
  stack.from_json(j.at("stack"));
  std::vector<Vector2d> visited;
  for (const auto& v : j.at("visited")) visited.push_back(point_from(v));
  std::vector<FailedPlace> failed;
  for (const auto& f : j.at("failed")) {
    FailedPlace place;
    place.map_point = point_from(f.at("at"));
    place.retry_utime = f.at("retry_utime").get<int64_t>();
    place.attempts = f.at("attempts").get<int>();
    // Absent in state files written before closed-gateway failures were bounded.
    place.closed_failures = f.value("closed_failures", 0);
    // Absent in state files written before places were tried again when the map near them changed.
    place.failed_utime = f.value("failed_utime", int64_t{0});
    if (f.contains("view_at_failure")) place.view_at_failure = place_view_from_json(f.at("view_at_failure"));
    // Absent in state files written before a failure was judged per goal.
    if (f.contains("failed_from")) place.failed_from = last_failure_from_json(f.at("failed_from"));
    failed.push_back(place);
  }
  const auto offered = j.at("offered_regions").get<std::set<int64_t>>();
  const auto goals = j.at("goals").get<std::vector<int>>();
  if (goals.size() != 3) throw std::invalid_argument("goals is not [sent, reached, failed]");

  phase_ = p;
  start_region_ = j.at("start_region").get<int64_t>();
  next_goal_id_ = next_goal_id;
  stack_ = std::move(stack);
  visited_ = std::move(visited);
  failed_ = std::move(failed);
  offered_regions_ = offered;
  finished_regions_ = offered;
  goals_sent_ = goals[0];
  goals_reached_ = goals[1];
  goals_failed_ = goals[2];
  // The goal that ran before the restart is chosen anew (the planner replaces it by the new id).
  goal_.reset();
  decide_now_ = true;
}

}  // namespace rgnav::explorer
