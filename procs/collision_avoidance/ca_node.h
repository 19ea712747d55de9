// Collision avoidance's node adapter: converts TARGETS, NAV_GOAL (cancel), ODOMETRY,
// LASER_FRONT, OBSTACLES_3D and LLD_STATUS for the CollisionAvoidance library and publishes
// the TRAJECTORY it decides; its mode goes into the heartbeat status and, with how long it has
// found no chain to its targets, onto CA_STATUS (on every change of mode and at 2 Hz of message
// time), so that the planner can tell a blocked passage from a slow one.
#pragma once

#include <optional>
#include <string>

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
  void publish_status(time::Time now);

  runtime::Node& node_;
  const CaNodeOptions options_;
  CollisionAvoidance ca_;
  Mode reported_ = Mode::kIdle;
  std::string reported_text_;
  int64_t goal_id_ = 0;                  // of the newest targets (0 after a cancel)
  bool status_sent_ = false;
  Mode status_mode_ = Mode::kIdle;       // the mode last sent on CA_STATUS ...
  time::Time status_sent_at_{};          // ... and when
  std::optional<time::Time> stuck_since_;   // REACTIVE or BLOCKED since, without a planned chain between
};

}  // namespace rgnav::collision_avoidance
