#include "ground_truth.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>

namespace rgnav::rgmap_pipeline {

using Eigen::Vector2d;
namespace fs = std::filesystem;

Vector2d TruthGateway::center() const
{
  Vector2d c = Vector2d::Zero();
  for (const auto& p : points) c += p;
  return points.empty() ? c : c / static_cast<double>(points.size());
}

int32_t GroundTruth::label_of(const std::string& room) const
{
  for (size_t i = 0; i < room_names.size(); ++i)
    if (room_names[i] == room) return static_cast<int32_t>(i + 1);
  return 0;
}

namespace {

// The <stem>_gt_segmentation.png beside an IPA map image (as sim::load_world finds it).
std::string segmentation_of(const std::string& source)
{
  const fs::path p(source);
  if (p.extension() != ".png") return "";
  std::string stem = p.stem().string();
  const std::string furn = "_furnitures";
  if (stem.size() > furn.size() && stem.compare(stem.size() - furn.size(), furn.size(), furn) == 0)
    stem.resize(stem.size() - furn.size());
  const fs::path gt = p.parent_path() / (stem + "_gt_segmentation.png");
  return fs::exists(gt) ? gt.string() : "";
}

bool segments_cross(const Vector2d& p, const Vector2d& q, const Vector2d& a, const Vector2d& b)
{
  auto cross = [](const Vector2d& u, const Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(q - p, a - p), d2 = cross(q - p, b - p);
  const double d3 = cross(b - a, p - a), d4 = cross(b - a, q - a);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

}  // namespace

GroundTruth ground_truth_of(const sim::World& world, double resolution)
{
  GroundTruth t;
  Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& r : world.regions)
    for (const auto& p : r.polygon) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (world.regions.empty()) throw std::runtime_error(world.source + ": no labelled rooms (ground truth)");
  lo -= Vector2d(resolution, resolution);
  hi += Vector2d(resolution, resolution);
  const int w = static_cast<int>(std::ceil((hi.x() - lo.x()) / resolution));
  const int h = static_cast<int>(std::ceil((hi.y() - lo.y()) / resolution));
  t.rooms = LabelGrid(w, h, resolution, lo);
  // Polygons filled in cell coordinates (y up is just another row order for fillPoly); a cell
  // belongs to a room when its centre is inside, up to fillPoly's rasterisation.
  cv::Mat labels(h, w, CV_32S, cv::Scalar(0));
  for (size_t k = 0; k < world.regions.size(); ++k) {
    t.room_names.push_back(world.regions[k].name);
    std::vector<cv::Point> poly;
    constexpr int kShift = 8;
    for (const auto& p : world.regions[k].polygon) {
      const Vector2d c = (p - lo) / resolution - Vector2d(0.5, 0.5);
      poly.emplace_back(static_cast<int>(std::lround(c.x() * (1 << kShift))), static_cast<int>(std::lround(c.y() * (1 << kShift))));
    }
    cv::fillPoly(labels, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(static_cast<double>(k + 1)), cv::LINE_8, kShift);
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) t.rooms.at(x, y) = labels.at<int32_t>(y, x);

  if (!world.gateways.empty()) {
    for (const auto& g : world.gateways) {
      if (g.points.size() < 2) continue;
      TruthGateway tg;
      tg.name = g.name;
      tg.points = g.points;
      for (const auto& r : g.regions)
        if (const int32_t l = t.label_of(r)) tg.rooms.push_back(l);
      const Vector2d c = tg.center();
      const int cx = static_cast<int>(std::floor((c.x() - t.rooms.origin.x()) / resolution));
      const int cy = static_cast<int>(std::floor((c.y() - t.rooms.origin.y()) / resolution));
      if (cx >= 0 && cy >= 0 && cx < t.rooms.width && cy < t.rooms.height) {
        const int32_t inside = t.rooms.at(cx, cy);
        if (inside > 0 && std::find(tg.rooms.begin(), tg.rooms.end(), inside) == tg.rooms.end()) tg.rooms.push_back(inside);
      }
      t.gateways.push_back(tg);
    }
  } else if (const std::string seg = segmentation_of(world.source); !seg.empty()) {
    t.gateways = gateways_from_images(world.source, seg, 0.05, t.rooms);
  }
  return t;
}

std::vector<TruthGateway> gateways_from_images(const std::string& map_png, const std::string& segmentation_png,
                                               double resolution, const LabelGrid& rooms)
{
  const cv::Mat map = cv::imread(map_png, cv::IMREAD_GRAYSCALE);
  const cv::Mat seg = cv::imread(segmentation_png, cv::IMREAD_GRAYSCALE);
  if (map.empty() || seg.empty() || map.size() != seg.size())
    throw std::runtime_error(map_png + " / " + segmentation_png + ": unreadable or sizes differ");
  const cv::Mat door = (map > 250) & (seg <= 250);
  cv::Mat comp;
  const int n = cv::connectedComponents(door, comp, 8, CV_32S);
  const int rows = map.rows;
  // Pixel (row, col) centre in the world (sim/image_world.h: origin 0 at the lower-left corner).
  auto world_of = [&](int r, int c) { return Vector2d((c + 0.5) * resolution, (rows - r - 0.5) * resolution); };
  auto room_at = [&](const Vector2d& p) -> int32_t {
    const int cx = static_cast<int>(std::floor((p.x() - rooms.origin.x()) / rooms.resolution));
    const int cy = static_cast<int>(std::floor((p.y() - rooms.origin.y()) / rooms.resolution));
    if (cx < 0 || cy < 0 || cx >= rooms.width || cy >= rooms.height) return 0;
    return rooms.at(cx, cy);
  };
  std::vector<std::vector<Vector2d>> pixels(static_cast<size_t>(n));
  std::vector<std::map<int32_t, int>> touch(static_cast<size_t>(n));
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < map.cols; ++c) {
      const int k = comp.at<int32_t>(r, c);
      if (k == 0) continue;
      const Vector2d p = world_of(r, c);
      pixels[static_cast<size_t>(k)].push_back(p);
      // Rooms within two pixels on either side of the doorway line.
      for (int dr = -2; dr <= 2; ++dr)
        for (int dc = -2; dc <= 2; ++dc) {
          const int32_t l = room_at(p + resolution * Vector2d(dc, -dr));
          if (l > 0) ++touch[static_cast<size_t>(k)][l];
        }
    }
  std::vector<TruthGateway> out;
  for (int k = 1; k < n; ++k) {
    const auto& px = pixels[static_cast<size_t>(k)];
    const auto& t = touch[static_cast<size_t>(k)];
    if (t.size() < 2 || px.size() < 3) continue;   // not between two rooms: a wall gap or noise
    // The two rooms it touches most.
    std::vector<std::pair<int, int32_t>> by_count;
    for (const auto& [l, cnt] : t) by_count.push_back({-cnt, l});
    std::sort(by_count.begin(), by_count.end());
    // Ends: extremes along the principal axis of the run's pixels.
    Vector2d m = Vector2d::Zero();
    for (const auto& p : px) m += p;
    m /= static_cast<double>(px.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const auto& p : px) cov += (p - m) * (p - m).transpose();
    const double ang = 0.5 * std::atan2(2 * cov(0, 1), cov(0, 0) - cov(1, 1));
    const Vector2d axis(std::cos(ang), std::sin(ang));
    double lo = 0, hi = 0;
    for (const auto& p : px) lo = std::min(lo, (p - m).dot(axis)), hi = std::max(hi, (p - m).dot(axis));
    TruthGateway g;
    g.name = "doorway_" + std::to_string(out.size() + 1);
    g.points = {m + (lo - 0.5 * resolution) * axis, m + (hi + 0.5 * resolution) * axis};
    g.rooms = {std::min(by_count[0].second, by_count[1].second), std::max(by_count[0].second, by_count[1].second)};
    out.push_back(g);
  }
  return out;
}

Graph truth_graph(const GroundTruth& truth, const std::vector<int32_t>& rooms)
{
  Graph g;
  const std::set<int32_t> keep(rooms.begin(), rooms.end());
  for (int32_t r : rooms) g.nodes.insert(r);
  for (const auto& gw : truth.gateways)
    for (size_t i = 0; i < gw.rooms.size(); ++i)
      for (size_t j = i + 1; j < gw.rooms.size(); ++j)
        if (keep.count(gw.rooms[i]) && keep.count(gw.rooms[j])) g.add_edge(gw.rooms[i], gw.rooms[j]);
  return g;
}

std::vector<int> crossed_gateways(const GroundTruth& truth, const std::vector<Vector2d>& path)
{
  std::vector<int> out;
  for (size_t k = 0; k < truth.gateways.size(); ++k) {
    const auto& pts = truth.gateways[k].points;
    // Edges: the line of a 2-point gateway, the closed outline of a crossing.
    std::vector<std::pair<Vector2d, Vector2d>> edges;
    for (size_t i = 0; i + 1 < pts.size(); ++i) edges.push_back({pts[i], pts[i + 1]});
    if (pts.size() > 2) edges.push_back({pts.back(), pts.front()});
    bool crossed = false;
    for (const auto& [a, b] : edges) {
      // Slightly longer than the opening, so a pass right at a door post still counts.
      const Vector2d d = (b - a).normalized() * 0.05;
      for (size_t i = 0; i + 1 < path.size() && !crossed; ++i) crossed = segments_cross(path[i], path[i + 1], a - d, b + d);
    }
    if (crossed) out.push_back(static_cast<int>(k));
  }
  return out;
}

}  // namespace rgnav::rgmap_pipeline
