// People walking their paths at constant speed. A person who would step into the robot
// waits instead (people do not walk through robots, and the robot never drives into them);
// with a personal space, a person walking toward the robot waits that far from it. After
// waiting their patience, they step sideways around the robot where the walls leave room,
// pass it, and drift back onto their path.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "sim/lms2xx_model.h"
#include "sim/world.h"

namespace rgnav::sim {

class People
{
 public:
  explicit People(std::vector<Person> people);

  // Distance from a point to the nearest static obstacle (walls, boxes, closed doors),
  // searched up to the given radius (farther: anything larger).
  using StaticClearance = std::function<double(const Vec2& p, double search)>;

  // Advances everyone by dt seconds, given the robot's disc.
  // robot: nullopt when people do not make way for it.
  void advance(double dt, const std::optional<Circle>& robot, const StaticClearance& clearance);
  // Current discs, in the order of World::people.
  std::vector<Circle> discs() const;
  size_t size() const { return people_.size(); }

 private:
  struct State
  {
    double s = 0.0;         // arc length walked along the (unrolled) path
    double waited = 0.0;    // [s] time spent before start_delay elapsed
    double waiting = 0.0;   // [s] waited for the robot (reset once it no longer stands ahead)
    Vec2 aside{0.0, 0.0};   // [m] sideways off the path, stepping around the robot
  };
  Vec2 position(size_t i, double s) const;
  // Where person i stands: on the path, plus the step aside.
  Vec2 centre(size_t i) const { return position(i, state_[i].s) + state_[i].aside; }
  // One sideways step toward passing the robot at `pass` (centre to centre) where the walls
  // allow; false: no room on either side.
  bool step_aside(size_t i, const Vec2& walking, const Circle& robot, double pass, double dt,
                  const StaticClearance& clearance);
  // One sideways step back toward the path, if it stays clear of the robot and the walls.
  void drift_back(size_t i, const std::optional<Circle>& robot, double dt, const StaticClearance& clearance);

  std::vector<Person> people_;
  std::vector<std::vector<double>> cumulative_;  // arc length at each path vertex (loop: incl. closing leg)
  std::vector<State> state_;
};

}  // namespace rgnav::sim
