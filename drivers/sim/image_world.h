// Worlds from occupancy images: ROS map_server maps (PGM/PNG + YAML) and the IPA room
// segmentation maps (PNG, 0.05 m/pixel). The free/blocked boundary of the image becomes
// vertical walls of a default height; ground-truth rooms come from a segmentation image in
// which black lines close each doorway, by flood filling its free components.
#pragma once

#include <string>
#include <vector>

#include "sim/world.h"

namespace cv { class Mat; }

namespace rgnav::sim {

struct OccupancyImage
{
  std::string file;
  double resolution = 0.05;   // [m/pixel]
  Vec2 origin{0, 0};          // world pose of the lower-left pixel corner (ROS convention)
  bool negate = false;
  // ROS semantics: p = (255 - v) / 255 (negate: v / 255). Free iff p < free_thresh;
  // everything else (occupied or unknown) is a wall: the simulator never drives into
  // unknown space. The default 0.018 makes only pixels >= 251 free (IPA: "> 250").
  double free_thresh = 0.018;
  double wall_height = 2.5;   // [m]
  std::string gt_segmentation;  // optional label image (same size and frame)
  double min_room_area = 1.0;   // [m^2] smaller free components of the label image are noise
};

// Adds the walls (and, with gt_segmentation, the rooms) of the image to `world`. Returns a
// start pose: the free pixel farthest from any wall (first in scan order on ties, so the
// result is deterministic) within the largest connected area of pixels more than
// kStartAreaClearanceM from walls (a robot-sized body can drive around in it). Throws
// config::ConfigError naming the file when an image cannot be read or the sizes differ.
inline constexpr double kStartAreaClearanceM = 0.4;

Pose2 add_occupancy_image(const OccupancyImage& image, World* world);

// Walls along the boundary between free (non-zero) and blocked pixels of a CV_8U mask whose
// lower-left pixel corner is at `origin`; runs along rows and columns are merged into one wall.
void add_boundary_walls(const cv::Mat& free_mask, double resolution, const Vec2& origin, double height, World* world);

// The rooms of a ground-truth segmentation image, named room_1.. in row-major discovery order.
std::vector<Region> rooms_from_segmentation(const OccupancyImage& image);

}  // namespace rgnav::sim
