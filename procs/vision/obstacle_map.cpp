#include "vision/obstacle_map.h"

#include "vision/octree_trim.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rgnav::vision {

namespace {

std::unique_ptr<octomap::OcTree> make_tree(const ObstacleMapOptions& o, double hit, double miss)
{
  // Sensor model and clamping are set once here and never changed while the map runs.
  auto t = std::make_unique<octomap::OcTree>(o.resolution);
  t->setProbHit(hit);
  t->setProbMiss(miss);
  t->setClampingThresMin(o.clamp_min);
  t->setClampingThresMax(o.clamp_max);
  return t;
}

// Per column of the grid while it is projected.
// Centre height of the voxel level holding height h (keys are computed from floats: a point on
// a level's boundary could land on either side).
double level_centre(double h, double res) { return (std::floor(h / res + 1e-6) + 0.5) * res; }

struct Column
{
  double log_free = 0;     // sum of log(1 - p) over the occupied cells of the band
  float stereo_laser = -1; // stereo occupancy in the laser's layer (-1: not seen)
  float laser = -1;        // laser occupancy (-1: not seen)
  bool known = false;
  bool drop_off = false;
};

}  // namespace

bool ObstacleGrid::cell_of(const Eigen::Vector2d& odom_point, int* x, int* y) const
{
  const Eigen::Vector2d g = odom_from_grid.inverse() * odom_point;
  const int cx = static_cast<int>(std::floor(g.x() / resolution));
  const int cy = static_cast<int>(std::floor(g.y() / resolution));
  if (cx < 0 || cy < 0 || cx >= width || cy >= height) return false;
  *x = cx;
  *y = cy;
  return true;
}

ObstacleMap::ObstacleMap(const ObstacleMapOptions& options) : options_(options), forgetting_(options.forget_in_view_after)
{
  reset_trees();
}

void ObstacleMap::reset_trees()
{
  stereo_ = make_tree(options_, options_.stereo_prob_hit, options_.stereo_prob_miss);
  laser_ = make_tree(options_, options_.laser_prob_hit, options_.laser_prob_miss);
  floor_ = make_tree(options_, options_.stereo_prob_hit, options_.stereo_prob_miss);
  forgetting_.clear();
}

void ObstacleMap::reset()
{
  reset_trees();
  anchored_ = false;
}

octomap::point3d ObstacleMap::to_tree(const Eigen::Vector3d& odom) const
{
  return octomap::point3d(static_cast<float>(odom.x() - anchor_.x()), static_cast<float>(odom.y() - anchor_.y()),
                          static_cast<float>(odom.z()));
}

void ObstacleMap::follow(const geometry::Pose2& odom_from_base)
{
  const Eigen::Vector2d p = odom_from_base.translation();
  if (!anchored_ || (p - anchor_).norm() > options_.reanchor_distance) {
    if (anchored_) ++reanchors_;
    reset_trees();
    // On the voxel lattice, so that grid cells and voxel columns coincide.
    anchor_ = (p / options_.resolution).array().round().matrix() * options_.resolution;
    anchored_ = true;
    last_trim_ = p;
    return;
  }
  if ((p - last_trim_).norm() >= options_.trim_distance) {
    trim(p);
    last_trim_ = p;
  }
}

void ObstacleMap::trim(const Eigen::Vector2d& odom_center)
{
  for (octomap::OcTree* tree : {stereo_.get(), laser_.get(), floor_.get()})
    trim_tree(*tree, odom_center - anchor_, options_.keep_radius);
  forgetting_.erase_if([&](const octomap::OcTreeKey& k) {
    const octomap::point3d p = stereo_->keyToCoord(k);
    return (Eigen::Vector2d(p.x(), p.y()) - (odom_center - anchor_)).norm() > options_.keep_radius;
  });
  ++trims_;
}

int64_t ObstacleMap::clear_stereo_column(const octomap::point3d& laser_cell)
{
  int64_t cleared = 0;
  const double res = options_.resolution;
  // The column and its eight neighbours: the two sensors place one surface a cell apart (their
  // own discretisation, stereo's depth noise at close range).
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      for (double z = 0.5 * res; z < options_.max_point_height + res; z += res) {
        octomap::OcTreeKey k;
        const octomap::point3d p(static_cast<float>(laser_cell.x() + dx * res), static_cast<float>(laser_cell.y() + dy * res),
                                 static_cast<float>(z));
        if (!stereo_->coordToKeyChecked(p, k)) continue;
        octomap::OcTreeNode* node = stereo_->search(k);
        if (node == nullptr || node->getLogOdds() <= 0.f) continue;
        stereo_->setNodeValue(k, 0.f);   // unknown: the camera may see it again
        ++cleared;
      }
  return cleared;
}

InsertStats ObstacleMap::insert_stereo(const std::vector<Eigen::Vector3f>& base_points, const Eigen::Vector3d& base_camera,
                                       const geometry::Pose2& odom_from_base, double focal_baseline, int64_t utime,
                                       const StereoView* view)
{
  follow(odom_from_base);
  const Eigen::Matrix2d rot = odom_from_base.rotation();
  const Eigen::Vector2d t = odom_from_base.translation();
  const auto to_odom = [&](const Eigen::Vector3d& b) {
    const Eigen::Vector2d xy = rot * b.head<2>() + t;
    return Eigen::Vector3d(xy.x(), xy.y(), b.z());
  };
  const Eigen::Vector3d camera = to_odom(base_camera);
  const double max_range2 = options_.max_range * options_.max_range;
  const double floor_z = 0.5 * options_.resolution;   // the floor layer's one level

  InsertStats stats;
  octomap::Pointcloud cloud;
  cloud.reserve(base_points.size());
  octomap::KeySet floor_seen, drop_offs, hit;
  const bool forgetting = forgetting_.enabled() && utime > 0 && view != nullptr;
  // Height error per metre of range: a depth error of Z^2 / (f B) * sigma moves a point along its
  // ray, its height by (camera height - point height) / Z of that.
  const double height_error_per_m = focal_baseline > 0 ? options_.disparity_sigma / focal_baseline : 0.0;
  for (const Eigen::Vector3f& pf : base_points) {
    Eigen::Vector3d b = pf.cast<double>();
    if (b.z() > options_.max_point_height) continue;
    const double range = (b - base_camera).norm();
    const double uncertainty = std::abs(base_camera.z() - b.z()) * range * height_error_per_m;
    const double tolerance = std::min(options_.floor_tolerance + uncertainty, options_.max_floor_tolerance);
    const bool descends = b.z() < base_camera.z();
    if (b.z() < -options_.drop_off_depth - (tolerance - options_.floor_tolerance) && descends) {
      // Holz et al. 4.2: a point below the floor is a hole; the obstacle is where its ray
      // crosses the floor, the edge the robot must not pass.
      const double s = base_camera.z() / (base_camera.z() - b.z());
      const Eigen::Vector3d crossing = base_camera + s * (b - base_camera);
      ++stats.drop_offs;
      if ((crossing - base_camera).squaredNorm() <= max_range2)
        drop_offs.insert(floor_->coordToKey(to_tree(to_odom(Eigen::Vector3d(crossing.x(), crossing.y(), floor_z)))));
      continue;
    }
    if (std::abs(b.z()) <= tolerance && descends) {
      // Floor: on the floor plane where its ray meets it (the depth is the uncertain part).
      b = base_camera + base_camera.z() / (base_camera.z() - b.z()) * (b - base_camera);
      b.z() = 0.0;
      const Eigen::Vector3d o = to_odom(b);
      if ((b - base_camera).squaredNorm() <= max_range2)
        floor_seen.insert(floor_->coordToKey(to_tree(Eigen::Vector3d(o.x(), o.y(), floor_z))));
      cloud.push_back(to_tree(o));
      continue;
    }
    cloud.push_back(to_tree(to_odom(b)));
    if (forgetting && (b - base_camera).squaredNorm() <= max_range2) hit.insert(stereo_->coordToKey(cloud.back()));
  }
  stats.points = cloud.size();
  const auto t0 = std::chrono::steady_clock::now();
  // discretize: many pixels fall into one voxel near the camera; one ray per end voxel.
  stereo_->insertPointCloud(cloud, to_tree(camera), options_.max_range, false, true);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const auto& k : floor_seen) floor_->updateNode(k, false);
  for (const auto& k : drop_offs)
    if (!floor_seen.count(k)) floor_->updateNode(k, true);
  if (forgetting) {
    Eigen::Isometry3d tree_from_base = Eigen::Isometry3d::Identity();
    tree_from_base.linear().topLeftCorner<2, 2>() = rot;
    tree_from_base.translation() = Eigen::Vector3d(t.x() - anchor_.x(), t.y() - anchor_.y(), 0.0);
    // A point hides a cell when it is nearer by more than a cell and its depth noise.
    const double depth_sigma_per_m2 = focal_baseline > 0 ? options_.disparity_sigma / focal_baseline : 0.0;
    const FrameView seen(*view, tree_from_base, base_points, options_.resolution, depth_sigma_per_m2);
    forgotten_ += forgetting_.update(*stereo_, hit, seen, utime);
  }
  return stats;
}

void ObstacleMap::insert_laser(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_base,
                               const geometry::Pose2& base_from_laser)
{
  follow(odom_from_base);
  const geometry::Pose2 odom_from_laser = odom_from_base * base_from_laser;
  const double h = level_centre(options_.laser_height, options_.resolution);
  octomap::Pointcloud cloud;
  cloud.reserve(scan.size());
  // A beam without return clears up to the free range: its end is put past it (OctoMap then
  // marks the ray free and no end cell occupied).
  const double beyond = options_.laser_max_range + 1.0;
  for (size_t i = 0; i < scan.size(); ++i) {
    double r;
    if (scan.hit(i)) r = std::min<double>(scan.ranges[i], beyond);
    else if (scan.no_return(i)) r = beyond;
    else continue;
    const Eigen::Vector2d p = odom_from_laser * (r * scan.direction(i));
    cloud.push_back(to_tree(Eigen::Vector3d(p.x(), p.y(), h)));
  }
  const Eigen::Vector2d o = odom_from_laser.translation();
  const octomap::point3d origin = to_tree(Eigen::Vector3d(o.x(), o.y(), h));
  // Laser cells seen occupied within reach of this scan, to tell which it now sees free.
  std::vector<octomap::OcTreeKey> occupied;
  if (options_.laser_clears_stereo) {
    const float r = static_cast<float>(options_.laser_max_range);
    const octomap::point3d lo(origin.x() - r, origin.y() - r, static_cast<float>(h)), hi(origin.x() + r, origin.y() + r, static_cast<float>(h));
    for (auto it = laser_->begin_leafs_bbx(lo, hi), end = laser_->end_leafs_bbx(); it != end; ++it)
      if (it->getLogOdds() > 0.f && it.getSize() <= options_.resolution * 1.5) occupied.push_back(it.getKey());
  }
  laser_->insertPointCloud(cloud, origin, options_.laser_max_range, false, true);
  for (const auto& k : occupied) {
    const octomap::OcTreeNode* node = laser_->search(k);
    if (node != nullptr && node->getLogOdds() <= 0.f) laser_cleared_ += clear_stereo_column(laser_->keyToCoord(k));
  }
}

ObstacleGrid ObstacleMap::project(const geometry::Pose2& odom_from_base, int64_t utime) const
{
  const double res = options_.resolution;
  const int n = std::max(1, static_cast<int>(std::lround(options_.grid_size / res)));
  ObstacleGrid g;
  g.utime = utime;
  g.resolution = res;
  g.width = g.height = n;
  g.min_height = options_.min_height;
  g.max_height = options_.max_height;
  // Grid corner on the voxel lattice of the trees (whose origin is the anchor).
  const Eigen::Vector2d robot = odom_from_base.translation() - anchor_;
  const Eigen::Vector2d corner = ((robot.array() - 0.5 * n * res) / res).floor().matrix() * res;
  g.odom_from_grid = geometry::Pose2(corner + anchor_, 0.0);
  g.cells.assign(static_cast<size_t>(n) * static_cast<size_t>(n), -1);
  if (!anchored_) return g;

  std::vector<Column> col(g.cells.size());
  // Voxel levels whose centres lie in the band, and the laser's level.
  const int band_lo = static_cast<int>(std::ceil(options_.min_height / res - 0.5));
  const int band_hi = static_cast<int>(std::floor(options_.max_height / res - 0.5));
  const double laser_z = level_centre(options_.laser_height, res);
  const int laser_level = static_cast<int>(std::floor(laser_z / res));
  const bool laser_in_band = laser_level >= band_lo && laser_level <= band_hi;

  // Calls fn(column, leaf) for every grid column a leaf of `tree` in [z0, z1] covers.
  const auto for_columns = [&](const octomap::OcTree& tree, double z0, double z1, auto&& fn) {
    const octomap::point3d lo(static_cast<float>(corner.x() + 0.5 * res), static_cast<float>(corner.y() + 0.5 * res),
                              static_cast<float>(z0));
    const octomap::point3d hi(static_cast<float>(corner.x() + (n - 0.5) * res), static_cast<float>(corner.y() + (n - 0.5) * res),
                              static_cast<float>(z1));
    for (auto it = tree.begin_leafs_bbx(lo, hi), end = tree.end_leafs_bbx(); it != end; ++it) {
      const double s = it.getSize();
      const int cells = std::max(1, static_cast<int>(std::lround(s / res)));
      const int x0 = static_cast<int>(std::lround((it.getX() - 0.5 * s - corner.x()) / res));
      const int y0 = static_cast<int>(std::lround((it.getY() - 0.5 * s - corner.y()) / res));
      const int z_first = static_cast<int>(std::lround((it.getZ() - 0.5 * s) / res));
      for (int y = std::max(0, y0); y < std::min(n, y0 + cells); ++y)
        for (int x = std::max(0, x0); x < std::min(n, x0 + cells); ++x)
          fn(col[static_cast<size_t>(y) * n + x], it->getOccupancy(), z_first, z_first + cells - 1);
    }
  };

  for_columns(*stereo_, (band_lo + 0.5) * res, (band_hi + 0.5) * res, [&](Column& c, double p, int z_first, int z_last) {
    int levels = std::min(z_last, band_hi) - std::max(z_first, band_lo) + 1;
    if (levels <= 0) return;
    c.known = true;
    if (laser_in_band && z_first <= laser_level && laser_level <= z_last) {
      c.stereo_laser = static_cast<float>(p);
      --levels;
    }
    // 5.5: columns are projected by multiplying probabilities. Free cells (OctoMap clamps them
    // near 0.12, not 0) are left out: ten of them would otherwise make a column look occupied.
    if (p > 0.5) c.log_free += levels * std::log1p(-p);
  });
  if (laser_in_band)
    for_columns(*laser_, laser_z, laser_z, [&](Column& c, double p, int, int) {
      c.laser = static_cast<float>(p);
      c.known = true;
    });
  for_columns(*floor_, 0.5 * res, 0.5 * res, [&](Column& c, double p, int, int) {
    if (p > 0.5) c.drop_off = true;
    c.known = true;
  });

  const double ws = 1.0 / (options_.stereo_sigma * options_.stereo_sigma);
  const double wl = 1.0 / (options_.laser_sigma * options_.laser_sigma);
  for (size_t i = 0; i < col.size(); ++i) {
    const Column& c = col[i];
    if (!c.known) continue;
    double log_free = c.log_free;
    double fused = -1;
    if (c.stereo_laser >= 0 && c.laser >= 0) fused = (ws * c.stereo_laser + wl * c.laser) / (ws + wl);
    else if (c.stereo_laser >= 0) fused = c.stereo_laser;
    else if (c.laser >= 0) fused = options_.laser_only_obstacles ? c.laser : std::min<double>(c.laser, 0.5);
    if (fused > 0.5) log_free += std::log1p(-fused);
    const double occupied = c.drop_off ? 1.0 : 1.0 - std::exp(log_free);
    g.cells[i] = static_cast<int8_t>(std::clamp<long>(std::lround(100.0 * occupied), 0, 100));
  }
  return g;
}

size_t ObstacleMap::leaf_count() const
{
  return stereo_->getNumLeafNodes() + laser_->getNumLeafNodes() + floor_->getNumLeafNodes();
}

size_t ObstacleMap::memory_bytes() const { return stereo_->memoryUsage() + laser_->memoryUsage() + floor_->memoryUsage(); }

}  // namespace rgnav::vision
