// trajectory_segment_t / trajectory_t <-> Segment / Trajectory. Only node adapters use
// these (the primitives themselves know no LCM). A segment travels as a few numbers: its
// kind, start pose, length, end curvatures and up to three kind-specific parameters.
#pragma once

#include <optional>
#include <string>

#include "rgnav/trajectory_segment_t.hpp"
#include "rgnav/trajectory_t.hpp"
#include "trajectory/trajectory.h"
#include "trajectory/velocity_profile.h"

namespace rgnav::trajectory {

// v_end: the profile's speed at the segment end; a segment without a speed limit of its own
// travels with v_max_default.
trajectory_segment_t to_msg(const Segment& seg, double v_end, double v_max_default);
// Refuses (with why) unknown kinds and parameters that describe no curve.
std::optional<Segment> from_msg(const trajectory_segment_t& m, std::string* why);

// profile may be null (v_end = 0 everywhere).
trajectory_t to_msg(const Trajectory& t, const VelocityProfile* profile, double v_max_default);
std::optional<Trajectory> from_msg(const trajectory_t& m, std::string* why);

}  // namespace rgnav::trajectory
