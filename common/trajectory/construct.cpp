#include "trajectory/construct.h"

#include "trajectory/fresnel.h"

#include <array>
#include <cmath>

namespace rgnav::trajectory {

using geometry::normalize_angle;

namespace {

// Where the two heading lines meet, as distances along each: start + d1 * dir0 = end - d2 * dir1.
bool corner(const Pose2& start, const Pose2& end, double* d1, double* d2)
{
  const Eigen::Vector2d u(std::cos(start.theta()), std::sin(start.theta()));
  const Eigen::Vector2d w(std::cos(end.theta()), std::sin(end.theta()));
  const Eigen::Vector2d r = end.translation() - start.translation();
  const double det = u.x() * w.y() - u.y() * w.x();  // sin(dtheta)
  if (std::fabs(det) < 1e-9) return false;
  // d1 u + d2 w = r
  *d1 = (r.x() * w.y() - r.y() * w.x()) / det;
  *d2 = (u.x() * r.y() - u.y() * r.x()) / det;
  return true;
}

// A chain that is a straight line, if end lies straight ahead of start with the same heading.
std::optional<Chain> straight(const Pose2& start, const Pose2& end)
{
  const Pose2 rel = start.between(end);
  if (std::fabs(rel.theta()) < 1e-9 && std::fabs(rel.y()) < 1e-9 && rel.x() > 0)
    return Chain({Segment::line(start, rel.x())});
  return std::nullopt;
}

}  // namespace

std::optional<Chain> line_arc_line(const Pose2& start, const Pose2& end, double kappa_max)
{
  if (auto s = straight(start, end)) return s;
  double d1, d2;
  if (!corner(start, end, &d1, &d2) || d1 <= 0 || d2 <= 0) return std::nullopt;
  const double dth = normalize_angle(end.theta() - start.theta());
  const double t = std::min(d1, d2);                     // tangent length of the fillet
  const double radius = t / std::tan(0.5 * std::fabs(dth));
  if (!(radius > 0) || 1.0 / radius > kappa_max) return std::nullopt;
  const double kappa = (dth > 0 ? 1.0 : -1.0) / radius;
  Chain c;
  if (d1 - t > 1e-9) c.push_back(Segment::line(start, d1 - t));
  c.append_at_end(Segment::arc(start, kappa, std::fabs(dth) * radius));
  if (d2 - t > 1e-9) c.append_at_end(Segment::line(start, d2 - t));
  return c;
}

Chain smooth_turn(const Pose2& start, double dtheta, double kappa)
{
  const double k = std::fabs(kappa), sgn = dtheta >= 0 ? 1.0 : -1.0, a = std::fabs(dtheta);
  Chain c;
  if (a < 1e-12) return c;
  const double lc = 2.0 * a / (3.0 * k), larc = a / (3.0 * k);
  c.push_back(Segment::clothoid(start, 0.0, sgn * k, lc));
  c.append_at_end(Segment::arc(start, sgn * k, larc));
  c.append_at_end(Segment::clothoid(start, sgn * k, 0.0, lc));
  return c;
}

std::optional<Chain> line_turn_line_g2(const Pose2& start, const Pose2& end, double kappa_max)
{
  if (auto s = straight(start, end)) return s;
  double d1, d2;
  if (!corner(start, end, &d1, &d2) || d1 <= 0 || d2 <= 0) return std::nullopt;
  const double dth = normalize_angle(end.theta() - start.theta());
  // The turn's shape for curvature 1, then scaled: every length scales with 1/kappa, and so
  // does its tangent length (the distance from its ends to the corner; equal, by symmetry).
  const Chain unit = smooth_turn(Pose2(), dth, 1.0);
  const Pose2 e = unit.end();
  const double t_unit = e.x() - e.y() / std::tan(dth);
  if (!(t_unit > 0)) return std::nullopt;
  const double lambda = std::min(d1, d2) / t_unit;  // as wide as the shorter leg allows
  if (1.0 / lambda > kappa_max) return std::nullopt;
  const double t = lambda * t_unit;
  Chain c;
  if (d1 - t > 1e-9) c.push_back(Segment::line(start, d1 - t));
  const Pose2 turn_start = c.empty() ? start : c.end();
  const Chain turn = smooth_turn(turn_start, dth, 1.0 / lambda);
  for (const Segment& s : turn.segments()) c.append_at_end(s);
  if (d2 - t > 1e-9) c.append_at_end(Segment::line(start, d2 - t));
  return c;
}

std::optional<Segment> clothoid_g1(const Pose2& start, const Pose2& end)
{
  const Eigen::Vector2d r = end.translation() - start.translation();
  const double dist = r.norm();
  if (dist < 1e-9) return std::nullopt;
  const double phi = std::atan2(r.y(), r.x());
  const double phi0 = normalize_angle(start.theta() - phi);
  const double phi1 = normalize_angle(end.theta() - phi);
  const double delta = phi1 - phi0;
  // Solve Y(2A, delta - A, phi0) = 0 for A (Bertolazzi & Frego, eq. 12), from their guess.
  double A = 3.0 * (phi0 + phi1);
  for (int it = 0; it < 50; ++it) {
    // g(A) = integral_0^1 sin(A t^2 + (delta - A) t + phi0) dt, g'(A) = integral cos(..) (t^2 - t) dt
    const auto I = phase_integrals(2.0 * A, delta - A, phi0);
    const double g = I.y, dg = I.dx;
    if (std::fabs(g) < 1e-14) break;
    if (std::fabs(dg) < 1e-14) break;
    A -= g / dg;
  }
  const auto I = phase_integrals(2.0 * A, delta - A, phi0);
  if (std::fabs(I.y) > 1e-10 || !(I.x > 0)) return std::nullopt;
  const double length = dist / I.x;
  const double k0 = (delta - A) / length, k1 = (delta + A) / length;
  return Segment::clothoid(start, k0, k1, length);
}

std::optional<Chain> dubins(const Pose2& start, const Pose2& end, double kappa)
{
  // Normalised problem (Shkel & Lumelsky 2001): start at the origin heading alpha, end at
  // (d, 0) heading beta, unit turning radius.
  const double r = 1.0 / kappa;
  const Eigen::Vector2d delta = end.translation() - start.translation();
  const double D = delta.norm(), d = D / r;
  const double th = std::atan2(delta.y(), delta.x());
  auto mod2pi = [](double x) {
    x = std::fmod(x, 2.0 * M_PI);
    return x < 0 ? x + 2.0 * M_PI : x;
  };
  const double a = mod2pi(start.theta() - th), b = mod2pi(end.theta() - th);
  const double sa = std::sin(a), sb = std::sin(b), ca = std::cos(a), cb = std::cos(b), cab = std::cos(a - b);
  struct Word
  {
    std::array<char, 3> dirs;
    std::array<double, 3> t;
    bool ok;
  };
  std::array<Word, 6> words;
  {  // LSL
    const double p2 = 2 + d * d - 2 * cab + 2 * d * (sa - sb);
    const double tmp = std::atan2(cb - ca, d + sa - sb);
    words[0] = {{'L', 'S', 'L'}, {mod2pi(-a + tmp), std::sqrt(std::max(0.0, p2)), mod2pi(b - tmp)}, p2 >= 0};
  }
  {  // RSR
    const double p2 = 2 + d * d - 2 * cab + 2 * d * (sb - sa);
    const double tmp = std::atan2(ca - cb, d - sa + sb);
    words[1] = {{'R', 'S', 'R'}, {mod2pi(a - tmp), std::sqrt(std::max(0.0, p2)), mod2pi(-b + tmp)}, p2 >= 0};
  }
  {  // LSR
    const double p2 = -2 + d * d + 2 * cab + 2 * d * (sa + sb);
    const double p = std::sqrt(std::max(0.0, p2));
    const double tmp = std::atan2(-ca - cb, d + sa + sb) - std::atan2(-2.0, p);
    words[2] = {{'L', 'S', 'R'}, {mod2pi(-a + tmp), p, mod2pi(-mod2pi(b) + tmp)}, p2 >= 0};
  }
  {  // RSL
    const double p2 = -2 + d * d + 2 * cab - 2 * d * (sa + sb);
    const double p = std::sqrt(std::max(0.0, p2));
    const double tmp = std::atan2(ca + cb, d - sa - sb) - std::atan2(2.0, p);
    words[3] = {{'R', 'S', 'L'}, {mod2pi(a - tmp), p, mod2pi(b - tmp)}, p2 >= 0};
  }
  {  // RLR
    const double tmp = (6.0 - d * d + 2 * cab + 2 * d * (sa - sb)) / 8.0;
    const double p = mod2pi(2 * M_PI - std::acos(std::clamp(tmp, -1.0, 1.0)));
    const double t = mod2pi(a - std::atan2(ca - cb, d - sa + sb) + p / 2.0);
    words[4] = {{'R', 'L', 'R'}, {t, p, mod2pi(a - b - t + p)}, std::fabs(tmp) <= 1.0};
  }
  {  // LRL
    const double tmp = (6.0 - d * d + 2 * cab + 2 * d * (-sa + sb)) / 8.0;
    const double p = mod2pi(2 * M_PI - std::acos(std::clamp(tmp, -1.0, 1.0)));
    const double t = mod2pi(-a - std::atan2(ca - cb, d + sa - sb) + p / 2.0);
    words[5] = {{'L', 'R', 'L'}, {t, p, mod2pi(b - a - t + p)}, std::fabs(tmp) <= 1.0};
  }
  const Word* best = nullptr;
  double best_len = INFINITY;
  for (const Word& w : words) {
    if (!w.ok) continue;
    const double len = w.t[0] + w.t[1] + w.t[2];
    if (len < best_len) {
      best_len = len;
      best = &w;
    }
  }
  if (!best) return std::nullopt;
  Chain c;
  for (int i = 0; i < 3; ++i) {
    const double len = best->t[i] * r;
    if (len < 1e-12) continue;
    const Pose2 from = c.empty() ? start : c.end();
    switch (best->dirs[i]) {
      case 'L': c.push_back(Segment::arc(from, kappa, len)); break;
      case 'R': c.push_back(Segment::arc(from, -kappa, len)); break;
      default: c.push_back(Segment::line(from, len)); break;
    }
  }
  if (c.empty()) return std::nullopt;
  return c;
}

std::optional<Segment> quarter_ellipse(const Pose2& start, const Pose2& end, double tolerance)
{
  const Pose2 rel = start.between(end);
  if (rel.x() <= 0 || std::fabs(rel.y()) < 1e-9) return std::nullopt;
  const double sigma = rel.y() > 0 ? 1.0 : -1.0;
  if (std::fabs(normalize_angle(rel.theta() - sigma * M_PI_2)) > tolerance) return std::nullopt;
  const double a = rel.x(), b = std::fabs(rel.y()), t0 = -sigma * M_PI_2;
  return Segment::conic(start, a, b, t0, sigma > 0, ellipse_arc_length(a, b, t0, 0.0));
}

}  // namespace rgnav::trajectory
