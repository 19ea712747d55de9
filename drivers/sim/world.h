// The simulated world: plain geometry with heights, moving people, scheduled doors, and the
// ground-truth labels (regions, gateways) evaluations compare against. A World is a value;
// loading (world_yaml.h, image_world.h) and simulating (simulator.h) are elsewhere.
// Frame: the world frame, x/y in metres, z up from the floor, angles CCW in radians.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace rgnav::sim {

using Vec2 = Eigen::Vector2d;

struct Pose2
{
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;  // [rad]
};

// A vertical wall patch: the segment a-b extruded from z_min to z_max.
struct Wall
{
  Vec2 a{0, 0};
  Vec2 b{0, 0};
  double z_min = 0.0;
  double z_max = 2.5;
};

// When a door is open or closed; the last entry at or before the current time wins.
struct DoorEvent
{
  double t = 0.0;  // [s] simulation time since start
  bool open = true;
};

// A door leaf closing the opening between hinge and latch (both on the wall line). An open
// door is folded away and blocks nothing; a closed one is a wall from the floor to `height`.
struct Door
{
  std::string name;
  Vec2 hinge{0, 0};
  Vec2 latch{0, 0};
  double height = 2.1;
  bool open = true;                  // state before the first schedule entry
  std::vector<DoorEvent> schedule;   // sorted by t
  double width() const { return (latch - hinge).norm(); }
  bool open_at(double t) const;
};

// An oriented box (furniture, pillars, cabinets) from z_min to z_max.
struct Box
{
  std::string name;
  Vec2 center{0, 0};
  Vec2 size{1, 1};  // [m] extent along the box's own x and y
  double yaw = 0.0;
  double z_min = 0.0;
  double z_max = 1.0;
  std::vector<Vec2> corners() const;  // CCW
};

// A table: four legs and a top. A laser at 0.4 m sees the legs and misses the top; the robot
// body (taller than the top) still collides with it.
struct Table
{
  std::string name;
  Vec2 center{0, 0};
  Vec2 size{1.2, 0.8};
  double yaw = 0.0;
  double height = 0.72;         // top surface
  double top_thickness = 0.04;
  double leg_size = 0.05;       // square legs, inset by their own size from the corners
  std::vector<Box> parts() const;  // legs then top
};

// A person walking a polyline at constant speed, seen as a circle from the floor to `height`.
struct Person
{
  std::string name;
  std::vector<Vec2> path;  // >= 1 point; one point = standing still
  double speed = 0.8;      // [m/s]
  bool loop = true;        // true: back to path[0] after the last point; false: walk back and forth
  bool once = false;       // walk the path once and stay at its end, their destination (loop is then unused)
  double radius = 0.22;
  double height = 1.75;
  double start_delay = 0.0;  // [s] stands at path[0] until then
  // Walking toward the robot (within 70 degrees of the walking direction), the person waits
  // rather than come closer than this to it, surface to surface, as people let a robot
  // pass; 0: only rather than touch it.
  double personal_space = 0.0;  // [m]
  // Having waited for the robot this long, the person steps around it where the walls leave
  // room (and passes it closer than the personal space), as people do with a robot that stands
  // in a hallway; no room: waits on. Infinite (the default): waits for the robot, however long.
  double patience = std::numeric_limits<double>::infinity();  // [s]
  // Meeting the robot in a doorway or a narrow hallway, people do one of several things; which
  // one is drawn at random for every encounter (seeded from the simulator's seed, people.h):
  // step aside where the walls leave the robot room to pass, and wait there until it has
  // (stand_aside_share); walk around it at once where there is room (go_around_share); or wait
  // where they are (the rest). No room for what they chose: they wait. Both 0 (the default):
  // they always wait, as above, and nothing is drawn.
  double stand_aside_share = 0.0;
  double go_around_share = 0.0;
  // Above `patience`: the patience of each encounter is drawn in [patience, patience_max].
  double patience_max = 0.0;  // [s]
  // Patience run out (waiting, or standing aside for a robot that does not come) and no room to
  // walk around it: they turn back the way they came (false: wait on); walking `once`, back at
  // the start of their path they try again. Two parties waiting for each other cannot wait for ever.
  bool turn_back = false;
};

// A flat picture hung on a wall, seen only by the cameras (posters, whiteboards: planar
// rectangles the vision looks for). a-b is its lower edge in the plane it hangs in: a
// centimetre off the wall face, on the side it faces.
struct WallObject
{
  enum class Kind { kPoster, kWhiteboard };
  std::string name;
  Kind kind = Kind::kPoster;
  Vec2 a{0, 0};
  Vec2 b{0, 0};
  double z_min = 1.0;  // [m] lower edge
  double z_max = 1.8;  // [m] upper edge
};

enum class RegionKind { kRoom, kHallway, kLobby, kOther };

struct Region
{
  std::string name;
  RegionKind kind = RegionKind::kRoom;
  std::vector<Vec2> polygon;  // simple polygon, either orientation
};

enum class GatewayClass {
  kDoor, kNarrowPassage, kXCrossing, kTJunction, kLTJunction, kRTJunction,
  kLTurn, kRTurn, kOpening, kDeadEnd
};

struct Gateway
{
  std::string name;
  GatewayClass cls = GatewayClass::kDoor;
  std::vector<Vec2> points;          // gateway points (dissertation fig. 4.1)
  std::vector<std::string> regions;  // names of the regions it connects
  // [rad] travel direction the class refers to (turns and T-junctions look different from
  // each approach); unset for direction-free classes (door, X-crossing, ...).
  std::optional<double> heading;
};

struct World
{
  std::string name;
  std::string source;  // file it came from (messages)
  Pose2 start;         // where the robot starts
  std::vector<Wall> walls;
  std::vector<Door> doors;
  std::vector<Box> boxes;
  std::vector<Table> tables;
  std::vector<Person> people;
  std::vector<WallObject> wall_objects;  // cameras only
  // Seeds the surfaces' texture for the cameras (the same seed: the same look).
  uint64_t texture_seed = 1;
  std::vector<Region> regions;
  std::vector<Gateway> gateways;
  std::vector<Vec2> tour;  // optional waypoints, starting near `start`
};

const char* to_string(RegionKind k);
const char* to_string(GatewayClass c);
std::optional<RegionKind> region_kind_from_string(const std::string& s);
std::optional<GatewayClass> gateway_class_from_string(const std::string& s);
std::vector<std::string> region_kind_names();
std::vector<std::string> gateway_class_names();

bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& polygon);
double polygon_area(const std::vector<Vec2>& polygon);  // absolute
Vec2 rotate(const Vec2& v, double angle);
double normalize_angle(double a);  // to (-pi, pi]

}  // namespace rgnav::sim
