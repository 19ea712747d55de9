#include "trajectory/velocity_profile.h"

#include <algorithm>
#include <cmath>

namespace rgnav::trajectory {

namespace {

struct Sample
{
  double s;
  double vlim;
  int turn_segment = -1;  // a turn in place happens here
};

double point_limit(const Segment& seg, double local_s, const Limits& lim)
{
  double v = std::min(lim.v_max, seg.v_max());
  const double k = std::fabs(seg.curvature_at(local_s));
  if (k > 1e-12) {
    v = std::min(v, std::sqrt(lim.a_lat_max / k));
    v = std::min(v, lim.omega_max / k);
  }
  const double dk = std::fabs(seg.sharpness_at(local_s));
  if (dk > 1e-12) v = std::min(v, std::sqrt(lim.alpha_max / dk));
  return v;
}

}  // namespace

double turn_duration(double angle, double omega_max, double alpha_max)
{
  const double a = std::fabs(angle);
  if (a >= omega_max * omega_max / alpha_max) return a / omega_max + omega_max / alpha_max;
  return 2.0 * std::sqrt(a / alpha_max);
}

VelocityProfile VelocityProfile::compute(const Chain& chain, const Limits& lim, double v_start, double v_end,
                                         double ds)
{
  VelocityProfile p;
  std::vector<Sample> samples;
  std::vector<size_t> segment_end_sample(chain.size());
  samples.reserve(static_cast<size_t>(chain.length() / ds) + 2 * chain.size() + 2);
  double prev_kappa = 0.0;
  bool have_prev = false;  // a driving segment precedes (for curvature jumps)
  for (size_t i = 0; i < chain.size(); ++i) {
    const Segment& seg = chain[i];
    const double a = chain.start_s(i);
    if (seg.kind() == Kind::kTurn) {
      samples.push_back({a, 0.0, static_cast<int>(i)});
      segment_end_sample[i] = samples.size() - 1;
      have_prev = false;
      continue;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(seg.length() / ds)));
    for (int j = 0; j <= n; ++j) {
      const double ls = seg.length() * j / n;
      Sample smp{a + ls, point_limit(seg, ls, lim)};
      if (j == 0 && have_prev) {
        const double jump = std::fabs(seg.curvature_at(0.0) - prev_kappa);
        if (jump > 1e-9) smp.vlim = std::min(smp.vlim, lim.omega_jump_max / jump);
      }
      if (j == 0 && !samples.empty() && samples.back().turn_segment < 0 && samples.back().s == smp.s) {
        samples.back().vlim = std::min(samples.back().vlim, smp.vlim);  // the joint
        continue;
      }
      samples.push_back(smp);
    }
    segment_end_sample[i] = samples.size() - 1;
    prev_kappa = seg.curvature_at(seg.length());
    have_prev = true;
  }
  if (samples.empty()) samples.push_back({0.0, 0.0});

  // Two passes over v^2 (constant acceleration between samples).
  const size_t n = samples.size();
  std::vector<double> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = samples[i].vlim;
  v.back() = std::min(v.back(), std::max(0.0, v_end));
  v[0] = std::max(0.0, v_start);
  for (size_t i = 0; i + 1 < n; ++i) {
    const double d = samples[i + 1].s - samples[i].s;
    v[i + 1] = std::min(v[i + 1], std::sqrt(v[i] * v[i] + 2.0 * lim.a_max * d));
  }
  for (size_t i = n - 1; i > 0; --i) {
    const double d = samples[i].s - samples[i - 1].s;
    const double reach = std::sqrt(v[i] * v[i] + 2.0 * lim.a_max * d);
    if (i - 1 == 0) {
      if (v[0] > reach + 1e-9) p.feasible_ = false;  // cannot brake in time from v_start
      continue;
    }
    v[i - 1] = std::min(v[i - 1], reach);
  }
  if (v_start > samples[0].vlim + 1e-9) p.feasible_ = false;

  // Knots with exact times.
  p.knots_.reserve(n + chain.size());
  double t = 0.0;
  for (size_t i = 0; i < n; ++i) {
    Knot k{t, samples[i].s, v[i], 0.0};
    if (samples[i].turn_segment >= 0) {
      const Segment& seg = chain[static_cast<size_t>(samples[i].turn_segment)];
      Turn tr;
      tr.segment = static_cast<size_t>(samples[i].turn_segment);
      tr.angle = seg.turn_angle();
      tr.alpha = lim.alpha_max;
      tr.omega_peak = std::min(lim.omega_max, std::sqrt(std::fabs(tr.angle) * lim.alpha_max));
      tr.t_acc = tr.omega_peak / lim.alpha_max;
      tr.t_total = turn_duration(tr.angle, lim.omega_max, lim.alpha_max);
      k.turn = static_cast<int>(p.turns_.size());
      p.turns_.push_back(tr);
      p.knots_.push_back(k);
      t += tr.t_total;
      continue;
    }
    if (i + 1 < n) {
      const double d = samples[i + 1].s - samples[i].s;
      if (d > 0) {
        const double vsum = v[i] + v[i + 1];
        k.a = (v[i + 1] * v[i + 1] - v[i] * v[i]) / (2.0 * d);
        t += vsum > 0 ? 2.0 * d / vsum : 0.0;
      }
    }
    p.knots_.push_back(k);
  }
  if (p.knots_.back().turn >= 0) p.knots_.push_back({t, p.knots_.back().s, 0.0, 0.0});  // rest after a final turn
  p.segment_end_v_.resize(chain.size());
  for (size_t i = 0; i < chain.size(); ++i)
    p.segment_end_v_[i] = chain[i].kind() == Kind::kTurn ? 0.0 : v[segment_end_sample[i]];
  return p;
}

size_t VelocityProfile::knot_before_time(double t) const
{
  auto it = std::upper_bound(knots_.begin(), knots_.end(), t, [](double x, const Knot& k) { return x < k.t; });
  return it == knots_.begin() ? 0 : static_cast<size_t>(it - knots_.begin()) - 1;
}

size_t VelocityProfile::knot_before_s(double s) const
{
  auto it = std::upper_bound(knots_.begin(), knots_.end(), s, [](double x, const Knot& k) { return x < k.s; });
  return it == knots_.begin() ? 0 : static_cast<size_t>(it - knots_.begin()) - 1;
}

ProfileState VelocityProfile::at_time(double t) const
{
  ProfileState st;
  if (knots_.empty()) return st;
  t = std::clamp(t, 0.0, total_time());
  const size_t i = knot_before_time(t);
  const Knot& k = knots_[i];
  const double tau = t - k.t;
  if (k.turn >= 0) {
    const Turn& tr = turns_[static_cast<size_t>(k.turn)];
    const double sgn = tr.angle >= 0 ? 1.0 : -1.0, A = std::fabs(tr.angle);
    double ang, om;
    if (tau < tr.t_acc) {
      ang = 0.5 * tr.alpha * tau * tau;
      om = tr.alpha * tau;
    } else if (tau < tr.t_total - tr.t_acc) {
      ang = 0.5 * tr.omega_peak * tr.t_acc + tr.omega_peak * (tau - tr.t_acc);
      om = tr.omega_peak;
    } else {
      const double rem = std::max(0.0, tr.t_total - tau);
      ang = A - 0.5 * tr.alpha * rem * rem;
      om = tr.alpha * rem;
    }
    st.s = k.s;
    st.turn = static_cast<int>(tr.segment);
    st.turn_angle = sgn * std::clamp(ang, 0.0, A);
    st.omega_turn = sgn * om;
    return st;
  }
  if (i + 1 >= knots_.size()) {
    st.s = k.s;
    st.v = k.v;
    return st;
  }
  st.a = k.a;
  st.v = std::max(0.0, k.v + k.a * tau);
  st.s = std::min(knots_[i + 1].s, k.s + k.v * tau + 0.5 * k.a * tau * tau);
  return st;
}

double VelocityProfile::speed_at(double s) const
{
  if (knots_.empty()) return 0.0;
  const Knot& k = knots_[knot_before_s(s)];
  if (k.turn >= 0) return 0.0;
  return std::sqrt(std::max(0.0, k.v * k.v + 2.0 * k.a * (s - k.s)));
}

double VelocityProfile::time_at(double s) const
{
  // The first time s is reached: a turn in place at s comes after arriving there.
  if (knots_.empty()) return 0.0;
  auto it = std::lower_bound(knots_.begin(), knots_.end(), s, [](const Knot& k, double x) { return k.s < x; });
  if (it == knots_.end()) return knots_.back().t;
  if (it->s <= s || it == knots_.begin()) return it->t;
  const Knot& k = *(it - 1);
  const double d = s - k.s;
  if (std::fabs(k.a) < 1e-12) return k.t + d / std::max(1e-12, k.v);
  const double disc = std::max(0.0, k.v * k.v + 2.0 * k.a * d);
  return k.t + (std::sqrt(disc) - k.v) / k.a;
}

}  // namespace rgnav::trajectory
