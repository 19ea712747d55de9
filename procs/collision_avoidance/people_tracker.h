// Tracks what moves in the laser's view (people walking) and predicts where it will be:
// the possibly moving points of each scan (local_map.h: cells hit for less than
// static_after) are clustered, clusters are associated with the tracks of the previous
// scans by nearest centroid, and each track's velocity is the least-squares slope of its
// centroid over the last `history` seconds. A track moving faster than min_speed predicts
// its points shifted along its velocity over the next `horizon` seconds; the local map
// treats those like obstacles that may move. The planner then neither plans across the
// path a person is about to walk nor stops on it: over the obstacle courses every collision
// was a person walking into a robot that had stopped in that person's way to let them pass.
//
// Not everything young is a mover: a box face the robot turns toward comes into view piece by
// piece, and its centroid "moves" along the face. A mover leaves its place: where it was a
// little earlier, the newest scan now looks through (walked aside) or is blocked short of it
// (walked toward the laser). A face coming into view is still hit where it was first seen;
// such a track predicts nothing. (On the obstacle courses a phantom track of that kind,
// predicted through the robot, kept it backing off between two boxes for a minute.)
#pragma once

#include <Eigen/Core>

#include <deque>
#include <functional>
#include <vector>

#include "time/message_time.h"

namespace rgnav::collision_avoidance {

struct PeopleTrackerOptions
{
  double cluster_distance = 0.30;  // [m] points closer than this belong to one cluster
  int min_points = 3;              // smaller clusters are ignored (noise, edges)
  double gate = 0.6;               // [m] a cluster this close to a track's prediction continues it
  double history = 0.6;            // [s] centroid history for the velocity fit
  double lost_after = 0.4;         // [s] a track not seen this long is dropped
  double min_speed = 0.15;         // [m/s] slower tracks predict nothing
  double max_speed = 2.5;          // [m/s] faster is an association error: no prediction
  double horizon = 1.0;            // [s] predicted this far ahead
  double step = 0.25;              // [s] one predicted copy of the cluster per step
  double max_still_there = 0.6;    // share of a track's oldest points the newest scan may still hit: more is no mover
  double stopped_memory = 20.0;    // [s] where a mover was last seen is kept this long (someone who stopped) ...
  double stopped_min_travel = 0.5; // [m] ... if it got this far from where its track began ...
  double stopped_min_moving = 1.0; // [s] ... and moved (predicted motion) this long: a face coming into view, a wall
                                   // seen piece by piece while the robot drives, moves for a moment
};

// Where a mover was last seen: a person who walked up and stopped (their cells turn static
// and the track ends) stands there, as far as anyone can tell.
struct LastSeenMover
{
  time::Time stamp{};
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // odom frame, the track's last centroid
  // [m/s] the last velocity it predicted with: the way they were walking before they stopped
  // (their velocity fit decays to nothing while they stand, before the track ends).
  Eigen::Vector2d walking = Eigen::Vector2d::Zero();
  double moving_steady = 0.0;  // [s] Track::moving_steady
  Eigen::Vector2d first = Eigen::Vector2d::Zero();  // Track::first: where its track began
};

// What the newest scan says about a place (odom frame): its beams there end at it, short of
// it (something nearer hides it), or beyond it; unknown outside the field of view.
enum class SeenNow
{
  kUnknown,
  kStillThere,
  kHidden,
  kFreeNow,
};
using SeenNowFn = std::function<SeenNow(const Eigen::Vector2d&)>;

struct Track
{
  int id = 0;
  std::deque<std::pair<time::Time, Eigen::Vector2d>> centroids;  // oldest first
  std::deque<std::vector<Eigen::Vector2d>> clusters;             // the clusters of `centroids` (newest last)
  bool left_its_place = true;  // the newest scan no longer sees it where it was (or cannot tell)
  bool moved = false;          // predicted motion at some time ...
  Eigen::Vector2d first = Eigen::Vector2d::Zero();  // ... and got this far from its first centroid:
  double travelled = 0.0;      // [m] a person walking, not a box face coming into view
  double moving_for = 0.0;     // [s] predicted motion this long in all
  // [s] of it while the robot held its heading: a wall coming into view as the robot turns
  // moves too, where the places it was fall out of view (nothing tells that it is still there).
  double moving_steady = 0.0;
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();           // [m/s]
  Eigen::Vector2d walking = Eigen::Vector2d::Zero();            // [m/s] the last velocity it predicted with
  time::Time last_seen{};
};

class PeopleTracker
{
 public:
  explicit PeopleTracker(const PeopleTrackerOptions& options) : options_(options) {}

  // The possibly moving points of one scan (odom frame) at its time; `seen_now` answers for
  // that scan (none: every track counts as having left its place). robot_turning: the robot
  // turned since the scan before.
  void update(time::Time stamp, const std::vector<Eigen::Vector2d>& moving_points, const SeenNowFn& seen_now = {},
              bool robot_turning = false);
  // Points where the tracked movers will be over the horizon (odom frame), from `now`.
  std::vector<Eigen::Vector2d> predicted(time::Time now) const;
  const std::vector<Track>& tracks() const { return tracks_; }
  // Where tracks that had moved ended (newest last), for stopped_memory.
  const std::deque<LastSeenMover>& last_seen_movers() const { return last_seen_; }

 private:
  std::vector<std::vector<Eigen::Vector2d>> clusters(const std::vector<Eigen::Vector2d>& points) const;
  void fit_velocity(Track& t) const;
  bool left_its_place(const Track& t, const SeenNowFn& seen_now) const;

  const PeopleTrackerOptions options_;
  bool predicts(const Track& t) const;

  std::vector<Track> tracks_;
  std::deque<LastSeenMover> last_seen_;
  int next_id_ = 1;
};

}  // namespace rgnav::collision_avoidance
