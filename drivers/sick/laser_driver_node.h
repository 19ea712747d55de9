// Node adapter of laser_driver: polls the Lms2xxDriver when its port is readable (and every
// 20 ms for its timeouts), publishes each scan on the laser channel, and reports the link
// state and error counters in the heartbeat status.
#pragma once

#include "laser_driver_options.h"
#include "lms2xx_driver.h"
#include "runtime/node.h"
#include "scan_conversions.h"

namespace rgnav::drivers::sick {

class LaserDriverNode
{
 public:
  LaserDriverNode(runtime::Node& node, LaserDriverOptions options);

  const Lms2xxDriver& driver() const { return driver_; }
  int64_t published() const { return published_; }

 private:
  void service();
  void update_status();

  runtime::Node& node_;
  const LaserDriverOptions options_;
  Lms2xxDriver driver_;
  ScanIdSequence ids_;
  int64_t published_ = 0;
};

}  // namespace rgnav::drivers::sick
