// How long the control loop itself was held up (ticks later than their period) since the newest
// odometry was taken in. When the whole host stalls, the base driver stalls with the loop: the
// odometry's age grew by the stall, yet nothing failed, and a stop for stale odometry would be
// a stop caused by the stall. The follower judges the odometry's age less this credit. A base
// driver that stalls alone (or is gone) earns none: the loop ran on time meanwhile.
#pragma once

#include <algorithm>

#include "time/message_time.h"

namespace rgnav::lld {

class StallCredit
{
 public:
  // cap: the longest stall excused (longer, the robot has been blind too long to go on).
  explicit StallCredit(double cap_s) : cap_s_(cap_s) {}

  // Once per tick: dt since the previous tick, the loop's period, and the stamp of the newest
  // odometry (a new stamp starts the credit afresh).
  void on_tick(double dt, double period, time::Time odometry_stamp)
  {
    if (odometry_stamp != stamp_) {
      stamp_ = odometry_stamp;
      credit_s_ = 0.0;
    }
    credit_s_ = std::min(cap_s_, credit_s_ + std::max(0.0, dt - period));
  }
  double credit_s() const { return credit_s_; }

 private:
  const double cap_s_;
  time::Time stamp_{};
  double credit_s_ = 0.0;
};

}  // namespace rgnav::lld
