// People walking their paths at constant speed. A person who would step into the robot
// waits instead (people do not walk through robots, and the robot never drives into them);
// with a personal space, a person walking toward the robot waits that far from it.
#pragma once

#include <optional>
#include <vector>

#include "sim/lms2xx_model.h"
#include "sim/world.h"

namespace rgnav::sim {

class People
{
 public:
  explicit People(std::vector<Person> people);

  // Advances everyone by dt seconds, given the robot's disc.
  // robot: nullopt when people do not make way for it.
  void advance(double dt, const std::optional<Circle>& robot);
  // Current discs, in the order of World::people.
  std::vector<Circle> discs() const;
  size_t size() const { return people_.size(); }

 private:
  struct State
  {
    double s = 0.0;         // arc length walked along the (unrolled) path
    double waited = 0.0;    // [s] time spent before start_delay elapsed
  };
  Vec2 position(size_t i, double s) const;

  std::vector<Person> people_;
  std::vector<std::vector<double>> cumulative_;  // arc length at each path vertex (loop: incl. closing leg)
  std::vector<State> state_;
};

}  // namespace rgnav::sim
