// The way the robot came, as a way out. Its recent positions (odom frame) with the clearance
// the local map showed at each while it drove there. A robot that got into a dead end with
// less than the full clearance (the reactive fallback steers with half the safety margin, a
// squeeze keeps less too) cannot leave by the rules that keep it out of such places: every
// chain, detour and back-off must keep the full clearance, or gain 0.5 m of it per metre
// driven, and the way it came in keeps neither; it turned on the spot for good. The way back
// along its own track needs only the clearance the robot had there, a body's width it drove
// through moments ago; what the map shows there now decides (something that appeared since
// closes it). The track is in the odometry frame: minutes of turning on the spot bend the
// odometry and the map turns against the track, so it serves soon after the robot got stuck.
#pragma once

#include <Eigen/Core>

#include <deque>
#include <optional>
#include <vector>

#include "collision_avoidance/local_map.h"

namespace rgnav::collision_avoidance {

struct OwnTrackOptions
{
  double spacing = 0.05;      // [m] one track point per this much driven
  double max_length = 6.0;    // [m] track kept
  double tolerance = 0.03;    // [m] the way back may pass this much closer than the robot did (scan noise)
  double min_clearance = 0.02;  // [m] beyond the robot's radius, always
  double beyond = 0.3;        // [m] the way back ends this far past its first point with the full clearance
  double min_length = 0.2;    // [m] shorter ways back are no way out
  double max_back = 3.0;      // [m] never farther back than this
};

struct TrackPoint
{
  Eigen::Vector2d at = Eigen::Vector2d::Zero();  // odom frame
  double clearance = 0.0;  // [m] the least the map showed here while the robot was here (up to the full clearance)
};

class OwnTrack
{
 public:
  explicit OwnTrack(const OwnTrackOptions& options) : options_(options) {}

  // The robot is at `at`, the map showing `clearance` there (searched up to the full clearance).
  // A jump farther than a few spacings (odometry reset, a new start) begins a new track.
  void add(const Eigen::Vector2d& at, double clearance);
  void clear() { points_.clear(); }
  // Keeps the oldest n points: the robot drives back over the rest (a way back is no way in).
  void keep_oldest(size_t n)
  {
    if (n < points_.size()) points_.resize(n);
  }
  const std::deque<TrackPoint>& points() const { return points_; }

 private:
  OwnTrackOptions options_;
  std::deque<TrackPoint> points_;  // oldest first
};

struct WayBack
{
  std::vector<Eigen::Vector2d> corners;  // odom frame, nearest first; the last is where it ends
  std::vector<Eigen::Vector2d> points;   // the track points it follows, nearest first ...
  std::vector<double> needs;             // ... and the clearance each needs [m]
  size_t track_index = 0;                // ... which is this point of the track
  double length = 0.0;                   // [m] along the track
};

// The way back from `here` along the track, as corners of a polyline that stays within a few centimetres of the track. Every point of it keeps what the
// robot had there, less the tolerance (at least robot_radius + min_clearance, at most
// `clearance`), on the map as it is now (the straight legs at least robot_radius +
// min_clearance). It leads out of what is tight now: it ends `beyond` past the first track
// point with the full clearance on the map now after the last point without it, or after
// max_back. Nothing: the robot is not on its track, nothing on the way back within max_back is
// tight (the ordinary rules lead out), or the way back is blocked (or the track ends) before
// its end.
std::optional<WayBack> way_back(const OwnTrack& track, const LocalMap& map,
                              const Eigen::Vector2d& here, double robot_radius, double clearance,
                              const OwnTrackOptions& options);

}  // namespace rgnav::collision_avoidance
