// What happened at a contact on an obstacle course (control_bench): who closed the gap. The
// simulator counts a collision when the robot's own motion brings its body into something
// (people stop short of the robot, they never step into it), but the gap may have been closed
// mostly by a person walking up to a robot that stood still or backed away; that is a
// different failure from the robot driving into someone. The history of the robot's and the
// people's true positions splits the closing of the gap over a time window into the robot's
// part (its displacement toward the person) and the person's (theirs toward the robot).
#pragma once

#include <Eigen/Core>

#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace rgnav::bench {

struct ContactSplit
{
  double window_s = 0.0;          // actually covered (shorter at the start of a course)
  double gap_before_m = 0.0;      // surface gap at the window's start
  double robot_closing_m = 0.0;   // the robot's displacement toward the person, summed
  double person_closing_m = 0.0;  // the person's toward the robot
  double person_speed_mps = 0.0;  // over the last 0.5 s
  std::string closed_by;          // "robot", "person", "both" or "neither" (under 2 cm each)
};

class ContactHistory
{
 public:
  explicit ContactHistory(double keep_s = 5.0) : keep_s_(keep_s) {}

  // True positions at time t (seconds, increasing): the robot's centre and every person's.
  void add(double t, const Eigen::Vector2d& robot, const std::vector<Eigen::Vector2d>& people);
  // The closing of the gap to person `person` over the last `window` seconds; the radii make
  // the surface gap. Nothing if there is no history or no such person.
  std::optional<ContactSplit> split(size_t person, double window, double radii) const;

 private:
  struct Sample
  {
    double t;
    Eigen::Vector2d robot;
    std::vector<Eigen::Vector2d> people;
  };
  double keep_s_;
  std::deque<Sample> samples_;
};

}  // namespace rgnav::bench
