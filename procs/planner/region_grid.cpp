#include "planner/region_grid.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::planner {

namespace {

// The region-frame rectangle the grid must cover: its freespace bitmap (unknown beyond it is
// occupied anyway) and its line map.
void extent(const rgmap::Region& region, Eigen::Vector2d* lo, Eigen::Vector2d* hi)
{
  const double inf = std::numeric_limits<double>::infinity();
  *lo = Eigen::Vector2d(inf, inf);
  *hi = -*lo;
  auto take = [&](const Eigen::Vector2d& p) {
    *lo = lo->cwiseMin(p);
    *hi = hi->cwiseMax(p);
  };
  const auto& fs = region.freespace;
  if (fs.width() > 0 && fs.height() > 0) {
    const double w = fs.width() * fs.resolution(), h = fs.height() * fs.resolution();
    for (const auto& c : {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0), Eigen::Vector2d(0, h), Eigen::Vector2d(w, h)})
      take(fs.region_from_grid() * c);
  }
  for (const auto& s : region.segments) {
    take(s.a);
    take(s.b);
  }
  if (!std::isfinite(lo->x())) *lo = *hi = Eigen::Vector2d::Zero();
}

}  // namespace

RegionGrid::RegionGrid(const rgmap::Region& region, const GridOptions& options,
                       const std::vector<NeighbourRegion>& neighbours,
                       const std::vector<std::vector<Eigen::Vector2d>>& gateways,
                       const std::vector<Eigen::Vector2d>& blocked)
    : options_(options), resolution_(options.resolution)
{
  Eigen::Vector2d lo, hi;
  extent(region, &lo, &hi);
  if (!neighbours.empty()) {
    lo -= Eigen::Vector2d::Constant(options_.neighbour_margin);
    hi += Eigen::Vector2d::Constant(options_.neighbour_margin);
  }
  // One occupied cell all round, so that the edge of the known world is an obstacle too.
  origin_ = lo - Eigen::Vector2d::Constant(resolution_);
  width_ = std::max(1, static_cast<int>(std::ceil((hi.x() - origin_.x()) / resolution_)) + 1);
  height_ = std::max(1, static_cast<int>(std::ceil((hi.y() - origin_.y()) / resolution_)) + 1);

  // 255 = free; 0 = occupied (a line, or nothing the freespace calls free).
  cv::Mat free_mask(height_, width_, CV_8UC1, cv::Scalar(0));
  // Bresenham: cv::line with 8-connectivity sets every cell the segment passes.
  auto draw = [this](cv::Mat& mask, const Eigen::Vector2d& pa, const Eigen::Vector2d& pb) {
    const Cell a = cell_of(pa), b = cell_of(pb);
    cv::line(mask, cv::Point(a.x(), a.y()), cv::Point(b.x(), b.y()), cv::Scalar(0), 1, cv::LINE_8);
  };
  cv::Mat own(height_, width_, CV_8UC1, cv::Scalar(0));
  for (int y = 1; y + 1 < height_; ++y)
    for (int x = 1; x + 1 < width_; ++x)
      if (region.freespace.is_free(center_of(Cell(x, y)))) own.at<uint8_t>(y, x) = 255;
  own.copyTo(free_mask);
  if (!neighbours.empty()) {
    // Where the region knows nothing, its neighbours' freespace. (Not their lines: a wall seen
    // from both sides is in both line maps a few centimetres apart, and the copy from beside,
    // placed through the gateway's transform, would narrow or close the opening.)
    cv::Mat beside(height_, width_, CV_8UC1, cv::Scalar(0));
    for (const auto& n : neighbours) {
      const geometry::Pose2 other_from_this = n.this_from_other.inverse();
      // Only the cells under the neighbour's freespace grid.
      const auto& fs = n.region->freespace;
      const double fw = fs.width() * fs.resolution(), fh = fs.height() * fs.resolution();
      Eigen::Vector2d flo(1e18, 1e18), fhi(-1e18, -1e18);
      for (const auto& c : {Eigen::Vector2d(0, 0), Eigen::Vector2d(fw, 0), Eigen::Vector2d(0, fh), Eigen::Vector2d(fw, fh)}) {
        const Eigen::Vector2d p = n.this_from_other * (fs.region_from_grid() * c);
        flo = flo.cwiseMin(p);
        fhi = fhi.cwiseMax(p);
      }
      const Cell c0 = cell_of(flo), c1 = cell_of(fhi);
      for (int y = std::max(1, c0.y()); y <= std::min(height_ - 2, c1.y()); ++y)
        for (int x = std::max(1, c0.x()); x <= std::min(width_ - 2, c1.x()); ++x)
          if (!own.at<uint8_t>(y, x) && fs.is_free(other_from_this * center_of(Cell(x, y))))
            beside.at<uint8_t>(y, x) = 255;
    }
    cv::bitwise_or(free_mask, beside, free_mask);
  }
  for (const auto& points : gateways) carve_gateway(free_mask, points);
  // A line lying wholly inside a door's or passage's opening, clear of its jambs, is something
  // standing in a way the robot has gone through (a person waiting there when the kernel saw it,
  // a chair): collision avoidance sees whether it is still there, and a way it cannot pass is
  // marked closed as it is tried. A shut door's leaf reaches the jambs and stays a wall.
  std::vector<const rgmap::LineSegment*> walls_drawn;
  for (const auto& seg : region.segments)
    if (!in_an_opening(seg.a, seg.b, gateways)) walls_drawn.push_back(&seg);
  for (const auto* seg : walls_drawn) draw(free_mask, seg->a, seg->b);
  const int blocked_cells = std::max(1, static_cast<int>(std::lround(options_.blocked_radius / resolution_)));
  auto draw_blocked = [&](cv::Mat& mask) {
    for (const auto& p : blocked) {
      const Cell c = cell_of(p);
      cv::circle(mask, cv::Point(c.x(), c.y()), blocked_cells, cv::Scalar(0), cv::FILLED, cv::LINE_8);
    }
  };
  const cv::Mat free_without_places = blocked.empty() ? cv::Mat() : free_mask.clone();
  draw_blocked(free_mask);
  cv::Mat dist;
  cv::distanceTransform(free_mask, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  // The walls alone (and the grid's border): the robot's body may reach unknown_overlap into
  // space the region has not seen, never into a wall.
  cv::Mat walls(height_, width_, CV_8UC1, cv::Scalar(255)), wall_dist;
  cv::rectangle(walls, cv::Rect(0, 0, width_, height_), cv::Scalar(0), 1);
  for (const auto* seg : walls_drawn) draw(walls, seg->a, seg->b);
  const cv::Mat walls_without_places = blocked.empty() ? cv::Mat() : walls.clone();
  draw_blocked(walls);
  cv::distanceTransform(walls, wall_dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  const double r = options_.robot_radius, m = options_.clearance_margin, w = options_.comfort_width;
  // Where the robot's body fits, from the distances to anything not free and to the walls.
  auto body_fits = [&](const cv::Mat& free_dist, const cv::Mat& walls_dist, int x, int y) {
    const double c = free_dist.at<float>(y, x) * resolution_;
    return options_.unknown_overlap > 0 ? !(c < r - options_.unknown_overlap || walls_dist.at<float>(y, x) * resolution_ < r)
                                        : !(c < r);
  };

  // Cost levels: 0 in open space; 1 in the comfort band [r + margin, r + margin + comfort)
  // (a slight push away from walls); 2 .. levels-1 split [r, r + margin) evenly, rising to
  // 1 + wall_cost at the blocked limit (clearance below the margin is paid for dearly, so paths
  // keep it wherever the passage allows and prefer wide passages to narrow ones).
  const int levels = std::clamp(options_.cost_levels, 3, 254);
  const int tight = levels - 2;   // levels inside the margin
  level_cost_.assign(static_cast<size_t>(levels), 1.0);
  level_cost_[1] = 1.0 + options_.comfort_cost;
  for (int k = 0; k < tight; ++k)
    level_cost_[static_cast<size_t>(2 + k)] =
        1.0 + options_.comfort_cost + (options_.wall_cost - options_.comfort_cost) * (k + 1.0) / tight;
  clearance_.resize(static_cast<size_t>(width_) * height_);
  level_.resize(clearance_.size());
  wall_clearance_.resize(clearance_.size());
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const size_t i = index(Cell(x, y));
      const float c = dist.at<float>(y, x) * static_cast<float>(resolution_);
      clearance_[i] = c;
      wall_clearance_[i] = wall_dist.at<float>(y, x) * static_cast<float>(resolution_);
      if (!body_fits(dist, wall_dist, x, y)) {
        level_[i] = kBlocked;
      } else if (c < r) {
        level_[i] = static_cast<uint8_t>(levels - 1);   // the body over unseen space: the dearest level
      } else if (c >= r + m + w) {
        level_[i] = 0;
      } else if (c >= r + m) {
        level_[i] = 1;
      } else {
        const int k = std::min(tight - 1, static_cast<int>((r + m - c) / m * tight));   // 0 near r + m
        level_[i] = static_cast<uint8_t>(2 + k);
      }
    }
  }
  // The robot's space in this region: free cells connected to the region's own freespace (a
  // start or goal is moved onto these only, never into a room behind a wall seen from beside).
  // Pieces: the 8-connected cells where the body fits, each piece's count of the region's own
  // freespace cells, and the piece with the most of them.
  struct Pieces
  {
    cv::Mat fits, labels;
    std::vector<int> own_cells;
    int32_t main = 0;
  };
  auto pieces_of = [&](const cv::Mat& free_dist, const cv::Mat& walls_dist) {
    Pieces p;
    p.fits = cv::Mat(height_, width_, CV_8UC1, cv::Scalar(0));
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x)
        if (body_fits(free_dist, walls_dist, x, y)) p.fits.at<uint8_t>(y, x) = 255;
    p.own_cells.assign(static_cast<size_t>(cv::connectedComponents(p.fits, p.labels, 8, CV_32S)), 0);
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x)
        if (own.at<uint8_t>(y, x) && p.fits.at<uint8_t>(y, x)) ++p.own_cells[static_cast<size_t>(p.labels.at<int>(y, x))];
    for (size_t l = 1; l < p.own_cells.size(); ++l)
      if (p.own_cells[l] > (p.main ? p.own_cells[static_cast<size_t>(p.main)] : 0)) p.main = static_cast<int32_t>(l);
    return p;
  };
  const Pieces here = pieces_of(dist, wall_dist);
  own_.assign(level_.size(), 0);
  component_.assign(level_.size(), 0);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      if (here.fits.at<uint8_t>(y, x)) {
        const int l = here.labels.at<int>(y, x);
        own_[index(Cell(x, y))] = here.own_cells[static_cast<size_t>(l)] > 0 ? 1 : 0;
        component_[index(Cell(x, y))] = l;
      }
  main_component_ = here.main;
  main_pieces_.assign(here.own_cells.size(), 0);
  if (main_component_) main_pieces_[static_cast<size_t>(main_component_)] = 1;
  if (blocked.empty()) return;
  // Blocked places may cut the main space in pieces; each piece is still the region's space
  // (the robot held before a place is not apart from it): the pieces of the main piece the
  // grid would have without them.
  cv::Mat open_dist, open_wall_dist;
  cv::distanceTransform(free_without_places, open_dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  cv::distanceTransform(walls_without_places, open_wall_dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  const Pieces open = pieces_of(open_dist, open_wall_dist);
  if (!open.main) return;
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      if (here.fits.at<uint8_t>(y, x) && open.labels.at<int>(y, x) == open.main)
        main_pieces_[static_cast<size_t>(here.labels.at<int>(y, x))] = 1;
}

bool RegionGrid::in_main_space(int32_t piece) const
{
  return piece > 0 && static_cast<size_t>(piece) < main_pieces_.size() && main_pieces_[static_cast<size_t>(piece)];
}

bool RegionGrid::in_an_opening(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                               const std::vector<std::vector<Eigen::Vector2d>>& gateways) const
{
  // Clear of the jambs by a cell: a line ending at a jamb is the wall's or a shut door's.
  const double clear = resolution_;
  for (const auto& points : gateways) {
    if (points.size() == 4) continue;   // a crossing's square: as wide as the hallways it joins
    for (const auto& [u, v] : rgmap::gateway_edges(points)) {
      const Eigen::Vector2d d = v - u;
      const double length = d.norm();
      if (length < 2 * clear + 1e-6) continue;
      const Eigen::Vector2d along = d / length;
      auto inside = [&](const Eigen::Vector2d& p) {
        const Eigen::Vector2d r = p - u;
        const double t = r.dot(along), n = std::fabs(along.x() * r.y() - along.y() * r.x());
        return t >= clear && t <= length - clear && n <= options_.passage_depth;
      };
      if (inside(a) && inside(b)) return true;
    }
  }
  return false;
}

void RegionGrid::carve_gateway(cv::Mat& free_mask, const std::vector<Eigen::Vector2d>& points) const
{
  auto fill = [&](const std::vector<Eigen::Vector2d>& corners) {
    std::vector<cv::Point> poly;
    for (const auto& p : corners) {
      const Cell c = cell_of(p);
      poly.emplace_back(c.x(), c.y());
    }
    cv::fillConvexPoly(free_mask, poly, cv::Scalar(255), cv::LINE_8);
  };
  if (points.size() == 4) {
    fill(points);   // a crossing's square
    return;
  }
  for (const auto& [a, b] : rgmap::gateway_edges(points)) {
    const Eigen::Vector2d d = b - a;
    if (d.norm() < 1e-6) continue;
    const Eigen::Vector2d n = Eigen::Vector2d(-d.y(), d.x()).normalized() * options_.passage_depth;
    fill({a + n, b + n, b - n, a - n});
  }
}

Cell RegionGrid::cell_of(const Eigen::Vector2d& p) const
{
  return Cell(static_cast<int>(std::floor((p.x() - origin_.x()) / resolution_)),
              static_cast<int>(std::floor((p.y() - origin_.y()) / resolution_)));
}

Eigen::Vector2d RegionGrid::center_of(const Cell& c) const
{
  return origin_ + resolution_ * Eigen::Vector2d(c.x() + 0.5, c.y() + 0.5);
}

std::optional<double> RegionGrid::line_cost(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const
{
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * resolution_))));
  double cost = 0;
  for (int i = 0; i <= n; ++i) {
    const Cell c = cell_of(a + (b - a) * (static_cast<double>(i) / n));
    if (!free(c)) return std::nullopt;
    // The two ends count half: a polyline's shared vertices are not counted twice.
    const double w = (i == 0 || i == n) ? 0.5 : 1.0;
    cost += w * level_cost_[level_[index(c)]];
  }
  return cost * len / n;
}

double RegionGrid::line_clearance(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const
{
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * resolution_))));
  double m = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    const Cell c = cell_of(a + (b - a) * (static_cast<double>(i) / n));
    m = std::min(m, in_bounds(c) ? static_cast<double>(clearance_[index(c)]) : 0.0);
  }
  return m;
}

std::optional<Cell> RegionGrid::nearest_free(const Cell& c, double reach_m) const
{
  if (free(c) && own_[index(c)]) return c;
  const int reach = static_cast<int>(std::ceil((reach_m < 0 ? options_.adapt_distance : reach_m) / resolution_));
  std::optional<Cell> best;
  double best_d2 = std::numeric_limits<double>::infinity();
  float best_clear = 0;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const double d2 = dx * dx + dy * dy;
      if (d2 > static_cast<double>(reach) * reach) continue;
      const Cell n(c.x() + dx, c.y() + dy);
      if (!free(n) || !own_[index(n)]) continue;
      const float cl = clearance_[index(n)];
      if (d2 < best_d2 - 1e-9 || (d2 < best_d2 + 1e-9 && cl > best_clear)) {
        best = n;
        best_d2 = d2;
        best_clear = cl;
      }
    }
  }
  return best;
}

std::optional<Cell> RegionGrid::nearest_reachable_in(const Eigen::Vector2d& from, int32_t piece, double reach_m) const
{
  if (piece <= 0) return std::nullopt;
  const Cell c = cell_of(from);
  const int reach = static_cast<int>(std::ceil(reach_m / resolution_));
  struct Candidate { double d2; Cell cell; };
  std::vector<Candidate> candidates;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const Cell n(c.x() + dx, c.y() + dy);
      if (!in_bounds(n) || component_[index(n)] != piece || !own_[index(n)]) continue;
      const double d2 = (center_of(n) - from).squaredNorm();
      if (d2 <= reach_m * reach_m) candidates.push_back({d2, n});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.d2 < b.d2; });
  for (const auto& cand : candidates)
    if (clear_of_lines(from, center_of(cand.cell))) return cand.cell;
  return std::nullopt;
}

bool RegionGrid::clear_of_lines(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const
{
  // Never nearer a line than the robot radius, or than the body already stands (a robot the map
  // shows against furniture may still back off it).
  const float keep = std::min(static_cast<float>(options_.robot_radius), wall_clearance(cell_of(from))) - 1e-4f;
  const double len = (to - from).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * resolution_))));
  for (int i = 1; i <= n; ++i)
    if (wall_clearance(cell_of(from + (to - from) * (static_cast<double>(i) / n))) < keep) return false;
  return true;
}

}  // namespace rgnav::planner
