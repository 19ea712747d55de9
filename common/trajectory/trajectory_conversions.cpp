#include "trajectory/trajectory_conversions.h"

#include <cmath>

#include "msg/conversions.h"

namespace rgnav::trajectory {

namespace {

constexpr double kMaxSegmentLength = 100.0;  // [m] no local trajectory is longer
constexpr int kMaxSegments = 256;

bool fail(std::string* why, const std::string& what)
{
  if (why) *why = what;
  return false;
}

}  // namespace

trajectory_segment_t to_msg(const Segment& seg, double v_end, double v_max_default)
{
  trajectory_segment_t m;
  m.kind = static_cast<int8_t>(seg.kind());
  m.start = msg::to_msg(seg.start());
  m.length = seg.length();
  m.kappa0 = seg.kappa0();
  m.kappa1 = seg.kappa1();
  m.param[0] = m.param[1] = m.param[2] = 0.0;
  if (seg.kind() == Kind::kConic) {
    m.param[0] = seg.semi_a();
    m.param[1] = seg.semi_b();
    m.param[2] = seg.ellipse_t0();
  } else if (seg.kind() == Kind::kTurn) {
    m.param[0] = seg.turn_angle();
  }
  m.v_max = std::isfinite(seg.v_max()) ? seg.v_max() : v_max_default;
  m.v_end = v_end;
  return m;
}

std::optional<Segment> from_msg(const trajectory_segment_t& m, std::string* why)
{
  if (!(m.length >= 0 && m.length <= kMaxSegmentLength)) {
    fail(why, "segment length outside [0, 100] m");
    return std::nullopt;
  }
  const Pose2 start = msg::to_pose2(m.start);
  std::optional<Segment> seg;
  switch (m.kind) {
    case trajectory_segment_t::KIND_LINE: seg = Segment::line(start, m.length); break;
    case trajectory_segment_t::KIND_ARC: seg = Segment::arc(start, m.kappa0, m.length); break;
    case trajectory_segment_t::KIND_CLOTHOID: seg = Segment::clothoid(start, m.kappa0, m.kappa1, m.length); break;
    case trajectory_segment_t::KIND_CONIC:
      if (!(m.param[0] > 0 && m.param[1] > 0) || std::fabs(m.param[2]) > 8.0) {
        fail(why, "conic segment needs semi-axes > 0 and a start angle in [-8, 8] rad");
        return std::nullopt;
      }
      seg = Segment::conic(start, m.param[0], m.param[1], m.param[2], m.kappa0 >= 0, m.length);
      break;
    case trajectory_segment_t::KIND_TURN:
      if (std::fabs(m.param[0]) > 4.0 * M_PI) {
        fail(why, "turn by more than two revolutions");
        return std::nullopt;
      }
      seg = Segment::turn(start, m.param[0]);
      break;
    default:
      fail(why, "unknown segment kind " + std::to_string(m.kind));
      return std::nullopt;
  }
  seg->set_v_max(m.v_max);
  return seg;
}

trajectory_t to_msg(const Trajectory& t, const VelocityProfile* profile, double v_max_default)
{
  trajectory_t m;
  m.utime = time::to_utime(t.stamp);
  m.trajectory_id = t.id;
  m.frame = trajectory_t::FRAME_ODOM;
  m.nsegments = static_cast<int32_t>(t.chain.size());
  m.segments.reserve(t.chain.size());
  for (size_t i = 0; i < t.chain.size(); ++i)
    m.segments.push_back(to_msg(t.chain[i], profile ? profile->segment_end_speed(i) : 0.0, v_max_default));
  m.a_max = t.a_max;
  m.omega_max = t.omega_max;
  m.predicted_end_utime = time::to_utime(t.predicted_end);
  m.stop_at_end = t.stop_at_end;
  return m;
}

std::optional<Trajectory> from_msg(const trajectory_t& m, std::string* why)
{
  if (m.frame != trajectory_t::FRAME_ODOM) {
    fail(why, "trajectory frame must be FRAME_ODOM");
    return std::nullopt;
  }
  if (m.nsegments > kMaxSegments) {
    fail(why, "more than 256 segments");
    return std::nullopt;
  }
  Trajectory t;
  t.id = m.trajectory_id;
  t.stamp = time::from_utime(m.utime);
  t.a_max = m.a_max;
  t.omega_max = m.omega_max;
  t.stop_at_end = m.stop_at_end;
  t.predicted_end = time::from_utime(m.predicted_end_utime);
  for (const auto& sm : m.segments) {
    auto seg = from_msg(sm, why);
    if (!seg) return std::nullopt;
    t.chain.push_back(*seg);
  }
  return t;
}

}  // namespace rgnav::trajectory
