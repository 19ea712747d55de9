// People walking their paths at constant speed. A person who would step into the robot
// waits instead (people do not walk through robots, and the robot never drives into them);
// with a personal space, a person walking toward the robot waits that far from it.
//
// Having to stop for the robot (it stands in their way: in a doorway, a narrow hallway) starts
// an encounter, and people then do what people do, drawn at random per encounter with the
// shares of their world.h Person (the draws come from the simulator's seed: a run replays).
// Waiting behind a robot that drives out of their way costs them no patience:
//   - wait where they are for their patience; then step around the robot where the walls leave
//     room, pass it and drift back onto their path; no room: turn back the way they came
//     (turn_back), or wait on;
//   - stand aside: step off their path, just far enough that the robot fits past them, and
//     wait there until it has passed (or their patience runs out: then they walk on);
//   - go around it at once where there is room.
// No room for what they chose: they wait. Their patience is what keeps two parties waiting
// for each other from waiting for ever. With the default shares nothing is drawn and people
// wait (and step around once their patience runs out), as they always did.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "sim/lms2xx_model.h"
#include "sim/rng.h"
#include "sim/world.h"

namespace rgnav::sim {

enum class EncounterChoice
{
  kWait,
  kStandAside,
  kGoAround,
};
const char* to_string(EncounterChoice c);

// One encounter: from the moment someone first had to stop for the robot until they walk on
// with the robot no longer ahead of them (or turn back, or end standing aside).
struct Encounter
{
  size_t person = 0;         // index in World::people
  double t = 0.0;            // [s] when it began (the time advance() was given so far)
  EncounterChoice choice = EncounterChoice::kWait;
  double patience = 0.0;     // [s] this encounter's
  bool no_room = false;      // what they chose needed room there was not: they waited instead
  bool stood_aside = false;  // got off their path and waited there
  bool went_around = false;  // stepped around the robot
  bool turned_back = false;
};

// Where someone standing aside goes (stand_aside_offset): off their path by `offset` to the
// `side` (+1 left of their walking direction, -1 right).
struct AsideSpot
{
  double side = 1.0;
  double offset = 0.0;  // [m]
};

class People
{
 public:
  // `rng`: the encounters' draws (unused while every share is 0).
  explicit People(std::vector<Person> people, Rng rng = Rng(0));

  // Distance from a point to the nearest static obstacle (walls, boxes, closed doors),
  // searched up to the given radius (farther: anything larger).
  using StaticClearance = std::function<double(const Vec2& p, double search)>;

  // Advances everyone by dt seconds, given the robot's disc.
  // robot: nullopt when people do not make way for it.
  void advance(double dt, const std::optional<Circle>& robot, const StaticClearance& clearance);
  // Current discs, in the order of World::people.
  std::vector<Circle> discs() const;
  size_t size() const { return people_.size(); }
  // Every encounter so far, in the order they began.
  const std::vector<Encounter>& encounters() const { return encounters_; }

  // Standing aside: the least step off the path (up to max_offset) after which a robot of
  // `robot_radius` (plus `robot_margin` from the walls) fits past a person of `radius` who
  // stands at `at` walking along `walking` (unit); away from the robot's side first. Nothing:
  // no room on either side.
  static std::optional<AsideSpot> stand_aside_spot(const Vec2& at, const Vec2& walking, double radius,
                                                   const Circle& robot, double robot_margin, double max_offset,
                                                   const StaticClearance& clearance);

 private:
  enum class Phase
  {
    kWalking,
    kStandingAside,
  };
  struct State
  {
    double s = 0.0;         // arc length walked along the (unrolled) path
    double dir = 1.0;       // +1 along the path, -1 back (turned back)
    double waited = 0.0;    // [s] time spent before start_delay elapsed
    double waiting = 0.0;   // [s] waited for the robot (reset once it no longer stands ahead)
    double patience = 0.0;  // [s] the current encounter's
    double resting = 0.0;   // [s] standing before walking on (back at the start of a path walked once)
    Vec2 aside{0.0, 0.0};   // [m] sideways off the path, stepping around the robot
    int encounter = -1;     // index in encounters_ while one lasts
    bool going_around = false;
    Phase phase = Phase::kWalking;
    Vec2 aside_goal{0.0, 0.0};  // standing aside: the `aside` to reach
    Vec2 walking{1.0, 0.0};     // standing aside: the direction they were walking (unit)
  };
  Vec2 position(size_t i, double s) const;
  // Where person i stands: on the path, plus the step aside.
  Vec2 centre(size_t i) const { return position(i, state_[i].s) + state_[i].aside; }
  // Having to stop for the robot: what they do this time, and their patience.
  Encounter& begin_encounter(size_t i);
  void end_encounter(size_t i);
  // Having to stop for the robot: act on the encounter's choice.
  void blocked(size_t i, const Vec2& walking, const Circle& robot, double dt, const StaticClearance& clearance);
  // One step of standing aside (toward the spot, then waiting for the robot to pass).
  void standing_aside(size_t i, const Circle& robot, double dt);
  // One sideways step toward passing the robot at `pass` (centre to centre) where the walls
  // allow; false: no room on either side.
  bool step_aside(size_t i, const Vec2& walking, const Circle& robot, double pass, double dt,
                  const StaticClearance& clearance);
  // One sideways step back toward the path, if it stays clear of the robot and the walls.
  void drift_back(size_t i, const std::optional<Circle>& robot, double dt, const StaticClearance& clearance);

  std::vector<Person> people_;
  std::vector<std::vector<double>> cumulative_;  // arc length at each path vertex (loop: incl. closing leg)
  std::vector<State> state_;
  std::vector<Encounter> encounters_;
  Rng rng_;
  double time_ = 0.0;  // [s] advanced so far
  // The robot's velocity, from its disc over the last steps (smoothed over kRobotVelocityTau):
  // a robot that drives out of someone's way costs them no patience.
  std::optional<Vec2> robot_was_;
  Vec2 robot_velocity_{0.0, 0.0};
};

}  // namespace rgnav::sim
