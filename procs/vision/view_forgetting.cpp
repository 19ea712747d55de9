#include "vision/view_forgetting.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::vision {

namespace {

// A pause between frames (the process stalled, the head stopped sending) is not time spent
// looking: at most this much counts per frame.
constexpr double kMaxFrameGapS = 0.5;

}  // namespace

FrameView::FrameView(const StereoView& view, const Eigen::Isometry3d& tree_from_base, const std::vector<Eigen::Vector3f>& points,
                     double margin_base, double depth_sigma_per_m2)
    : view_(view),
      camera_from_tree_(view.base_from_camera.inverse() * tree_from_base.inverse()),
      bins_x_((view.width + kBin - 1) / kBin),
      bins_y_((view.height + kBin - 1) / kBin),
      nearest_(static_cast<size_t>(std::max(0, bins_x_ * bins_y_)), std::numeric_limits<float>::infinity()),
      margin_base_(margin_base),
      depth_sigma_per_m2_(depth_sigma_per_m2)
{
  const Eigen::Isometry3d camera_from_base = view.base_from_camera.inverse();
  for (const Eigen::Vector3f& p : points) {
    const Eigen::Vector3d c = camera_from_base * p.cast<double>();
    if (c.z() <= 0) continue;
    const int bx = static_cast<int>(std::floor((view.focal * c.x() / c.z() + view.cx) / kBin));
    const int by = static_cast<int>(std::floor((view.focal * c.y() / c.z() + view.cy) / kBin));
    if (bx < 0 || by < 0 || bx >= bins_x_ || by >= bins_y_) continue;
    float& n = nearest_[static_cast<size_t>(by) * static_cast<size_t>(bins_x_) + static_cast<size_t>(bx)];
    n = std::min(n, static_cast<float>(c.z()));
  }
}

bool FrameView::sees(const Eigen::Vector3d& tree_point, double size) const
{
  const Eigen::Vector3d c = camera_from_tree_ * tree_point;
  // The whole voxel within the depth range (its half diagonal on either side of its centre).
  const double half = 0.87 * size;
  if (c.z() - half < view_.min_depth || c.z() + half > view_.max_depth) return false;
  const double u = view_.focal * c.x() / c.z() + view_.cx;
  const double v = view_.focal * c.y() / c.z() + view_.cy;
  const double r = view_.focal * half / (c.z() - half);   // [px] the voxel's half extent in the image, at most
  if (u - r < 0 || v - r < 0 || u + r > view_.width || v + r > view_.height) return false;
  // Not hidden: no point measured clearly nearer anywhere the voxel projects to.
  const double hidden_below = c.z() - margin_base_ - depth_sigma_per_m2_ * c.z() * c.z();
  const int bx0 = static_cast<int>((u - r) / kBin), bx1 = std::min(bins_x_ - 1, static_cast<int>((u + r) / kBin));
  const int by0 = static_cast<int>((v - r) / kBin), by1 = std::min(bins_y_ - 1, static_cast<int>((v + r) / kBin));
  for (int by = by0; by <= by1; ++by)
    for (int bx = bx0; bx <= bx1; ++bx)
      if (nearest_[static_cast<size_t>(by) * static_cast<size_t>(bins_x_) + static_cast<size_t>(bx)] < hidden_below) return false;
  return true;
}

int64_t ViewForgetting::update(octomap::OcTree& tree, const octomap::KeySet& hit, const FrameView& view, int64_t utime)
{
  const double dt = last_utime_ > 0 && utime > last_utime_ ? std::min(kMaxFrameGapS, 1e-6 * static_cast<double>(utime - last_utime_)) : 0.0;
  last_utime_ = utime;
  int64_t forgotten = 0;
  const double size = tree.getResolution();
  for (auto it = cells_.begin(); it != cells_.end();) {
    if (hit.count(it->first)) {
      it->second = 0;
      ++it;
      continue;
    }
    octomap::OcTreeNode* node = tree.search(it->first);
    if (node == nullptr || node->getLogOdds() <= 0.f) {   // seen free since (a ray passed): nothing to forget
      it = cells_.erase(it);
      continue;
    }
    const octomap::point3d p = tree.keyToCoord(it->first);
    if (view.sees(Eigen::Vector3d(p.x(), p.y(), p.z()), size)) it->second += dt;
    if (it->second < forget_after_s_) {
      ++it;
      continue;
    }
    // Back to unknown (log-odds 0): neither an obstacle nor seen free.
    tree.setNodeValue(it->first, 0.f);
    ++forgotten;
    it = cells_.erase(it);
  }
  for (const auto& k : hit) cells_.emplace(k, 0.0);
  return forgotten;
}

}  // namespace rgnav::vision
