// Odometry's translation scale, learned from scan matches (online calibration). A wheel radius
// a percent off makes odometry a percent long or short on every metre; where the scans fix both
// translation directions that is seen and averaged out, but along a hallway the scans leave the
// axis to odometry (icp.degenerate_min_points), and there the error adds up: a 70 m
// hallway, beyond the LMS's 8 m, came out 0.5-0.7 m stretched on the simulator's 1 % scale
// error, and every lap the same, so no loop closure could take it out (bench slam). Kümmerle
// et al. 2011 calibrate odometry inside the SLAM problem; this keeps to the one parameter that
// a hallway cannot observe, estimated where the scans can.
#pragma once

#include "scan_mapper/pose_math.h"

namespace rgnav::scan_mapper {

struct OdometryScaleOptions
{
  double window_m = 0.0;        // forgetting: samples count over about this much travel (0: off)
  double min_step_m = 0.1;      // shorter increments (turns on the spot) say nothing of the scale
  double min_travel_m = 5.0;    // the scale is 1 until this much travel has been measured
  double max_error = 0.1;       // the scale stays within 1 +- this
};

class OdometryScale
{
 public:
  explicit OdometryScale(OdometryScaleOptions options) : options_(options) {}

  bool enabled() const { return options_.window_m > 0.0; }
  // One well-constrained match: odometry's increment and the scans' (both in the same frame).
  // The measured length along odometry's direction over odometry's length is one sample; the
  // estimate is their least-squares ratio, weighted by length, forgetting over window_m.
  void add(const Pose2& odometry_increment, const Pose2& measured_increment);
  // The factor odometry's translation is multiplied by (true / odometry); 1 until learned.
  double scale() const;
  // Odometry's increment with its translation scaled.
  Pose2 corrected(const Pose2& odometry_increment) const;
  double measured_travel_m() const { return travel_m_; }

 private:
  OdometryScaleOptions options_;
  double sum_measured_odometry_ = 0.0;  // sum of forgotten (measured along) x (odometry length)
  double sum_odometry_squared_ = 0.0;   // sum of forgotten (odometry length)^2
  double travel_m_ = 0.0;               // odometry length of every sample taken
};

}  // namespace rgnav::scan_mapper
