#include "building_reach.h"

#include <opencv2/imgproc.hpp>

#include "building_layout.h"

namespace rgnav::buildings {

std::vector<int> spaces_out_of_reach(const cv::Mat& map, const cv::Mat& labels, int spaces, double clearance_m)
{
  cv::Mat dist;
  cv::distanceTransform(map == 255, dist, cv::DIST_L2, 5);
  const cv::Mat drivable = dist > static_cast<float>(clearance_m / kMetresPerPixel);
  cv::Mat areas, stats, centroids;
  const int n = cv::connectedComponentsWithStats(drivable, areas, stats, centroids, 8, CV_32S);
  int largest = 0;
  for (int k = 1; k < n; ++k)
    if (largest == 0 || stats.at<int>(k, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA)) largest = k;
  std::vector<char> reached(static_cast<size_t>(spaces), 0);
  for (int y = 0; y < map.rows; ++y)
    for (int x = 0; x < map.cols; ++x)
      if (largest > 0 && areas.at<int32_t>(y, x) == largest)
        if (const int l = labels.at<int32_t>(y, x); l > 0 && l <= spaces) reached[static_cast<size_t>(l - 1)] = 1;
  std::vector<int> out;
  for (int i = 0; i < spaces; ++i)
    if (!reached[static_cast<size_t>(i)]) out.push_back(i);
  return out;
}

}  // namespace rgnav::buildings
