// A trajectory as the low-level drive receives it: a chain, the limits its velocity profile
// must respect, and whether to stop at its end. Plain C++ (trajectory_conversions.h maps it
// to and from trajectory_t).
#pragma once

#include <cstdint>

#include "time/message_time.h"
#include "trajectory/chain.h"

namespace rgnav::trajectory {

struct Trajectory
{
  int64_t id = 0;
  time::Time stamp{};          // when it was planned (message time)
  Chain chain;                 // in the odometry frame
  double a_max = 0.5;          // [m/s^2]
  double omega_max = 1.2;      // [rad/s]
  bool stop_at_end = true;
  time::Time predicted_end{};  // planner's prediction of the completion time
};

}  // namespace rgnav::trajectory
