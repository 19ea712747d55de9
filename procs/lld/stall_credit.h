// How long the control loop itself was held up (ticks later than their period) since the newest
// odometry was taken in. When the whole host stalls, the base driver stalls with the loop: the
// odometry's age grew by the stall, yet nothing failed, and a stop for stale odometry would be
// a stop caused by the stall. The follower judges the odometry's age less this credit. A base
// driver that stalls alone (or is gone) earns none: the loop ran on time meanwhile. Nor does a
// gap longer than the cap: that is this process stopped (SIGSTOP, then the supervisor's
// SIGCONT), not a host hiccup, and the robot has been blind too long to go on.
#pragma once

#include <algorithm>

#include "time/message_time.h"

namespace rgnav::lld {

class StallCredit
{
 public:
  // cap: the longest single gap excused; a longer one voids the credit.
  explicit StallCredit(double cap_s) : cap_s_(cap_s) {}

  // Once per tick: dt since the previous tick, the loop's period, and the stamp of the newest
  // odometry (a new stamp starts the credit afresh).
  void on_tick(double dt, double period, time::Time odometry_stamp)
  {
    if (odometry_stamp != stamp_) {
      stamp_ = odometry_stamp;
      credit_s_ = 0.0;
    }
    const double late = std::max(0.0, dt - period);
    credit_s_ = late > cap_s_ ? 0.0 : std::min(cap_s_, credit_s_ + late);
  }
  double credit_s() const { return credit_s_; }

 private:
  const double cap_s_;
  time::Time stamp_{};
  double credit_s_ = 0.0;
};

}  // namespace rgnav::lld
