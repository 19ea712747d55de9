#include "sim/image_world.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "config/config.h"
#include "config/file_checks.h"

namespace rgnav::sim {

namespace {

// The image as 8-bit grey; throws ConfigError naming the file when it is empty, cut off
// (a decoder would fill the missing rows) or cannot be decoded.
cv::Mat read_gray(const std::string& file)
{
  const std::string bytes = config::read_image_file(file, "occupancy image");
  const cv::Mat raw(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data()));
  cv::Mat gray = cv::imdecode(raw, cv::IMREAD_GRAYSCALE);
  if (gray.empty()) throw config::ConfigError(file + ": cannot decode occupancy image");
  return gray;
}

// 255 where the pixel is free, 0 elsewhere.
cv::Mat free_mask(const OccupancyImage& image, const std::string& file)
{
  const cv::Mat gray = read_gray(file);
  cv::Mat mask(gray.size(), CV_8U);
  for (int r = 0; r < gray.rows; ++r)
    for (int c = 0; c < gray.cols; ++c) {
      const int v = gray.at<uint8_t>(r, c);
      const double p = image.negate ? v / 255.0 : (255 - v) / 255.0;
      mask.at<uint8_t>(r, c) = p < image.free_thresh ? 255 : 0;
    }
  return mask;
}

// Pixel corner (col, row) in the image -> world; rows grow downwards in the image.
Vec2 corner_to_world(const OccupancyImage& im, int rows, double col, double row)
{
  return {im.origin.x() + col * im.resolution, im.origin.y() + (rows - row) * im.resolution};
}

}  // namespace

void add_boundary_walls(const cv::Mat& mask, double resolution, const Vec2& origin, double height, World* world)
{
  const int rows = mask.rows, cols = mask.cols;
  auto is_free = [&](int r, int c) {
    return r >= 0 && c >= 0 && r < rows && c < cols && mask.at<uint8_t>(r, c) != 0;
  };
  auto add = [&](double c0, double r0, double c1, double r1) {
    Wall w;
    w.a = {origin.x() + c0 * resolution, origin.y() + (rows - r0) * resolution};
    w.b = {origin.x() + c1 * resolution, origin.y() + (rows - r1) * resolution};
    w.z_max = height;
    world->walls.push_back(w);
  };
  // Horizontal boundaries: between row r-1 and row r, merged into runs along the row.
  for (int r = 0; r <= rows; ++r) {
    int run_start = -1;
    for (int c = 0; c <= cols; ++c) {
      const bool edge = c < cols && is_free(r - 1, c) != is_free(r, c);
      if (edge && run_start < 0) run_start = c;
      if (!edge && run_start >= 0) {
        add(run_start, r, c, r);
        run_start = -1;
      }
    }
  }
  // Vertical boundaries: between column c-1 and column c, merged along the column.
  for (int c = 0; c <= cols; ++c) {
    int run_start = -1;
    for (int r = 0; r <= rows; ++r) {
      const bool edge = r < rows && is_free(r, c - 1) != is_free(r, c);
      if (edge && run_start < 0) run_start = r;
      if (!edge && run_start >= 0) {
        add(c, run_start, c, r);
        run_start = -1;
      }
    }
  }
}

Pose2 add_occupancy_image(const OccupancyImage& image, World* world)
{
  const cv::Mat mask = free_mask(image, image.file);
  const int rows = mask.rows, cols = mask.cols;
  add_boundary_walls(mask, image.resolution, image.origin, image.wall_height, world);
  if (!image.gt_segmentation.empty()) {
    auto rooms = rooms_from_segmentation(image);
    const cv::Mat labels = read_gray(image.gt_segmentation);
    if (labels.rows != rows || labels.cols != cols)
      throw config::ConfigError(image.gt_segmentation + ": size differs from " + image.file);
    for (auto& r : rooms) world->regions.push_back(std::move(r));
  }
  cv::Mat dist;
  cv::distanceTransform(mask, dist, cv::DIST_L2, 5);
  // Furniture can wall off a pocket of wide free space (furnished building maps):
  // a start there reaches no room. Start in the largest area a robot can drive around in.
  const cv::Mat drivable = dist > static_cast<float>(kStartAreaClearanceM / image.resolution);
  cv::Mat areas, stats, centroids;
  const int n = cv::connectedComponentsWithStats(drivable, areas, stats, centroids, 8, CV_32S);
  int largest = 0;
  for (int k = 1; k < n; ++k)
    if (largest == 0 || stats.at<int>(k, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA)) largest = k;
  cv::Point best;
  float best_d = -1.f;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if ((largest == 0 || areas.at<int>(r, c) == largest) && dist.at<float>(r, c) > best_d) {
        best_d = dist.at<float>(r, c);
        best = {c, r};
      }
  const Vec2 p = corner_to_world(image, rows, best.x + 0.5, best.y + 0.5);
  return {p.x(), p.y(), 0.0};
}

std::vector<Region> rooms_from_segmentation(const OccupancyImage& image)
{
  const cv::Mat mask = free_mask(image, image.gt_segmentation);
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 4, CV_32S);
  const double min_pixels = image.min_room_area / (image.resolution * image.resolution);
  std::vector<Region> rooms;
  // Component labels follow row-major order of first pixels: a deterministic naming.
  for (int k = 1; k < n; ++k) {
    if (stats.at<int>(k, cv::CC_STAT_AREA) < min_pixels) continue;
    const cv::Mat component = labels == k;
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(component, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    if (contours.empty()) continue;
    size_t largest = 0;
    for (size_t i = 1; i < contours.size(); ++i)
      if (contours[i].size() > contours[largest].size()) largest = i;
    std::vector<cv::Point> approx;
    cv::approxPolyDP(contours[largest], approx, 1.0, true);
    Region room;
    room.name = "room_" + std::to_string(rooms.size() + 1);
    room.kind = RegionKind::kRoom;
    // Contour points are pixel indices; their centres are at +0.5.
    for (const auto& p : approx) room.polygon.push_back(corner_to_world(image, mask.rows, p.x + 0.5, p.y + 0.5));
    if (room.polygon.size() >= 3) rooms.push_back(std::move(room));
  }
  return rooms;
}

}  // namespace rgnav::sim
