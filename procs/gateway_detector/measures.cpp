#include "gateway_detector/measures.h"

#include <algorithm>
#include <cmath>

namespace rgnav::gateway_detector {

namespace {
const char* const kNames[kNumCrossingClasses] = {"x_crossing", "t_crossing", "lt_crossing", "rt_crossing",
                                                 "l_turn",     "r_turn",     "dead_end",    "hallway"};
// open[class] = {left, front, right}: the eight classes are exactly the eight combinations.
const bool kOpen[kNumCrossingClasses][3] = {
    {true, true, true},    {true, false, true},   {true, true, false},  {false, true, true},
    {true, false, false},  {false, false, true},  {false, false, false}, {false, true, false}};

// Beam index range [first, last] between the bearings of two points, clipped to the scan.
bool sector_beams(const sensors::LaserScan& scan, const Vec2& a, const Vec2& b, size_t* first, size_t* last)
{
  double ba = std::atan2(a.y(), a.x()), bb = std::atan2(b.y(), b.x());
  if (ba > bb) std::swap(ba, bb);
  const double lo = scan.angle_min, hi = scan.bearing(scan.size() - 1);
  ba = std::max(ba, lo);
  bb = std::min(bb, hi);
  if (scan.size() == 0 || ba > bb) return false;
  *first = static_cast<size_t>(std::ceil((ba - lo) / scan.angle_increment - 1e-9));
  *last = std::min(scan.size() - 1, static_cast<size_t>(std::floor((bb - lo) / scan.angle_increment + 1e-9)));
  return *first <= *last;
}

// The line shifted by `by` metres away from the laser origin.
Line shifted_away(const Line& l, double by)
{
  // Signed distance of the origin is -rho; moving away means increasing |rho| on the far side.
  return Line{l.theta, l.rho >= 0 ? l.rho + by : l.rho - by};
}
}  // namespace

const char* crossing_class_name(int c) { return c >= 0 && c < kNumCrossingClasses ? kNames[c] : "unknown"; }

int crossing_class_from_name(const std::string& name)
{
  for (int c = 0; c < kNumCrossingClasses; ++c)
    if (name == kNames[c]) return c;
  return -1;
}

bool expects_open(int cls, int sector) { return kOpen[cls][sector]; }

double distance_measure(const Vlm& v, double dhw)
{
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double d = (v.points[(i + 1) % 4] - v.points[i]).norm();
    // Clamped at 0 so one wild side cannot outweigh the other three (the formula is
    // unbounded below when |d - d_hw| > d_hw).
    sum += std::max(0.0, 1.0 - std::sqrt(std::fabs(d - dhw) / dhw));
  }
  return 0.25 * sum;
}

double rectangularity_measure(const Vlm& v)
{
  double dev = 0.0;
  for (int i = 0; i < 4; ++i) {
    const Vec2 p = v.points[i];
    const Vec2 a = v.points[(i + 3) % 4] - p, b = v.points[(i + 1) % 4] - p;
    const double na = a.norm(), nb = b.norm();
    const double alpha = (na < 1e-9 || nb < 1e-9) ? 0.0 : std::acos(std::clamp(a.dot(b) / (na * nb), -1.0, 1.0));
    dev += std::fabs(alpha - M_PI / 2);
  }
  return std::max(0.0, 1.0 - dev / (2.0 * M_PI));
}

SectorMeasures sector_measures(const sensors::LaserScan& scan, const Line& line, const Vec2& a, const Vec2& b, const MeasureOptions& o)
{
  SectorMeasures r;
  size_t first, last;
  if (!sector_beams(scan, a, b, &first, &last)) return r;
  const Line par = shifted_away(line, o.over_line_setback);
  int n = 0, on = 0, over = 0, occluded = 0;
  for (size_t i = first; i <= last; ++i) {
    if (scan.invalid(i)) continue;
    ++n;
    const double bearing = scan.bearing(i);
    const double dvl = ray_range(line, bearing);
    const double dpar = ray_range(par, bearing);
    const bool far = scan.no_return(i);
    if (!far && dvl > 0 && std::isfinite(dvl)) {
      const double diff = scan.ranges[i] - dvl;
      if (diff >= o.on_line_low && diff <= o.on_line_high) ++on;
      if (diff < o.on_line_low) ++occluded;
    }
    if (dpar > 0 && std::isfinite(dpar) && (far || scan.ranges[i] > dpar)) ++over;
  }
  r.beams = n;
  if (n == 0) return r;
  r.occluded = static_cast<double>(occluded) / n;
  const int visible = o.exclude_occluded ? n - occluded : n;
  if (visible < std::max(1, o.exclude_occluded ? o.min_visible_beams : 1)) return r;
  r.on_line = static_cast<double>(on) / visible;
  r.over_line = static_cast<double>(over) / visible;
  return r;
}

double on_line_fsm(const sensors::LaserScan& scan, const Line& line, const Vec2& a, const Vec2& b, const MeasureOptions& o, int* beams)
{
  const SectorMeasures m = sector_measures(scan, line, a, b, o);
  if (beams) *beams = m.beams;
  return m.on_line;
}

double over_line_fsm(const sensors::LaserScan& scan, const Line& line, const Vec2& a, const Vec2& b, const MeasureOptions& o)
{
  return sector_measures(scan, line, a, b, o).over_line;
}

Measures measure(const sensors::LaserScan& scan, const Vlm& v, const MeasureOptions& o)
{
  Measures m;
  m.w_d = distance_measure(v, o.hallway_width);
  m.w_r = rectangularity_measure(v);
  const Line* lines[3] = {&v.left, &v.front, &v.right};
  const int ends[3][2] = {{0, 1}, {1, 2}, {2, 3}};
  for (int s = 0; s < 3; ++s) {
    const Vec2& a = v.points[ends[s][0]];
    const Vec2& b = v.points[ends[s][1]];
    const SectorMeasures sm = sector_measures(scan, *lines[s], a, b, o);
    m.on_line[s] = sm.on_line;
    m.over_line[s] = sm.over_line;
    m.occluded[s] = sm.occluded;
    m.beams[s] = sm.beams;
  }
  return m;
}

ObservationVector class_weights(const Measures& m, const MeasureOptions& o)
{
  ObservationVector w{};
  const double general = 0.5 * o.f_vlm * (m.w_d + m.w_r);
  for (int c = 0; c < kNumCrossingClasses; ++c) {
    double fsm = 0.0;
    for (int s = 0; s < 3; ++s) fsm += kOpen[c][s] ? m.over_line[s] : m.on_line[s];
    w[c] = general + o.f_gw / 3.0 * fsm;
  }
  return w;
}

}  // namespace rgnav::gateway_detector
