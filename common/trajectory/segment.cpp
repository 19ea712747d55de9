#include "trajectory/segment.h"

#include <algorithm>
#include <cmath>

#include "trajectory/fresnel.h"
#include "trajectory/gauss_legendre.h"

namespace rgnav::trajectory {

using geometry::normalize_angle;

namespace {

Pose2 advance(const Pose2& start, const Eigen::Vector2d& local, double dtheta)
{
  return Pose2(start.translation() + start.rotation() * local, start.theta() + dtheta);
}

}  // namespace

Segment Segment::line(const Pose2& start, double length)
{
  Segment s;
  s.kind_ = Kind::kLine;
  s.start_ = start;
  s.length_ = std::max(0.0, length);
  return s;
}

Segment Segment::arc(const Pose2& start, double kappa, double length)
{
  Segment s;
  s.kind_ = Kind::kArc;
  s.start_ = start;
  s.length_ = std::max(0.0, length);
  s.kappa0_ = s.kappa1_ = kappa;
  return s;
}

Segment Segment::clothoid(const Pose2& start, double kappa0, double kappa1, double length)
{
  Segment s;
  s.kind_ = Kind::kClothoid;
  s.start_ = start;
  s.length_ = std::max(0.0, length);
  s.kappa0_ = kappa0;
  s.kappa1_ = kappa1;
  return s;
}

Segment Segment::conic(const Pose2& start, double a, double b, double t0, bool ccw, double length)
{
  Segment s;
  s.kind_ = Kind::kConic;
  s.start_ = start;
  s.length_ = std::max(0.0, length);
  s.a_ = std::fabs(a);
  s.b_ = std::fabs(b);
  s.t0_ = t0;
  const double sigma = ccw ? 1.0 : -1.0;
  // Tangent at t0 in the ellipse frame decides how the ellipse is rotated; the start point
  // then places its centre.
  const double phi0 = std::atan2(sigma * s.b_ * std::cos(t0), -sigma * s.a_ * std::sin(t0));
  s.psi_ = start.theta() - phi0;
  const Eigen::Vector2d local(s.a_ * std::cos(t0), s.b_ * std::sin(t0));
  s.center_ = start.translation() - Pose2(0, 0, s.psi_).rotation() * local;
  const double sp0 = s.conic_speed(t0);
  s.kappa0_ = sigma * s.a_ * s.b_ / (sp0 * sp0 * sp0);  // sign carries the direction
  const double t1 = s.conic_param_at(s.length_);
  const double sp1 = s.conic_speed(t1);
  s.kappa1_ = sigma * s.a_ * s.b_ / (sp1 * sp1 * sp1);
  return s;
}

Segment Segment::turn(const Pose2& start, double angle)
{
  Segment s;
  s.kind_ = Kind::kTurn;
  s.start_ = start;
  s.turn_ = angle;
  return s;
}

double Segment::conic_speed(double t) const
{
  const double st = std::sin(t), ct = std::cos(t);
  return std::sqrt(a_ * a_ * st * st + b_ * b_ * ct * ct);
}

Eigen::Vector2d Segment::conic_point(double t) const
{
  return center_ + Pose2(0, 0, psi_).rotation() * Eigen::Vector2d(a_ * std::cos(t), b_ * std::sin(t));
}

double Segment::conic_arc_length(double ta, double tb) const { return ellipse_arc_length(a_, b_, ta, tb); }

double ellipse_arc_length(double a, double b, double ta, double tb)
{
  auto speed = [&](double t) {
    const double st = std::sin(t), ct = std::cos(t);
    return std::sqrt(a * a * st * st + b * b * ct * ct);
  };
  // |tb - ta| in panels of at most 0.25 rad of the parameter; 10-point Gauss-Legendre.
  const double span = tb - ta;
  const int panels = std::max(1, static_cast<int>(std::ceil(std::fabs(span) / 0.25)));
  const double h = span / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double mid = ta + (p + 0.5) * h, half = 0.5 * h;
    for (int i = 0; i < 5; ++i)
      sum += half * kGaussLegendreW[i] * (speed(mid - half * kGaussLegendreX[i]) + speed(mid + half * kGaussLegendreX[i]));
  }
  return std::fabs(sum);
}

double Segment::conic_param_at(double s) const
{
  // Newton on the arc length: ds/dtau = speed; the speed never drops below min(a, b).
  const double sigma = conic_sigma();
  double tau = s / std::max(1e-9, std::max(a_, b_));
  for (int i = 0; i < 30; ++i) {
    const double t = t0_ + sigma * tau;
    const double f = conic_arc_length(t0_, t) - s;
    const double step = f / std::max(1e-12, conic_speed(t));
    tau -= step;
    if (tau < 0) tau = 0;
    if (std::fabs(step) < 1e-13) break;
  }
  return t0_ + sigma * tau;
}

Pose2 Segment::pose_at(double s) const
{
  s = std::clamp(s, 0.0, length_);
  switch (kind_) {
    case Kind::kLine:
      return advance(start_, {s, 0.0}, 0.0);
    case Kind::kArc: {
      const double k = kappa0_, th = k * s;
      if (std::fabs(th) < 1e-9) return advance(start_, {s, 0.5 * k * s * s}, th);
      return advance(start_, {std::sin(th) / k, (1.0 - std::cos(th)) / k}, th);
    }
    case Kind::kClothoid: {
      const double c = length_ > 0 ? (kappa1_ - kappa0_) / length_ : 0.0;
      return advance(start_, clothoid_displacement(kappa0_, c, s), kappa0_ * s + 0.5 * c * s * s);
    }
    case Kind::kConic: {
      const double t = conic_param_at(s), sigma = conic_sigma();
      const double heading = psi_ + std::atan2(sigma * b_ * std::cos(t), -sigma * a_ * std::sin(t));
      // The heading is continuous along the arc; unwrap it relative to the start.
      const double dth = normalize_angle(heading - start_.theta());
      return Pose2(conic_point(t), start_.theta() + dth);
    }
    case Kind::kTurn:
      return start_;
  }
  return start_;
}

double Segment::curvature_at(double s) const
{
  s = std::clamp(s, 0.0, length_);
  switch (kind_) {
    case Kind::kLine:
    case Kind::kTurn:
      return 0.0;
    case Kind::kArc:
      return kappa0_;
    case Kind::kClothoid:
      return length_ > 0 ? kappa0_ + (kappa1_ - kappa0_) * s / length_ : kappa0_;
    case Kind::kConic: {
      const double sp = conic_speed(conic_param_at(s));
      return conic_sigma() * a_ * b_ / (sp * sp * sp);
    }
  }
  return 0.0;
}

double Segment::sharpness_at(double s) const
{
  switch (kind_) {
    case Kind::kClothoid:
      return length_ > 0 ? (kappa1_ - kappa0_) / length_ : 0.0;
    case Kind::kConic: {
      const double h = std::min(1e-3, 0.5 * length_);
      if (h <= 0) return 0.0;
      const double lo = std::max(0.0, s - h), hi = std::min(length_, s + h);
      return (curvature_at(hi) - curvature_at(lo)) / (hi - lo);
    }
    default:
      return 0.0;
  }
}

Pose2 Segment::end() const
{
  if (kind_ == Kind::kTurn) return Pose2(start_.translation(), start_.theta() + turn_);
  return pose_at(length_);
}

double Segment::heading_change() const
{
  switch (kind_) {
    case Kind::kLine:
      return 0.0;
    case Kind::kArc:
      return kappa0_ * length_;
    case Kind::kClothoid:
      return 0.5 * (kappa0_ + kappa1_) * length_;
    case Kind::kConic: {
      // Integral of the curvature = change of the tangent angle of the ellipse.
      const double t1 = conic_param_at(length_), sigma = conic_sigma();
      auto tangent_angle = [&](double t) {
        // Unwrapped tangent angle of (-a sin t, b cos t) as a function of t.
        return std::atan2(b_ * std::cos(t), -a_ * std::sin(t));
      };
      // The tangent angle increases monotonically with t; count the wraps.
      double total = 0.0;
      const int steps = std::max(1, static_cast<int>(std::ceil(std::fabs(t1 - t0_) / 0.5)));
      double prev = tangent_angle(t0_);
      for (int i = 1; i <= steps; ++i) {
        const double cur = tangent_angle(t0_ + (t1 - t0_) * i / steps);
        total += normalize_angle(cur - prev);
        prev = cur;
      }
      (void)sigma;
      return total;
    }
    case Kind::kTurn:
      return turn_;
  }
  return 0.0;
}

Projection project(const Segment& seg, const Eigen::Vector2d& p, double s_lo, double s_hi)
{
  const double len = seg.length();
  s_lo = std::clamp(s_lo, 0.0, len);
  s_hi = std::clamp(s_hi, s_lo, len);
  auto evaluate = [&](double s) {
    Projection r;
    r.s = s;
    r.pose = seg.pose_at(s);
    const Eigen::Vector2d d = p - r.pose.translation();
    r.distance = d.norm();
    r.lateral = -std::sin(r.pose.theta()) * d.x() + std::cos(r.pose.theta()) * d.y();
    return r;
  };
  if (seg.kind() == Kind::kTurn || len <= 0) return evaluate(0.0);
  if (seg.kind() == Kind::kLine) {
    const Eigen::Vector2d dir(std::cos(seg.start().theta()), std::sin(seg.start().theta()));
    return evaluate(std::clamp((p - seg.start().translation()).dot(dir), s_lo, s_hi));
  }
  if (seg.kind() == Kind::kArc && std::fabs(seg.kappa0()) > 1e-9) {
    // Closest point on the circle: the angle of p around the centre, unwrapped from the start.
    const double k = seg.kappa0(), r = 1.0 / k;
    const Pose2& st = seg.start();
    const Eigen::Vector2d c = st.translation() + r * Eigen::Vector2d(-std::sin(st.theta()), std::cos(st.theta()));
    const Eigen::Vector2d a0 = st.translation() - c, ap = p - c;
    double ang = std::atan2(a0.x() * ap.y() - a0.y() * ap.x(), a0.dot(ap));  // CCW from start
    if (k < 0) ang = -ang;
    if (ang < 0) ang += 2.0 * M_PI;
    double s = ang / std::fabs(k);
    // Past the end of the arc: whichever end is closer.
    if (s > s_hi || s < s_lo) {
      const Projection lo = evaluate(s_lo), hi = evaluate(s_hi);
      return lo.distance <= hi.distance ? lo : hi;
    }
    return evaluate(s);
  }
  // General: coarse sampling, then Newton on (p - c(s)) . t(s) = 0.
  const int n = std::clamp(static_cast<int>(std::ceil((s_hi - s_lo) / 0.05)), 1, 400);
  Projection best = evaluate(s_lo);
  for (int i = 1; i <= n; ++i) {
    const Projection c = evaluate(s_lo + (s_hi - s_lo) * i / n);
    if (c.distance < best.distance) best = c;
  }
  double s = best.s;
  for (int it = 0; it < 8; ++it) {
    const Pose2 q = seg.pose_at(s);
    const Eigen::Vector2d t(std::cos(q.theta()), std::sin(q.theta())), nrm(-t.y(), t.x());
    const Eigen::Vector2d d = p - q.translation();
    const double f = d.dot(t);
    const double df = -1.0 + seg.curvature_at(s) * d.dot(nrm);
    if (std::fabs(df) < 1e-9) break;
    const double next = std::clamp(s - f / df, s_lo, s_hi);
    if (std::fabs(next - s) < 1e-10) {
      s = next;
      break;
    }
    s = next;
  }
  const Projection refined = evaluate(s);
  return refined.distance <= best.distance ? refined : best;
}

}  // namespace rgnav::trajectory
