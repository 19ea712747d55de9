// Correlative scan matching (Olson 2009): an exhaustive search over a window of (x, y, theta)
// for the pose that maximises the summed likelihood of the scan's points in a grid built
// from the reference points. Two resolutions and branch and bound make it exact and fast: a
// coarse grid holding the maximum of each block of fine cells bounds the score of every fine
// translation in that block, so blocks that cannot beat the best found are never expanded.
#pragma once

#include <vector>

#include "scan_mapper/pose_math.h"
#include "scan_mapper/scan_types.h"

namespace rgnav::scan_mapper {

struct CorrelativeOptions
{
  double resolution_m = 0.05;   // fine grid cell = translation step
  double sigma_m = 0.06;        // width of each point's likelihood bump
  int coarse_factor = 8;        // fine cells per coarse block side
  double max_angular_step_deg = 1.0;
};

class LikelihoodGrid
{
 public:
  // Grid over the points' bounding box plus margin_m.
  LikelihoodGrid(const Points& points, const CorrelativeOptions& options, double margin_m = 0.5);

  double resolution() const { return res_; }
  int coarse_factor() const { return b_; }
  // Fine value at cell (ix, iy); 0 outside.
  float fine(int ix, int iy) const
  {
    return (ix < 0 || iy < 0 || ix >= w_ || iy >= h_) ? 0.f : fine_[static_cast<size_t>(iy) * w_ + ix];
  }
  // Max of fine cells [ix, ix+B) x [iy, iy+B); 0 where the block misses the grid.
  float coarse(int ix, int iy) const
  {
    ix += b_;
    iy += b_;
    return (ix < 0 || iy < 0 || ix >= cw_ || iy >= ch_) ? 0.f : coarse_[static_cast<size_t>(iy) * cw_ + ix];
  }
  // Continuous position → cell coordinates (floating).
  double cell_x(double x) const { return (x - x0_) / res_; }
  double cell_y(double y) const { return (y - y0_) / res_; }

 private:
  double res_, x0_ = 0.0, y0_ = 0.0;
  int b_, w_ = 0, h_ = 0, cw_ = 0, ch_ = 0;
  std::vector<float> fine_, coarse_;
};

struct CorrelativeWindow
{
  double linear_m = 0.3;     // +- search in x and y around the guess
  double angular_rad = 0.2;  // +- search in theta around the guess
};

struct CorrelativeResult
{
  Pose2 map_from_scan;
  double score = 0.0;  // mean likelihood of the scan points, in [0, 1]
  // The best score of the poses at least `distinct_m` from the best one (any angle), when asked
  // for: close to `score`, the window holds a second place that fits about as well (a hallway's
  // doors at regular spacing), and the match may be either.
  double runner_up = 0.0;
};

// scan points are in the scan's frame; guess is map_from_scan in the grid's frame. distinct_m > 0
// also finds runner_up (a second branch and bound over the same candidates).
CorrelativeResult correlative_match(const Points& scan, const LikelihoodGrid& grid, const Pose2& guess,
                                    const CorrelativeWindow& window, const CorrelativeOptions& options,
                                    double distinct_m = 0.0);

}  // namespace rgnav::scan_mapper
