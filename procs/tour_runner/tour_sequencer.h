// Walks a list of targets: the current target advances when the robot comes within
// reach_radius of it; the next few targets are what collision avoidance (or the simple
// follower) steers toward. Knows nothing of LCM or frames: targets and poses share a frame.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::tour_runner {

struct SequencerOptions
{
  double reach_radius = 0.35;   // [m] a target counts as reached within this distance
  int lookahead = 3;            // targets handed on at once
};

class TourSequencer
{
 public:
  TourSequencer(SequencerOptions options, std::vector<Eigen::Vector2d> targets);

  // Advances past every target reached from `pose`; returns true if the index moved.
  bool update(const geometry::Pose2& pose);
  // The next `lookahead` targets (fewer near the end; empty when done).
  std::vector<Eigen::Vector2d> upcoming() const;
  bool done() const { return next_ >= targets_.size(); }
  size_t reached() const { return next_; }
  size_t size() const { return targets_.size(); }
  // Names the goal the upcoming targets serve (target_list_t.goal_id): the 1-based index of the
  // target being driven to. Re-sent lists for the same target carry the same id, so collision
  // avoidance can tell a new goal from the same targets re-expressed.
  int64_t goal_id() const { return static_cast<int64_t>(next_) + 1; }

 private:
  const SequencerOptions options_;
  std::vector<Eigen::Vector2d> targets_;
  size_t next_ = 0;
};

}  // namespace rgnav::tour_runner
