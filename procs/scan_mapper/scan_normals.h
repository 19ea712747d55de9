// The surface normals of one scan's points, which make a pair point-to-line in ICP (icp.h).
#pragma once

#include <Eigen/Core>

#include <vector>

#include "scan_mapper/scan_types.h"

namespace rgnav::scan_mapper {

struct ScanNormalOptions
{
  double radius_m = 0.15;  // the neighbours within this radius give a point's normal, where they lie on a line
  // A point for which they give none (too few neighbours: a far surface, or one seen at grazing
  // incidence; or they are no line) takes the normal of the chord through its two neighbours in
  // beam order, where both are within beam_max_gap_m of it and each step turns from the chord
  // by at most beam_max_bend_rad: a surface sampled sparsely, not a corner or an occlusion
  // edge. A 1 deg scanner samples a 2 m hallway's wall 6 m ahead every 0.6 m; without a normal
  // each such sample pairs point-to-point with whichever sample of that wall another scan put
  // nearest, and so holds the fit along the wall, where the wall says nothing. 0: off.
  double beam_max_gap_m = 0.0;
  double beam_max_bend_rad = 0.1;
};

struct ScanNormals
{
  Points normals;                // unit; toward the viewpoint, so that a normal says which face was seen
  std::vector<char> has_normal;  // per point
};

// points: one scan's, in beam order; viewpoint: the laser's position in their frame.
ScanNormals scan_normals(const Points& points, const Eigen::Vector2d& viewpoint, const ScanNormalOptions& options);

}  // namespace rgnav::scan_mapper
