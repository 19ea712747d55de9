// Collision avoidance's node adapter: converts TARGETS, NAV_GOAL (cancel), ODOMETRY,
// LASER_FRONT, OBSTACLES_3D and LLD_STATUS for the CollisionAvoidance library and publishes
// the TRAJECTORY it decides; its mode goes into the heartbeat status.
#pragma once

#include "collision_avoidance/ca_options.h"
#include "collision_avoidance/collision_avoidance.h"
#include "runtime/node.h"

namespace rgnav::collision_avoidance {

class CaNode
{
 public:
  CaNode(runtime::Node& node, const CaNodeOptions& options);
  const CollisionAvoidance& ca() const { return ca_; }

 private:
  void decide(time::Time now);

  runtime::Node& node_;
  const CaNodeOptions options_;
  CollisionAvoidance ca_;
  Mode reported_ = Mode::kIdle;
  std::string reported_text_;
};

}  // namespace rgnav::collision_avoidance
