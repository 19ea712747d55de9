#include "procs/rg_kernel/freespace_trim.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <limits>
#include <set>

namespace rgnav::rg_kernel {

std::vector<Cell> trim_seen_through(const std::vector<Cell>& cells, const std::vector<Cell>& origins, int radius)
{
  if (cells.empty() || radius <= 0) return cells;
  int32_t x0 = std::numeric_limits<int32_t>::max(), y0 = x0, x1 = std::numeric_limits<int32_t>::min(), y1 = x1;
  for (const auto& [x, y] : cells) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  // A border of `radius` cells, so that the erosion treats the grid's edge as occupied.
  const int pad = radius + 1;
  cv::Mat free = cv::Mat::zeros(y1 - y0 + 1 + 2 * pad, x1 - x0 + 1 + 2 * pad, CV_8U);
  for (const auto& [x, y] : cells) free.at<uint8_t>(y - y0 + pad, x - x0 + pad) = 255;
  const cv::Mat disk = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1));
  // Where the disk fits: a passage narrower than it leaves a gap between the two sides' centres
  // (an opening would not: the disks of both sides reach into a door through a thin wall).
  cv::Mat centres, labels;
  cv::erode(free, centres, disk);
  cv::connectedComponents(centres, labels, 8, CV_32S);
  // The components a robot position is the region's by: the nearest centre within twice the
  // radius (what the dilations below give back), e.g. a position beside a wall or in a doorway.
  const int reach = 2 * radius;
  std::set<int32_t> kept;
  for (const auto& [ox, oy] : origins) {
    const int cx = ox - x0 + pad, cy = oy - y0 + pad;
    int best = 0, best_d2 = reach * reach + 1;
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        const int x = cx + dx, y = cy + dy, d2 = dx * dx + dy * dy;
        if (x < 0 || y < 0 || x >= labels.cols || y >= labels.rows || d2 >= best_d2) continue;
        if (const int l = labels.at<int32_t>(y, x); l > 0) best = l, best_d2 = d2;
      }
    if (best > 0) kept.insert(best);
  }
  if (kept.empty()) return cells;
  cv::Mat own = cv::Mat::zeros(free.size(), CV_8U);
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x)
      if (kept.count(labels.at<int32_t>(y, x))) own.at<uint8_t>(y, x) = 255;
  // Back to the disks (the opening of the region's own space), and once more: corners, the
  // border along walls, the near half of its doors.
  cv::dilate(own, own, disk, cv::Point(-1, -1), 2);
  std::vector<Cell> out;
  out.reserve(cells.size());
  for (const auto& c : cells)
    if (own.at<uint8_t>(c.second - y0 + pad, c.first - x0 + pad)) out.push_back(c);
  return out;
}

}  // namespace rgnav::rg_kernel
