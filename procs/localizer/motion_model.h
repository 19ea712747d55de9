// The odometry motion model: a particle moves by the odometry increment between two updates,
// perturbed by noise that grows like the odometry's own error (motion_noise in the config; the
// simulator's error model is the check: tests/procs/localizer/motion_model_test.cpp).
#pragma once

#include <random>

#include "geometry/pose2.h"
#include "localizer/localizer_options.h"

namespace rgnav::localizer {

struct MotionStd
{
  double along = 0, lateral = 0, rotation = 0;   // [m], [m], [rad] one sigma
};

// The error expected of an odometry increment `delta` (previous base frame) under `noise`.
MotionStd motion_std(const geometry::Pose2& delta, const MotionNoise& noise);

// The increment `delta` with noise drawn from motion_std, for one particle.
geometry::Pose2 sample_motion(const geometry::Pose2& delta, const MotionNoise& noise, std::mt19937_64& rng);

}  // namespace rgnav::localizer
