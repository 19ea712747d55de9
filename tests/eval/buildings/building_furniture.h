// Furniture of a generated building's furnished variant, as the IPA *_furnitures.png maps draw
// it: tables and chairs by their legs only (what a laser at knee height sees), cabinets and
// shelves along walls, round bins and plants in corners, small boxes of clutter; halls get rows
// of tables. Nothing stands in front of a doorway. Furniture that would keep the robot out of a
// room it could enter in the plain map is left out (first in that room and its neighbours).
#pragma once

#include <opencv2/core.hpp>

#include "building_layout.h"

namespace rgnav::buildings {

// `map` with furniture drawn in (CV_8U, furniture 0 or 200: not free); labels as
// BuildingImages::labels.
cv::Mat furnish(const Building& building, const cv::Mat& labels, const cv::Mat& map);

}  // namespace rgnav::buildings
