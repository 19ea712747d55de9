#include "doorway_world.h"

#include <algorithm>
#include <cmath>

namespace rgnav::bench {
namespace {

constexpr double kRoomDepth = 5.0;    // [m] each room, along the way through
constexpr double kRoomHalfWidth = 3.0;
constexpr double kApproach = 3.0;     // [m] start and goal from the opening's mouths
constexpr double kMouth = 0.7;        // [m] route points this far out of each mouth, on the axis

sim::Wall wall(double x0, double y0, double x1, double y1)
{
  sim::Wall w;
  w.a = {x0, y0};
  w.b = {x1, y1};
  return w;
}

// The room-wall-room outline: the wall between the rooms fills -depth/2 <= x <= depth/2 but
// for the opening |y| < width/2.
std::vector<sim::Wall> walls(double width, double depth)
{
  const double h = kRoomHalfWidth, x0 = -depth / 2 - kRoomDepth, x1 = depth / 2 + kRoomDepth;
  const double a = depth / 2, w = width / 2;
  return {wall(x0, -h, x0, h),  wall(x1, -h, x1, h),                    // far ends
          wall(x0, -h, -a, -h), wall(x0, h, -a, h),                     // the first room's sides
          wall(a, -h, x1, -h),  wall(a, h, x1, h),                      // the second room's
          wall(-a, -h, -a, -w), wall(-a, w, -a, h),                     // the wall's faces ...
          wall(a, -h, a, -w),   wall(a, w, a, h),
          wall(-a, -w, a, -w),  wall(-a, w, a, w)};                     // ... and the opening's sides
}

// Points from a to b at most `spacing` apart (b included, a not).
void densify(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double spacing, std::vector<geometry::Pose2>* out)
{
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing)));
  for (int i = 1; i <= n; ++i) out->emplace_back(a + (b - a) * (static_cast<double>(i) / n), 0.0);
}

}  // namespace

DoorwayEncounter draw_doorway_encounter(std::mt19937& rng, int index, double clearance)
{
  DoorwayEncounter e;
  const bool hallway = index % 2 == 1;
  e.kind = hallway ? "hallway" : "doorway";
  const double min_width = 2.0 * (clearance + 0.06);
  std::uniform_real_distribution<double> doorway_width(min_width, std::max(min_width, 1.2)),
      hallway_width(min_width, 1.5), thickness(0.1, 0.3), length(2.5, 6.0), side(-1.0, 1.0),
      speed(0.5, 1.1), space(0.3, 0.5), lead(-5.0, 5.0);
  e.width = hallway ? hallway_width(rng) : doorway_width(rng);
  e.depth = hallway ? length(rng) : thickness(rng);
  e.world.name = "doorway_encounter";
  e.world.walls = walls(e.width, e.depth);
  const double a = e.depth / 2;
  const Eigen::Vector2d start(-a - kApproach, side(rng)), goal(a + kApproach, side(rng));
  e.world.start = {start.x(), start.y(), 0.0};
  e.goal = geometry::Pose2(goal, 0.0);
  const Eigen::Vector2d in(-a - kMouth, 0.0), out(a + kMouth, 0.0);
  densify(start, in, 1.0, &e.targets);
  densify(in, out, 1.0, &e.targets);
  densify(out, goal, 1.0, &e.targets);

  // The person walks the other way along the opening's axis, from the far room to a place in
  // the near one, once (someone who turned back tries again from where they came).
  sim::Person p;
  p.name = "walker";
  p.speed = speed(rng);
  p.personal_space = space(rng);
  p.patience = 3.0;
  p.patience_max = 15.0;
  p.stand_aside_share = 1.0 / 3.0;
  p.go_around_share = 1.0 / 3.0;
  p.turn_back = true;
  p.loop = false;
  p.once = true;  // to their destination in the near room
  // When the robot reaches the opening's centre (standing start, about 0.45 m/s in the open and
  // 0.25 m/s between walls that close), and when the person should.
  const double robot_eta = 1.5 + (in - start).norm() / 0.45 + (kMouth + a) / 0.25;
  e.person_lead_s = lead(rng);
  const double person_y0 = side(rng), person_y1 = side(rng);
  const double inside = kMouth + a;  // from the far mouth point to the opening's centre
  const double first_leg = std::clamp(p.speed * (robot_eta - e.person_lead_s) - inside, 1.0, kRoomDepth - 0.5);
  p.start_delay = std::max(0.0, robot_eta - e.person_lead_s - (first_leg + inside) / p.speed);
  const Eigen::Vector2d far_mouth(a + kMouth, 0.0), near_mouth(-a - kMouth, 0.0);
  p.path = {far_mouth + Eigen::Vector2d(first_leg, person_y0), far_mouth, near_mouth,
            near_mouth + Eigen::Vector2d(-(kRoomDepth - 1.2), person_y1)};
  e.world.people.push_back(p);
  return e;
}

}  // namespace rgnav::bench
