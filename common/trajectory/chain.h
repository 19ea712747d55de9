// A chain of primitives driven one after the other. Positions along the chain are measured
// by the arc length s from its start; turns in place occupy no length (they sit at the s
// where they happen), so a few helpers take a segment index as well.
#pragma once

#include <vector>

#include "trajectory/segment.h"

namespace rgnav::trajectory {

class Chain
{
 public:
  Chain() = default;
  explicit Chain(std::vector<Segment> segments);

  // Appends a segment; it should start where the chain ends (see continuity()).
  void push_back(const Segment& seg);
  // Appends seg re-anchored at the current end pose (shape kept, start pose replaced).
  void append_at_end(const Segment& seg);

  const std::vector<Segment>& segments() const { return segments_; }
  size_t size() const { return segments_.size(); }
  bool empty() const { return segments_.empty(); }
  const Segment& operator[](size_t i) const { return segments_[i]; }
  // Arc length at the start of segment i.
  double start_s(size_t i) const { return start_s_[i]; }
  double length() const { return length_; }
  Pose2 start() const { return segments_.front().start(); }
  Pose2 end() const { return segments_.back().end(); }

  // The segment containing s (for an s on a joint: the later one, skipping turns at s).
  size_t segment_at(double s) const;
  Pose2 pose_at(double s) const;
  double curvature_at(double s) const;

  // Largest position [m] and heading [rad] mismatch between the end of a segment and the
  // start of the next.
  struct Continuity
  {
    double position = 0.0;
    double heading = 0.0;
    double curvature = 0.0;  // largest curvature jump at a joint (0 for G2 chains)
  };
  Continuity continuity() const;

  // Closest point to p with s in [s_lo, s_hi] (chain arc length).
  struct ChainProjection
  {
    size_t segment = 0;
    double s = 0.0;          // chain arc length
    Projection local;        // in the segment (local.s is the segment's own arc length)
  };
  ChainProjection project(const Eigen::Vector2d& p, double s_lo, double s_hi) const;

 private:
  std::vector<Segment> segments_;
  std::vector<double> start_s_;
  double length_ = 0.0;
};

// The same segment shape starting at another pose.
Segment reanchor(const Segment& seg, const Pose2& start);

}  // namespace rgnav::trajectory
