// An occupancy grid rendered from aligned scans (hit / pass counts along every beam), its
// PNG image, and the map-consistency measure of the benchmark: the share of scan end points
// within a tolerance of an occupied cell of the final map. Misaligned scans put end points
// into space other scans saw through, so consistency drops when the map is not coherent.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "scan_mapper/scan_mapper.h"

namespace rgnav::scan_mapper {

struct OccupancyOptions
{
  double resolution_m = 0.05;
  double max_range_m = 30.0;      // beams beyond are not used
  double occupied_ratio = 0.3;    // hits / (hits + passes) for an occupied cell
  double margin_m = 1.0;
};

class OccupancyGrid
{
 public:
  static OccupancyGrid build(const std::vector<ScanNode>& nodes, const Pose2& base_from_laser,
                             const OccupancyOptions& options);

  bool occupied(int ix, int iy) const;
  bool known(int ix, int iy) const;
  // 8-bit image, +y up: occupied black, free white, unknown grey.
  cv::Mat render() const;
  // Share of end points (of the same nodes) within tolerance_m of an occupied cell.
  double consistency(const std::vector<ScanNode>& nodes, const Pose2& base_from_laser, double tolerance_m) const;

  int width() const { return w_; }
  int height() const { return h_; }
  double resolution() const { return o_.resolution_m; }

 private:
  template <class F>
  static void for_each_endpoint(const std::vector<ScanNode>& nodes, const Pose2& base_from_laser, double max_range, F&& f);
  int cell_x(double x) const { return static_cast<int>(std::floor((x - x0_) / o_.resolution_m)); }
  int cell_y(double y) const { return static_cast<int>(std::floor((y - y0_) / o_.resolution_m)); }

  OccupancyOptions o_;
  double x0_ = 0.0, y0_ = 0.0;
  int w_ = 0, h_ = 0;
  std::vector<uint16_t> hits_, passes_;
};

}  // namespace rgnav::scan_mapper
