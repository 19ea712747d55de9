// 3D rectangles in a rectified stereo frame (diss. 3.3): quadrangle hypotheses of the left image
// (image_quadrangles.h), each one's plane normal from its vanishing line, the plane's offset
// from the disparities sampled just inside and outside its sides (the nearest offset many
// samples agree with: the diss.'s average over measured corners, kept from what is off the
// plane — the room seen through a door, mismatches at depth edges), the corners by ray-plane
// intersection, then the refined fit (rectangle3d.h). A hypothesis stays when three of its sides
// have samples on the plane and enough of all do (a quadrangle of lines that is no planar thing
// in space has not), and its sides have an object's size.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "vision/image_quadrangles.h"
#include "vision/rectangle3d.h"

namespace rgnav::vision {

struct RectangleDetectorOptions
{
  QuadrangleOptions quadrangles;
  RefineOptions refine;            // its focal_baseline is the rig's, set by the caller
  double inset_px = 4.0;           // samples this far inside and outside the sides ...
  int samples_per_side = 16;       // ... this many along each
  double plane_tolerance_px = 1.0; // [px of disparity] a sample on the plane
  double min_support = 0.4;        // share of the valid samples on the plane (about half may lie off it)
  int min_valid_samples = 12;
  double min_side_m = 0.15;        // sides of an object's size
  double max_side_m = 3.0;
};

struct DetectedRectangle
{
  Quadrangle image;     // [px] rectified left image
  Rectangle3d camera;   // rectified left camera frame
  double support = 0.0; // share of the samples on its plane
  double grey_inside = -1.0;  // mean grey level (0..255) of the image inside it (its sides' margin left out)
};

// `gray`: the rectified left image (8-bit); `disparity16`: its disparity (CV_16S, 1/16 px) at
// 1/`disparity_scale` of the image's resolution (invalid below 0); `camera`: the rectified left
// camera at full resolution.
std::vector<DetectedRectangle> detect_rectangles(const cv::Mat& gray, const cv::Mat& disparity16, int disparity_scale,
                                                 const Pinhole& camera, const RectangleDetectorOptions& options);

}  // namespace rgnav::vision
