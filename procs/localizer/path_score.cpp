#include "localizer/path_score.h"

#include <algorithm>
#include <deque>
#include <optional>
#include <set>

namespace rgnav::localizer {

using geometry::Pose2;

std::pair<const RegionModel*, Pose2> holding_region(const RegionMaps& maps, int64_t region, const Pose2& region_from_base,
                                                    double bbox_margin, int hops)
{
  const RegionModel* start = maps.region(region);
  if (!start) return {nullptr, region_from_base};
  const auto holds = [&](const RegionModel& m, const Pose2& p) {
    return m.is_free(p.translation()) && m.in_bbox(p.translation(), bbox_margin);
  };
  if (holds(*start, region_from_base)) return {start, region_from_base};
  // Breadth first through the gateways: the nearest region (fewest gateways) that holds it.
  struct Step { const RegionModel* m; Pose2 pose; int depth; };
  std::deque<Step> queue{{start, region_from_base, 0}};
  std::set<int64_t> seen{start->id};
  while (!queue.empty()) {
    const Step s = queue.front();
    queue.pop_front();
    if (s.depth >= hops) continue;
    for (const auto& link : s.m->links) {
      const RegionModel* n = maps.region(link.to);
      if (!n || !seen.insert(n->id).second) continue;
      const Pose2 there = link.here_from_there.inverse() * s.pose;
      if (holds(*n, there)) return {n, there};
      queue.push_back({n, there, s.depth + 1});
    }
  }
  return {start, region_from_base};
}

double path_score(const RegionMaps& maps, const BeamScorer& scorer, int64_t region, const Pose2& region_from_base,
                  const std::vector<PlacedView>& views, double bbox_margin)
{
  double s = 0;
  for (const auto& v : views) {
    const auto [m, pose] = holding_region(maps, region, region_from_base * v.now_from_then, bbox_margin);
    if (!m) return -1e300;
    s += scorer.score(m->field, pose, *v.points);
  }
  return s;
}

namespace {

// The freespace a beam is judged in: the region's own, and with `through_gateways` its
// neighbours' beyond the gateways too, where the stacked field holds their lines: outside the
// region's own rectangle (region_maps.cpp; inside it the region's own lines are the authority,
// and a neighbour's freespace there would judge beams against walls the field left out).
// `last` remembers the neighbour the walk was in, which most often holds the next step.
struct StackedFreespace
{
  const RegionMaps& maps;
  const RegionModel& m;
  bool through_gateways;
  mutable const RegionLink* last = nullptr;

  bool is_free(const Eigen::Vector2d& p) const
  {
    if (m.is_free(p)) return true;
    if (!through_gateways || m.in_bbox(p, 0.0)) return false;
    const auto neighbour_free = [&](const RegionLink& l) {
      const RegionModel* n = maps.region(l.to);
      return n && n->is_free(l.here_from_there.inverse() * p);
    };
    if (last && neighbour_free(*last)) return true;
    for (const auto& l : m.links)
      if (&l != last && neighbour_free(l)) {
        last = &l;
        return true;
      }
    return false;
  }
};

// Whether the map judges a beam from `from` that ends at `to` (no line near its end). The map
// says "no wall there" only when its carved freespace goes on past the end (a beam end falls in
// the free cell in front of any wall: the scans carve up to their own end points); it says
// "the beam should have stopped" when the beam leaves the freespace earlier where a line is. A
// beam that meets the end of the freespace where no line is has run into what the map's lines
// do not hold: unjudged.
bool judged_ray(const RegionModel& m, const StackedFreespace& free, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                double near_line)
{
  const double length = (to - from).norm();
  const double cell = m.freespace.resolution(), step = 0.5 * cell;
  if (length < step) return false;
  const Eigen::Vector2d dir = (to - from) / length;
  for (double t = step; t <= length + 1.5 * cell; t += step) {
    const Eigen::Vector2d p = from + t * dir;
    if (free.is_free(p)) continue;
    return t < length - cell && m.field.distance(p) <= near_line;
  }
  return true;
}

}  // namespace

std::vector<BeamFit> path_beam_fits(const RegionMaps& maps, const BeamScorer& scorer, int64_t region, const Pose2& region_from_base,
                                    const std::vector<PlacedView>& views, double bbox_margin, double near_line, bool through_gateways)
{
  std::vector<BeamFit> out;
  for (const auto& v : views) {
    const auto [m, pose] = holding_region(maps, region, region_from_base * v.now_from_then, bbox_margin);
    // One per view: the neighbour the last beam's walk ended in is where the next one's most
    // likely goes.
    const std::optional<StackedFreespace> free =
        m ? std::optional<StackedFreespace>(StackedFreespace{maps, *m, through_gateways}) : std::nullopt;
    for (const auto& p : *v.points) {
      BeamFit f;
      if (m) {
        const Eigen::Vector2d q = pose * p;
        const float d = m->field.distance(q);
        f.log_p = scorer.log_p(d);
        f.known = d <= near_line || judged_ray(*m, *free, pose.translation(), q, near_line);
      } else {
        f.log_p = scorer.floor();
      }
      out.push_back(f);
    }
  }
  return out;
}

JudgedDifference jointly_judged(const std::vector<BeamFit>& a, const std::vector<BeamFit>& b)
{
  JudgedDifference d;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    if (a[i].known && b[i].known) {
      d.log_ratio += a[i].log_p - b[i].log_p;
      ++d.beams;
    }
  return d;
}

}  // namespace rgnav::localizer
