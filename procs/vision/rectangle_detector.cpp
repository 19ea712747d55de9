#include "vision/rectangle_detector.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::vision {
namespace {

struct Sample
{
  Eigen::Vector2d pixel;  // full resolution
  double disparity;       // [px] at full resolution
  int side;               // 0..3
};

// Valid disparities just inside and just outside the quadrangle's sides: a rectangle's plane
// holds one or both (a whiteboard on a wall: both; a door frame: the wall outside, the room
// beyond seen through it inside; a box's face: the inside).
std::vector<Sample> side_samples(const Quadrangle& q, const cv::Mat& disp16, int scale, const RectangleDetectorOptions& o)
{
  std::vector<Sample> out;
  const Eigen::Vector2d centre = (q[0] + q[1] + q[2] + q[3]) / 4.0;
  for (int s = 0; s < 4; ++s) {
    const Eigen::Vector2d a = q[s], b = q[(s + 1) % 4];
    Eigen::Vector2d in(-(b - a).y(), (b - a).x());
    if (in.norm() < 1e-9) continue;
    in.normalize();
    if (in.dot(centre - a) < 0) in = -in;
    for (int k = 0; k < o.samples_per_side; ++k) {
      const double t = (k + 0.5) / o.samples_per_side;
      for (const double offset : {o.inset_px, -o.inset_px}) {
        const Eigen::Vector2d p = a + t * (b - a) + offset * in;
        const int x = static_cast<int>(std::lround(p.x() / scale)), y = static_cast<int>(std::lround(p.y() / scale));
        if (x < 0 || y < 0 || x >= disp16.cols || y >= disp16.rows) continue;
        const int16_t d = disp16.at<int16_t>(y, x);
        if (d <= 0) continue;
        out.push_back({p, d / 16.0 * scale, s});
      }
    }
  }
  return out;
}

// Mean grey level inside the quadrangle shrunk toward its centre (its edges and frame left out):
// what the object shows (a whiteboard is white), -1 when nothing of it is in the image.
double grey_inside(const cv::Mat& gray, const Quadrangle& q)
{
  const Eigen::Vector2d centre = (q[0] + q[1] + q[2] + q[3]) / 4.0;
  std::vector<cv::Point> poly;
  for (const auto& c : q) {
    const Eigen::Vector2d p = centre + 0.8 * (c - centre);
    poly.emplace_back(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
  }
  const cv::Rect box = cv::boundingRect(poly) & cv::Rect(0, 0, gray.cols, gray.rows);
  if (box.area() <= 0) return -1.0;
  cv::Mat mask = cv::Mat::zeros(box.size(), CV_8U);
  for (auto& p : poly) p -= box.tl();
  cv::fillConvexPoly(mask, poly, cv::Scalar(255));
  if (cv::countNonZero(mask) == 0) return -1.0;
  return cv::mean(gray(box), mask)[0];
}

// The disparity the plane n·X = d predicts at a pixel (0: the ray misses it in front).
double predicted_disparity(const Pinhole& camera, const Eigen::Vector3d& n, double d, const Eigen::Vector2d& pixel,
                           double focal_baseline)
{
  const double denom = n.dot(camera.ray(pixel));
  if (std::fabs(denom) < 1e-9) return 0.0;
  const double z = d / denom;  // the ray has z = 1: its multiple is the depth
  return z > 0.0 ? focal_baseline / z : 0.0;
}

}  // namespace

std::vector<DetectedRectangle> detect_rectangles(const cv::Mat& gray, const cv::Mat& disparity16, int disparity_scale,
                                                 const Pinhole& camera, const RectangleDetectorOptions& o)
{
  std::vector<DetectedRectangle> out;
  if (gray.empty() || disparity16.empty() || disparity16.type() != CV_16S || disparity_scale < 1) return out;
  const auto quads = group_quadrangles(merge_segments(detect_segments(gray), o.quadrangles), o.quadrangles);
  const double fb = o.refine.focal_baseline;
  for (const auto& q : quads) {
    const auto n = plane_normal(q, camera);
    if (!n) continue;
    const auto samples = side_samples(q, disparity16, disparity_scale, o);
    if (static_cast<int>(samples.size()) < o.min_valid_samples) continue;
    // Each sample's point, Z = f B / d along its pixel's ray, gives one plane offset n·X. The
    // sides are the object's edges, and an object hides what lies behind it: its plane is the
    // nearest offset that many samples agree with (the diss.'s average over measured corners,
    // kept from the samples off the plane — the room seen through a door, whose far wall has
    // the same normal and often more samples).
    const double fbl = fb;
    auto on_plane = [&](double d, const Sample& s) {
      const double p = predicted_disparity(camera, *n, d, s.pixel, fbl);
      return p > 0.0 && std::fabs(p - s.disparity) <= o.plane_tolerance_px;
    };
    std::vector<std::pair<double, int>> candidates;  // offset, samples agreeing
    int most = 0;
    for (const auto& c : samples) {
      const double dc = n->dot(camera.ray(c.pixel) * (fb / c.disparity));
      if (dc >= 0.0) continue;
      int agree = 0;
      for (const auto& s : samples) agree += on_plane(dc, s);
      candidates.emplace_back(dc, agree);
      most = std::max(most, agree);
    }
    if (most < o.min_valid_samples / 2) continue;
    double d = -std::numeric_limits<double>::infinity();
    for (const auto& [dc, agree] : candidates)
      if (10 * agree >= 7 * most && dc > d) d = dc;  // nearest: the offset nearest zero
    // The nearest candidate lies at the near edge of its band of agreeing samples: the median
    // offset of the samples it agrees with centres it (twice: the band moves with it).
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<double> inliers;
      for (const auto& s : samples)
        if (on_plane(d, s)) inliers.push_back(n->dot(camera.ray(s.pixel) * (fb / s.disparity)));
      if (inliers.empty()) break;
      std::nth_element(inliers.begin(), inliers.begin() + static_cast<long>(inliers.size() / 2), inliers.end());
      d = inliers[inliers.size() / 2];
    }
    const auto first = intersect_plane(q, camera, *n, d);
    if (!first) continue;
    std::array<std::optional<Eigen::Vector3d>, 4> corners;
    for (int i = 0; i < 4; ++i) corners[i] = first->corners[i];
    auto rect = refine_rectangle(q, camera, *first, corners, o.refine);
    if (!rect) continue;
    // Support: every side has samples on the refined plane (on one of its two sides at least),
    // and enough of all samples are.
    const Eigen::Vector3d& nn = rect->normal;
    const double dd = nn.dot(rect->corners[0]);
    std::array<int, 4> side_on{0, 0, 0, 0}, side_all{0, 0, 0, 0};
    int on = 0;
    for (const auto& s : samples) {
      const double p = predicted_disparity(camera, nn, dd, s.pixel, fb);
      const bool hit = p > 0.0 && std::fabs(p - s.disparity) <= o.plane_tolerance_px;
      on += hit;
      side_on[static_cast<size_t>(s.side)] += hit;
      ++side_all[static_cast<size_t>(s.side)];
    }
    const double support = static_cast<double>(on) / static_cast<double>(samples.size());
    // A side seen along a receding face (a door jamb's inside, at an angle) may have none.
    int sides_on = 0;
    for (int k = 0; k < 4; ++k) sides_on += side_on[k] >= std::max(2, side_all[k] / 4);
    if (support < o.min_support || sides_on < 3) continue;
    if (std::min(rect->side_a, rect->side_b) < o.min_side_m || std::max(rect->side_a, rect->side_b) > o.max_side_m) continue;
    out.push_back({q, *rect, support, grey_inside(gray, q)});
  }
  return out;
}

}  // namespace rgnav::vision
