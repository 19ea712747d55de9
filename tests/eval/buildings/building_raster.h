// A generated building (building_layout.h) drawn as the IPA building maps are (Bormann et al.
// 2016, 0.05 m/pixel): the map (white free, black walls, grey outside), its furnished variant
// and the ground-truth segmentation (the map with a black bar closing every doorway, so that
// flood filling its free pixels gives the rooms). Walls are 1-4 px thick with scan-like noise
// (bumps and notches on their faces that never open a wall).
#pragma once

#include <opencv2/core.hpp>

#include "building_layout.h"

namespace rgnav::buildings {

struct BuildingImages
{
  cv::Mat map;            // CV_8U: 255 free, 0 wall, 205 outside the building
  cv::Mat furnished;      // the map with furniture (building_furniture.h)
  cv::Mat segmentation;   // the map with every doorway closed on the wall line
  cv::Mat labels;         // CV_32S: space index + 1 per pixel of its rectangles, 0 outside
};

constexpr uint8_t kFree = 255, kWall = 0, kOutside = 205;

BuildingImages render_building(const Building& building);

// The pixels that close doorway d in the segmentation: its opening across the wall's thickness
// (as the IPA segmentations close doorways), so the rooms on either side border it directly.
cv::Rect closing_line(const Building& building, const Doorway& d);

}  // namespace rgnav::buildings
