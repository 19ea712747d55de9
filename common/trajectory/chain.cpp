#include "trajectory/chain.h"

#include <algorithm>
#include <cmath>

namespace rgnav::trajectory {

Chain::Chain(std::vector<Segment> segments)
{
  segments_.reserve(segments.size());
  for (const auto& s : segments) push_back(s);
}

void Chain::push_back(const Segment& seg)
{
  start_s_.push_back(length_);
  segments_.push_back(seg);
  length_ += seg.length();
}

Segment reanchor(const Segment& seg, const Pose2& start)
{
  Segment out = seg;
  switch (seg.kind()) {
    case Kind::kLine: out = Segment::line(start, seg.length()); break;
    case Kind::kArc: out = Segment::arc(start, seg.kappa0(), seg.length()); break;
    case Kind::kClothoid: out = Segment::clothoid(start, seg.kappa0(), seg.kappa1(), seg.length()); break;
    case Kind::kConic:
      out = Segment::conic(start, seg.semi_a(), seg.semi_b(), seg.ellipse_t0(), seg.kappa0() >= 0, seg.length());
      break;
    case Kind::kTurn: out = Segment::turn(start, seg.turn_angle()); break;
  }
  out.set_v_max(seg.v_max());
  return out;
}

void Chain::append_at_end(const Segment& seg) { push_back(empty() ? seg : reanchor(seg, end())); }

size_t Chain::segment_at(double s) const
{
  if (segments_.empty()) return 0;
  // Last segment whose start is <= s, then skip back over nothing: a zero-length segment at
  // s is passed (we are after it) unless it is the last one.
  auto it = std::upper_bound(start_s_.begin(), start_s_.end(), s);
  size_t i = it == start_s_.begin() ? 0 : static_cast<size_t>(it - start_s_.begin()) - 1;
  return i;
}

Pose2 Chain::pose_at(double s) const
{
  const size_t i = segment_at(s);
  const Segment& seg = segments_[i];
  return seg.kind() == Kind::kTurn ? seg.end() : seg.pose_at(s - start_s_[i]);
}

double Chain::curvature_at(double s) const
{
  const size_t i = segment_at(s);
  return segments_[i].curvature_at(s - start_s_[i]);
}

Chain::Continuity Chain::continuity() const
{
  Continuity c;
  for (size_t i = 1; i < segments_.size(); ++i) {
    const Pose2 e = segments_[i - 1].end(), s = segments_[i].start();
    c.position = std::max(c.position, (e.translation() - s.translation()).norm());
    c.heading = std::max(c.heading, std::fabs(geometry::normalize_angle(e.theta() - s.theta())));
    if (segments_[i - 1].kind() != Kind::kTurn && segments_[i].kind() != Kind::kTurn)
      c.curvature = std::max(c.curvature, std::fabs(segments_[i - 1].curvature_at(segments_[i - 1].length()) -
                                                    segments_[i].curvature_at(0.0)));
  }
  return c;
}

Chain::ChainProjection Chain::project(const Eigen::Vector2d& p, double s_lo, double s_hi) const
{
  ChainProjection best;
  for (size_t i = 0; i < segments_.size(); ++i) {
    const double a = start_s_[i], b = a + segments_[i].length();
    if (b < s_lo || a > s_hi) continue;
    if (segments_[i].kind() == Kind::kTurn) continue;
    const Projection pr = trajectory::project(segments_[i], p, s_lo - a, s_hi - a);
    if (pr.distance < best.local.distance) {
      best.segment = i;
      best.s = a + pr.s;
      best.local = pr;
    }
  }
  if (!std::isfinite(best.local.distance) && !segments_.empty()) {
    // Only turns in the window: the turn's position.
    const size_t i = segment_at(std::clamp(s_lo, 0.0, length_));
    best.segment = i;
    best.s = start_s_[i];
    best.local = trajectory::project(segments_[i], p, 0, 0);
  }
  return best;
}

}  // namespace rgnav::trajectory
