// The demo's scripted operator, without LCM: names the explorer's regions after the simulated
// world's ground-truth rooms. The explorer gives a region's centroid in the RG map's frame; the
// scan mapper's map frame is the odometry frame at its first scan, which is where the robot
// stood when the simulation started, so world_from_map is the world's start pose. The room
// whose polygon holds the centroid names the region (else the nearest within reach, else
// "area_<id>"); a name already given to another region gets "_2", "_3", ... (the RG map's
// names pick one region each).
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "sim/world.h"

namespace rgnav::demo {

struct Answer
{
  std::string name;         // the name to give
  std::string room;         // the ground-truth room it came from ("" for area_<id>)
  std::string kind;         // room | hallway | lobby | other | ""
  double world_x = 0, world_y = 0;
};

class SimOperator
{
 public:
  explicit SimOperator(sim::World world, double reach_m = 2.0) : world_(std::move(world)), reach_(reach_m) {}

  // The answer for region `region_id` whose centroid is (x, y) in the map frame. Asked again
  // for the same region, the same answer.
  Answer name(int64_t region_id, double map_x, double map_y);
  const std::map<int64_t, Answer>& answers() const { return answers_; }
  const sim::World& world() const { return world_; }
  // Map frame -> world frame.
  sim::Vec2 to_world(double map_x, double map_y) const;

 private:
  sim::World world_;
  double reach_;
  std::map<int64_t, Answer> answers_;
};

}  // namespace rgnav::demo
