#include "collision_avoidance/local_map.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::collision_avoidance {

namespace {
constexpr double kTurningRate = 0.15;  // [rad/s] the robot turns faster than this: tracks' motion may be its own
}  // namespace

void LocalMap::add_scan(ScanPoints scan)
{
  const bool memory = options_.memory > 0.0;
  const BeamView view(scan, options_.clear_margin);
  // Before this scan's hits are remembered: they lie at their own beams' ends.
  if (memory) forget_seen_through(view);
  // One pass over the hits: how long each cell has been hit decides whether a point may be
  // moving (the people tracker's input) or stands still (remembered: a person walking
  // leaves no trail of obstacles behind in places no beam looks at again).
  std::vector<Eigen::Vector2d> young;
  for (const auto& b : scan.points) {
    if (b.squaredNorm() > options_.max_range * options_.max_range) continue;
    const Eigen::Vector2d p = scan.odom_from_base * b;
    CellHits& h = hits_[cell_key(p)];
    if (h.last == time::Time{} || time::to_seconds(scan.stamp - h.last) > options_.occupancy_gap) h.first = scan.stamp;
    h.last = scan.stamp;
    if (time::to_seconds(h.last - h.first) < options_.static_after)
      young.push_back(p);
    else if (memory)
      remembered_[memory_key(p)] = {p, scan.stamp};
  }
  // Turning: the robot's heading changed since the scan before (more than scan noise).
  bool turning = false;
  if (!scans_.empty()) {
    const double dt = time::to_seconds(scan.stamp - scans_.back().stamp);
    const double dth = std::fabs(geometry::normalize_angle(scan.odom_from_base.theta() - scans_.back().odom_from_base.theta()));
    turning = dt > 0.0 && dth > kTurningRate * dt;
  }
  tracker_.update(scan.stamp, young, [&view](const Eigen::Vector2d& p) { return view.look(p); }, turning);
  if (memory && !scan.outline.empty() &&
      (views_.empty() || time::to_seconds(scan.stamp - views_.back().stamp) >= options_.view_interval)) {
    ScanPoints field_of_view;
    field_of_view.stamp = scan.stamp;
    field_of_view.odom_from_base = scan.odom_from_base;
    field_of_view.laser_origin = scan.laser_origin;
    field_of_view.outline = scan.outline;
    views_.push_back(std::move(field_of_view));
  }
  scans_.push_back(std::move(scan));
  while (static_cast<int>(scans_.size()) > options_.max_scans) scans_.pop_front();
}

BeamView::BeamView(const ScanPoints& scan, double margin)
    : laser_from_odom_(Pose2(scan.laser_origin, 0.0).inverse() * scan.odom_from_base.inverse()), margin_(margin)
{
  beams_.reserve(scan.outline.size());
  for (const auto& e : scan.outline) {
    const Eigen::Vector2d d = e - scan.laser_origin;
    beams_.emplace_back(std::atan2(d.y(), d.x()), d.norm());
  }
  std::sort(beams_.begin(), beams_.end());
}

SeenNow BeamView::look(const Eigen::Vector2d& odom_point) const
{
  const Eigen::Vector2d q = laser_from_odom_ * odom_point;
  const double bearing = std::atan2(q.y(), q.x());
  auto hi = std::lower_bound(beams_.begin(), beams_.end(), std::make_pair(bearing, -1.0));
  if (hi == beams_.begin() || hi == beams_.end()) return SeenNow::kUnknown;
  const auto lo = std::prev(hi);
  const double d = q.norm();
  if (std::min(hi->second, lo->second) > d + margin_) return SeenNow::kFreeNow;
  if (std::max(hi->second, lo->second) < d - margin_) return SeenNow::kHidden;
  return SeenNow::kStillThere;
}

SeenNow LocalMap::seen_now(const Eigen::Vector2d& p) const
{
  if (scans_.empty()) return SeenNow::kUnknown;
  const BeamView view(scans_.back(), options_.clear_margin);
  return view.empty() ? SeenNow::kUnknown : view.look(p);
}

bool BeamView::stands_apart(const Eigen::Vector2d& odom_point, double radius, double jump) const
{
  const Eigen::Vector2d q = laser_from_odom_ * odom_point;
  auto end = [&](size_t i) {
    return Eigen::Vector2d(beams_[i].second * std::cos(beams_[i].first), beams_[i].second * std::sin(beams_[i].first));
  };
  size_t lo = beams_.size(), hi = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < beams_.size(); ++i)
    if ((end(i) - q).norm() <= radius) {
      lo = std::min(lo, i);
      hi = std::max(hi, i);
      nearest = std::min(nearest, beams_[i].second);
    }
  if (lo > hi) return false;
  // Neither flank nearer than the thing itself (a wall seen at a grazing angle goes on toward
  // the laser on its near side: beams there end nearer, and on its far side farther by as much
  // as a jump at a few metres), and at least one of them reaching `jump` farther.
  const double left = lo > 0 ? beams_[lo - 1].second : std::numeric_limits<double>::infinity();
  const double right = hi + 1 < beams_.size() ? beams_[hi + 1].second : std::numeric_limits<double>::infinity();
  if (std::min(left, right) < nearest) return false;
  return (lo > 0 && left >= nearest + jump) || (hi + 1 < beams_.size() && right >= nearest + jump);
}

bool LocalMap::stands_apart(const Eigen::Vector2d& p, double radius, double jump) const
{
  if (scans_.empty()) return false;
  const BeamView view(scans_.back(), options_.clear_margin);
  return !view.empty() && view.stands_apart(p, radius, jump);
}

void LocalMap::forget_seen_through(const BeamView& view)
{
  if (view.empty()) return;
  for (auto it = remembered_.begin(); it != remembered_.end();)
    it = view.look(it->second.point) == SeenNow::kFreeNow ? remembered_.erase(it) : std::next(it);
}

void LocalMap::set_grid_points(time::Time stamp, std::vector<Eigen::Vector2d> odom_points)
{
  grid_stamp_ = stamp;
  grid_points_ = std::move(odom_points);
}

void LocalMap::rebuild(time::Time now)
{
  while (!scans_.empty() && time::to_seconds(now - scans_.front().stamp) > options_.max_age) scans_.pop_front();
  // The 3D grid is a map (the vision's occupancy, projected), not a scan: on a loaded host a frame
  // takes seconds through the vision, and its grid arrives older than max_age (under stress-ng the
  // robot drove into a table top the grid held). It holds until a newer one replaces it, at most
  // the memory time (a vision that stopped leaves nothing behind for longer).
  const double grid_age = std::max(options_.max_age, options_.memory);
  if (!grid_points_.empty() && time::to_seconds(now - grid_stamp_) > grid_age) grid_points_.clear();
  while (!views_.empty() && time::to_seconds(now - views_.front().stamp) > options_.memory) views_.pop_front();
  points_.clear();
  for (const auto& s : scans_)
    for (const auto& p : s.points)
      if (p.squaredNorm() <= options_.max_range * options_.max_range) points_.push_back(s.odom_from_base * p);
  // Young cells among the scan points (the 3D grid is a map of its own: static).
  // Young runs of hits may be people walking. This includes what the laser sees for the
  // first time: a person stepping out from behind a box is in cells no beam ever saw free,
  // so "free before" alone would call them static (measured: 25 instead of 7 collisions
  // over the 50 obstacle courses). Door frames turn static after static_after.
  const double keep = std::max(options_.max_age, 2.0 * options_.occupancy_gap);
  for (auto it = hits_.begin(); it != hits_.end();)
    it = time::to_seconds(now - it->second.last) > keep ? hits_.erase(it) : std::next(it);
  moving_.clear();
  auto is_static = [&](int64_t k) {
    auto it = hits_.find(k);
    return it != hits_.end() && time::to_seconds(it->second.last - it->second.first) >= options_.static_after;
  };
  for (const auto& p : points_) {
    if (is_static(cell_key(p))) continue;
    // A young cell right beside a static one extends what stands there (the face of a box
    // coming into view as the robot drives round it); treating those as possibly moving kept
    // the robot creeping past boxes, stopping for every newly seen piece of their sides.
    const int cx = static_cast<int>(std::floor(p.x() / options_.cell));
    const int cy = static_cast<int>(std::floor(p.y() / options_.cell));
    bool extends_static = false;
    for (int dx = -1; dx <= 1 && !extends_static; ++dx)
      for (int dy = -1; dy <= 1 && !extends_static; ++dy)
        if ((dx || dy) && is_static(key(cx + dx, cy + dy))) extends_static = true;
    if (!extends_static) moving_.push_back(p);
  }
  // Remembered points from before the kept scans (the kept ones are in already); static:
  // what stays out of view stays where it was as far as the robot can tell.
  if (!scans_.empty()) {
    const time::Time oldest = scans_.front().stamp;
    const Eigen::Vector2d here = scans_.back().odom_from_base.translation();
    for (auto it = remembered_.begin(); it != remembered_.end();) {
      const Remembered& r = it->second;
      if (time::to_seconds(now - r.stamp) > options_.memory ||
          (r.point - here).squaredNorm() > options_.max_range * options_.max_range) {
        it = remembered_.erase(it);
        continue;
      }
      if (r.stamp < oldest) points_.push_back(r.point);
      ++it;
    }
  }
  predicted_ = tracker_.predicted(now);
  predicted_begin_ = points_.size();
  points_.insert(points_.end(), predicted_.begin(), predicted_.end());
  predicted_end_ = points_.size();
  moving_.insert(moving_.end(), predicted_.begin(), predicted_.end());
  points_.insert(points_.end(), grid_points_.begin(), grid_points_.end());
  index_.clear();
  for (size_t i = 0; i < points_.size(); ++i) {
    const int ix = static_cast<int>(std::floor(points_[i].x() / options_.cell));
    const int iy = static_cast<int>(std::floor(points_[i].y() / options_.cell));
    index_[key(ix, iy)].push_back(static_cast<uint32_t>(i));
  }
  build_field();
}

void LocalMap::build_field()
{
  field_.release();
  if (points_.empty()) return;
  Eigen::Vector2d lo = points_.front(), hi = points_.front();
  for (const auto& p : points_) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  constexpr double kMaxSide = 40.0;
  lo.array() -= kFieldPad;
  hi.array() += kFieldPad;
  if ((hi - lo).maxCoeff() > kMaxSide) return;  // absurd spread (bad data): exact search only
  const int cols = static_cast<int>(std::ceil((hi.x() - lo.x()) / field_cell_));
  const int rows = static_cast<int>(std::ceil((hi.y() - lo.y()) / field_cell_));
  cv::Mat free_img(rows, cols, CV_8UC1, cv::Scalar(255));
  for (const auto& p : points_) {
    const int x = std::clamp(static_cast<int>((p.x() - lo.x()) / field_cell_), 0, cols - 1);
    const int y = std::clamp(static_cast<int>((p.y() - lo.y()) / field_cell_), 0, rows - 1);
    free_img.at<uint8_t>(y, x) = 0;
  }
  cv::distanceTransform(free_img, field_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  field_ *= field_cell_;
  field_origin_ = lo;
}

double LocalMap::clearance(const Eigen::Vector2d& p, double radius) const { return nearest(p, radius, false); }

double LocalMap::clearance_observed(const Eigen::Vector2d& p, double radius) const { return nearest(p, radius, true); }

double LocalMap::nearest(const Eigen::Vector2d& p, double radius, bool observed_only) const
{
  if (!field_.empty()) {
    const int x = static_cast<int>(std::floor((p.x() - field_origin_.x()) / field_cell_));
    const int y = static_cast<int>(std::floor((p.y() - field_origin_.y()) / field_cell_));
    if (x >= 0 && y >= 0 && x < field_.cols && y < field_.rows) {
      // The field measures between cell centres: the true distance is within one cell
      // diagonal (p and the point each up to half a diagonal from their centres).
      if (field_.at<float>(y, x) - 1.42 * field_cell_ > radius) return std::numeric_limits<double>::infinity();
    } else if (radius < kFieldPad) {
      return std::numeric_limits<double>::infinity();  // the field extends kFieldPad past every point
    }
  }
  double best2 = radius * radius;
  bool found = false;
  const int r = static_cast<int>(std::ceil(radius / options_.cell));
  const int cx = static_cast<int>(std::floor(p.x() / options_.cell));
  const int cy = static_cast<int>(std::floor(p.y() / options_.cell));
  for (int dx = -r; dx <= r; ++dx)
    for (int dy = -r; dy <= r; ++dy) {
      auto it = index_.find(key(cx + dx, cy + dy));
      if (it == index_.end()) continue;
      for (uint32_t i : it->second) {
        if (observed_only && i >= predicted_begin_ && i < predicted_end_) continue;
        const double d2 = (points_[i] - p).squaredNorm();
        if (d2 <= best2) {
          best2 = d2;
          found = true;
        }
      }
    }
  return found ? std::sqrt(best2) : std::numeric_limits<double>::infinity();
}

}  // namespace rgnav::collision_avoidance

namespace rgnav::collision_avoidance {

namespace {
// Few points (people), queried for the first metre of a chain only: a plain scan will do.
double nearest_within(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& p, double radius)
{
  double best2 = radius * radius;
  bool found = false;
  for (const auto& q : points) {
    const double d2 = (q - p).squaredNorm();
    if (d2 <= best2) {
      best2 = d2;
      found = true;
    }
  }
  return found ? std::sqrt(best2) : std::numeric_limits<double>::infinity();
}
}  // namespace

double LocalMap::clearance_predicted(const Eigen::Vector2d& p, double radius) const
{
  return nearest_within(predicted_, p, radius);
}

double LocalMap::clearance_moving(const Eigen::Vector2d& p, double radius) const
{
  return nearest_within(moving_, p, radius);
}

}  // namespace rgnav::collision_avoidance
