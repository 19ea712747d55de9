#include "building_raster.h"

#include <algorithm>

#include "building_furniture.h"
#include "sim/rng.h"

namespace rgnav::buildings {

namespace {

const cv::Point kSteps[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};

bool inside(const cv::Mat& m, cv::Point p) { return p.x >= 0 && p.y >= 0 && p.x < m.cols && p.y < m.rows; }

cv::Mat space_labels(const Building& b)
{
  cv::Mat labels(b.height, b.width, CV_32S, cv::Scalar(0));
  for (size_t i = 0; i < b.spaces.size(); ++i)
    for (const auto& r : b.spaces[i].rects)
      labels(cv::Rect(r.x0, r.y0, r.width(), r.height())).setTo(cv::Scalar(static_cast<double>(i + 1)));
  return labels;
}

// A wall of thickness t on the grid line between pixels `low` and low + 1 covers
// low - (t-1)/2 .. low + t/2 (the pixels the segmentation closes a doorway with).
int band_lo(int low, int t) { return low - (t - 1) / 2; }
int band_hi(int low, int t) { return low + t / 2; }

cv::Mat wall_mask(const Building& b, const cv::Mat& labels)
{
  cv::Mat walls(labels.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      const int la = labels.at<int32_t>(y, x);
      if (x + 1 < labels.cols) {
        const int lb = labels.at<int32_t>(y, x + 1);
        if (la != lb) {
          const int t = wall_thickness_px(b, la - 1, lb - 1);
          for (int c = std::max(0, band_lo(x, t)); c <= std::min(labels.cols - 1, band_hi(x, t)); ++c) walls.at<uint8_t>(y, c) = 255;
        }
      }
      if (y + 1 < labels.rows) {
        const int lb = labels.at<int32_t>(y + 1, x);
        if (la != lb) {
          const int t = wall_thickness_px(b, la - 1, lb - 1);
          for (int r = std::max(0, band_lo(y, t)); r <= std::min(labels.rows - 1, band_hi(y, t)); ++r) walls.at<uint8_t>(r, x) = 255;
        }
      }
    }
  return walls;
}

// True when freeing pixel p joins no two spaces: every free 4-neighbour has p's label.
bool frees_within_space(const cv::Mat& map, const cv::Mat& labels, cv::Point p)
{
  const int l = labels.at<int32_t>(p);
  if (l == 0) return false;
  for (const auto& s : kSteps) {
    const cv::Point q = p + s;
    if (inside(map, q) && map.at<uint8_t>(q) == kFree && labels.at<int32_t>(q) != l) return false;
  }
  return true;
}

// Scan-like wall faces: short bumps (1 px into the room) and notches (1 px into walls at least
// 3 px thick), a few per ten metres of wall, never opening a wall.
void add_wall_noise(const Building& b, const cv::Mat& labels, cv::Mat* map)
{
  sim::Rng rng = sim::Rng::derive(b.seed, 0x4015E);
  cv::Mat& m = *map;
  struct Face
  {
    cv::Point wall, dir;   // dir: from the wall pixel to the free one
  };
  std::vector<Face> faces;
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x)
      if (m.at<uint8_t>(y, x) == kWall)
        for (const auto& s : kSteps) {
          const cv::Point q = cv::Point(x, y) + s;
          if (inside(m, q) && m.at<uint8_t>(q) == kFree) faces.push_back({{x, y}, s});
        }
  for (const Face& f : faces) {
    const double u = rng.uniform();
    if (u >= 0.012) continue;
    const bool bump = u < 0.007;
    const cv::Point along(f.dir.y, f.dir.x);
    const int run = 2 + static_cast<int>(rng.next_u64() % 7);
    for (int k = 0; k < run; ++k) {
      const cv::Point p = f.wall + k * along;
      if (bump) {
        // Only onto the same face: wall behind, free in front.
        const cv::Point q = p + f.dir;
        if (inside(m, q) && m.at<uint8_t>(p) == kWall && m.at<uint8_t>(q) == kFree) m.at<uint8_t>(q) = kWall;
        continue;
      }
      const cv::Point q = p + f.dir, b1 = p - f.dir, b2 = p - 2 * f.dir;
      if (!inside(m, q) || !inside(m, b2) || m.at<uint8_t>(q) != kFree) break;
      if (m.at<uint8_t>(p) != kWall || m.at<uint8_t>(b1) != kWall || m.at<uint8_t>(b2) != kWall) break;
      if (labels.at<int32_t>(p) != labels.at<int32_t>(q) || !frees_within_space(m, labels, p)) break;
      m.at<uint8_t>(p) = kFree;
    }
  }
}

// The opening of a doorway: across the whole wall band and a pixel beyond (a bump in front of
// the door would narrow it), along its span.
cv::Rect opening(const Building& b, const Doorway& d, const cv::Size& size)
{
  const int t = wall_thickness_px(b, d.a, d.b);
  const int lo = band_lo(d.line - 1, t) - 1, hi = band_hi(d.line - 1, t) + 1;
  const cv::Rect r = d.vertical ? cv::Rect(lo, d.from, hi - lo + 1, d.width_px()) : cv::Rect(d.from, lo, d.width_px(), hi - lo + 1);
  return r & cv::Rect(cv::Point(0, 0), size);
}

}  // namespace

cv::Rect closing_line(const Building& b, const Doorway& d)
{
  const int t = wall_thickness_px(b, d.a, d.b);
  const int lo = band_lo(d.line - 1, t);
  return d.vertical ? cv::Rect(lo, d.from, t, d.width_px()) : cv::Rect(d.from, lo, d.width_px(), t);
}

BuildingImages render_building(const Building& b)
{
  BuildingImages out;
  out.labels = space_labels(b);
  out.map = cv::Mat(out.labels.size(), CV_8U, cv::Scalar(kOutside));
  out.map.setTo(cv::Scalar(kFree), out.labels > 0);
  out.map.setTo(cv::Scalar(kWall), wall_mask(b, out.labels));
  add_wall_noise(b, out.labels, &out.map);
  for (const auto& d : b.doorways) {
    const cv::Rect r = opening(b, d, out.map.size());
    cv::Mat cut = out.map(r);
    cut.setTo(cv::Scalar(kFree), out.labels(r) > 0);
  }
  out.segmentation = out.map.clone();
  for (const auto& d : b.doorways) out.segmentation(closing_line(b, d)).setTo(cv::Scalar(kWall));
  out.furnished = furnish(b, out.labels, out.map);
  return out;
}

}  // namespace rgnav::buildings
