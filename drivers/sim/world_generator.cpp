#include "sim/world_generator.h"

#include <opencv2/core.hpp>

#include <cmath>
#include <map>

#include "sim/image_world.h"
#include "sim/rng.h"

namespace rgnav::sim {

namespace {

constexpr double kRes = 0.05;  // [m] raster pitch; every generated coordinate is a multiple of it

struct Rect
{
  double x0, y0, x1, y1;
  std::vector<Vec2> polygon() const { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }
  Vec2 center() const { return {(x0 + x1) / 2, (y0 + y1) / 2}; }
};

// Free space as a union of rectangles; its boundary becomes the walls (so walls get the
// thickness of the gaps between rooms, as in a real building).
class FreeSpace
{
 public:
  void add(const Rect& r) { rects_.push_back(r); }
  void build_walls(double height, World* world) const
  {
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
    for (const auto& r : rects_) {
      x0 = std::min(x0, r.x0); y0 = std::min(y0, r.y0);
      x1 = std::max(x1, r.x1); y1 = std::max(y1, r.y1);
    }
    const Vec2 origin(x0 - 1.0, y0 - 1.0);
    const int cols = static_cast<int>(std::lround((x1 - x0 + 2.0) / kRes));
    const int rows = static_cast<int>(std::lround((y1 - y0 + 2.0) / kRes));
    cv::Mat mask(rows, cols, CV_8U, cv::Scalar(0));
    for (const auto& r : rects_) {
      const int c0 = static_cast<int>(std::lround((r.x0 - origin.x()) / kRes));
      const int c1 = static_cast<int>(std::lround((r.x1 - origin.x()) / kRes));
      const int r0 = rows - static_cast<int>(std::lround((r.y1 - origin.y()) / kRes));
      const int r1 = rows - static_cast<int>(std::lround((r.y0 - origin.y()) / kRes));
      mask(cv::Range(r0, r1), cv::Range(c0, c1)).setTo(255);
    }
    add_boundary_walls(mask, kRes, origin, height, world);
  }

 private:
  std::vector<Rect> rects_;
};

Box make_box(const std::string& name, Vec2 center, Vec2 size, double z_max, double yaw = 0.0)
{
  Box b;
  b.name = name;
  b.center = center;
  b.size = size;
  b.yaw = yaw;
  b.z_max = z_max;
  return b;
}

Table make_table(const std::string& name, Vec2 center, Vec2 size, double yaw = 0.0)
{
  Table t;
  t.name = name;
  t.center = center;
  t.size = size;
  t.yaw = yaw;
  return t;
}

Person make_person(const std::string& name, std::vector<Vec2> path, double speed, bool loop, double delay)
{
  Person p;
  p.name = name;
  p.path = std::move(path);
  p.speed = speed;
  p.loop = loop;
  p.start_delay = delay;
  return p;
}

Gateway make_gateway(const std::string& name, GatewayClass cls, std::vector<Vec2> pts, const std::string& from,
                     const std::string& to, std::optional<double> heading = std::nullopt)
{
  Gateway g;
  g.name = name;
  g.cls = cls;
  g.points = std::move(pts);
  g.regions = {from};
  if (!to.empty()) g.regions.push_back(to);
  g.heading = heading;
  return g;
}

Region make_region(const std::string& name, RegionKind kind, const Rect& r) { return {name, kind, r.polygon()}; }

// Which wall of a room its door is in.
enum class Side { kSouth, kNorth, kWest, kEast };

struct Office
{
  std::string name;
  Rect room;        // interior
  Side door_side;
  double door_at;   // door centre along the door wall (x for south/north, y for west/east)
  std::string hall; // region the door opens to
  double wall_to_hall;  // thickness of the wall the door is in
  bool cluttered = false;
  bool closed = false;  // closed at start, opened by the schedule later
};

// Furniture relative to the door wall: u along it (0 = its left end seen from inside), v the
// depth into the room from it.
void furnish(const Office& o, World* w)
{
  const Rect& r = o.room;
  const bool ns = o.door_side == Side::kSouth || o.door_side == Side::kNorth;
  const double width = ns ? r.x1 - r.x0 : r.y1 - r.y0;
  const double depth = ns ? r.y1 - r.y0 : r.x1 - r.x0;
  auto at = [&](double u, double v) -> Vec2 {
    switch (o.door_side) {
      case Side::kSouth: return {r.x0 + u, r.y0 + v};
      case Side::kNorth: return {r.x1 - u, r.y1 - v};
      case Side::kWest: return {r.x0 + v, r.y1 - u};
      case Side::kEast: return {r.x1 - v, r.y0 + u};
    }
    return {};
  };
  auto size = [&](double along, double across) -> Vec2 { return ns ? Vec2(along, across) : Vec2(across, along); };
  // A desk (legs only: the laser sees four posts) at the far wall, a cabinet in a far corner.
  w->tables.push_back(make_table(o.name + ".desk", at(width * 0.35, depth - 0.45), size(1.6, 0.8)));
  w->boxes.push_back(make_box(o.name + ".cabinet", at(width - 0.35, depth - 0.65), size(0.6, 1.2), 1.9));
  // For the cameras: a whiteboard on the far wall above the desk, a poster on the side wall.
  WallObject board;
  board.name = o.name + ".whiteboard";
  board.kind = WallObject::Kind::kWhiteboard;
  board.a = at(width * 0.35 - 0.7, depth - 0.01);
  board.b = at(width * 0.35 + 0.7, depth - 0.01);
  board.z_min = 1.0;
  board.z_max = 1.9;
  w->wall_objects.push_back(board);
  WallObject poster;
  poster.name = o.name + ".poster";
  poster.a = at(0.01, depth * 0.35);
  poster.b = at(0.01, depth * 0.35 + 0.6);
  poster.z_min = 1.1;
  poster.z_max = 1.9;
  w->wall_objects.push_back(poster);
  if (!o.cluttered) return;
  w->tables.push_back(make_table(o.name + ".table", at(width * 0.45, depth * 0.5), size(1.2, 0.8)));
  w->boxes.push_back(make_box(o.name + ".chair1", at(width * 0.45 - 0.9, depth * 0.5), size(0.45, 0.45), 0.9));
  w->boxes.push_back(make_box(o.name + ".chair2", at(width * 0.35, depth - 1.2), size(0.45, 0.45), 0.9));
  w->boxes.push_back(make_box(o.name + ".boxes", at(0.35, depth * 0.7), size(0.5, 0.7), 0.6));
  w->boxes.push_back(make_box(o.name + ".shelf", at(width - 0.2, depth * 0.45), size(0.3, 1.0), 1.6));
}

void add_office(const Office& o, FreeSpace* fs, World* w)
{
  fs->add(o.room);
  const double half = 0.5;  // 1 m doors
  const double t = o.wall_to_hall;
  Rect opening{};
  Vec2 hinge, latch;
  switch (o.door_side) {
    case Side::kSouth:
      opening = {o.door_at - half, o.room.y0 - t, o.door_at + half, o.room.y0};
      hinge = {o.door_at - half, o.room.y0 - t / 2}; latch = {o.door_at + half, o.room.y0 - t / 2};
      break;
    case Side::kNorth:
      opening = {o.door_at - half, o.room.y1, o.door_at + half, o.room.y1 + t};
      hinge = {o.door_at - half, o.room.y1 + t / 2}; latch = {o.door_at + half, o.room.y1 + t / 2};
      break;
    case Side::kWest:
      opening = {o.room.x0 - t, o.door_at - half, o.room.x0, o.door_at + half};
      hinge = {o.room.x0 - t / 2, o.door_at - half}; latch = {o.room.x0 - t / 2, o.door_at + half};
      break;
    case Side::kEast:
      opening = {o.room.x1, o.door_at - half, o.room.x1 + t, o.door_at + half};
      hinge = {o.room.x1 + t / 2, o.door_at - half}; latch = {o.room.x1 + t / 2, o.door_at + half};
      break;
  }
  fs->add(opening);
  Door d;
  d.name = o.name + ".door";
  d.hinge = hinge;
  d.latch = latch;
  d.open = !o.closed;
  if (o.closed) d.schedule = {{300.0, true}};
  w->doors.push_back(d);
  w->regions.push_back(make_region(o.name, RegionKind::kRoom, o.room));
  w->gateways.push_back(make_gateway(o.name + ".door", GatewayClass::kDoor, {hinge, latch}, o.name, o.hall));
  furnish(o, w);
}

}  // namespace

World office_world()
{
  World w;
  w.name = "office";
  w.start = {20.0, 2.0, M_PI / 2};
  FreeSpace fs;
  const Rect hall_a{1, 12, 39, 14}, hall_b_south{19, 6, 21, 12}, hall_b_north{19, 14, 21, 24};
  // Labelled as the RG model cuts it (crossing gateways join hallway regions, diss. Fig. 4.1):
  // hall_a is two hallways, one each side of the X-crossing, whose square is the gateway's own
  // area and in no region. The T-junction's and the turns' squares lie in one of the hallways
  // they join.
  const Rect hall_a_west{1, 12, 19, 14}, hall_a_east{21, 12, 39, 14};
  const Rect hall_c{19, 24, 37, 26}, hall_d{35, 14, 37, 24}, lobby{14, 0, 26, 6};
  for (const Rect& r : {hall_a, hall_b_south, hall_b_north, hall_c, hall_d, lobby}) fs.add(r);
  // Hallways and junction squares are walls-free unions.

  std::vector<Office> offices;
  // South row, doors north onto hall_a (the wall between is 0.15 m).
  const double south_x[] = {3, 7, 11, 15, 21, 25, 29, 33};
  for (int i = 0; i < 8; ++i) {
    Office o;
    o.name = (i < 4 ? "office_w" : "office_e") + std::to_string(i % 4 + 1);
    o.room = {south_x[i] + 0.1, 6.15, south_x[i] + 3.9, 11.85};
    o.door_side = Side::kNorth;
    o.door_at = south_x[i] + 2.0;
    o.hall = i < 4 ? "hall_a_west" : "hall_a_east";
    o.wall_to_hall = 0.15;
    o.cluttered = (i == 1 || i == 4 || i == 6);
    o.closed = (i == 7);
    offices.push_back(o);
  }
  // North-west: a lab and a kitchen onto hall_a, a meeting room onto hall_b_north.
  offices.push_back({"lab", {1.1, 14.15, 6.9, 19.85}, Side::kSouth, 4.0, "hall_a_west", 0.15, true, false});
  offices.push_back({"kitchen", {7.1, 14.15, 12.9, 19.85}, Side::kSouth, 10.0, "hall_a_west", 0.15, false, false});
  offices.push_back({"meeting", {13.1, 14.15, 18.9, 19.85}, Side::kEast, 17.0, "hall_b_north", 0.1, false, false});
  // Inside the loop: two onto hall_a, two onto hall_c.
  offices.push_back({"office_n1", {21.1, 14.15, 27.9, 18.9}, Side::kSouth, 24.5, "hall_a_east", 0.15, false, false});
  offices.push_back({"office_n2", {28.1, 14.15, 34.9, 18.9}, Side::kSouth, 31.5, "hall_a_east", 0.15, true, false});
  offices.push_back({"office_n3", {21.1, 19.1, 27.9, 23.85}, Side::kNorth, 24.5, "hall_c", 0.15, false, false});
  offices.push_back({"office_n4", {28.1, 19.1, 34.9, 23.85}, Side::kNorth, 31.5, "hall_c", 0.15, false, false});

  w.regions.push_back(make_region("hall_a_west", RegionKind::kHallway, hall_a_west));
  w.regions.push_back(make_region("hall_a_east", RegionKind::kHallway, hall_a_east));
  w.regions.push_back(make_region("hall_b_south", RegionKind::kHallway, hall_b_south));
  w.regions.push_back(make_region("hall_b_north", RegionKind::kHallway, hall_b_north));
  w.regions.push_back(make_region("hall_c", RegionKind::kHallway, hall_c));
  w.regions.push_back(make_region("hall_d", RegionKind::kHallway, hall_d));
  w.regions.push_back(make_region("lobby", RegionKind::kLobby, lobby));
  for (const auto& o : offices) add_office(o, &fs, &w);
  fs.build_walls(2.5, &w);

  // Lobby: reception counter, a pillar, two tables (legs only).
  w.boxes.push_back(make_box("lobby.counter", {16.5, 3.0}, {0.8, 2.5}, 1.1));
  w.boxes.push_back(make_box("lobby.pillar", {23.0, 3.0}, {0.4, 0.4}, 2.5));
  w.tables.push_back(make_table("lobby.table1", {23.0, 1.2}, {1.0, 1.0}));
  w.tables.push_back(make_table("lobby.table2", {17.0, 5.0}, {1.2, 0.8}));

  w.people.push_back(make_person("walker_a", {{3.0, 13.3}, {37.0, 13.3}}, 0.9, false, 0.0));
  // walker_b turns at x = 11, halfway between the doors of office_w2 and office_w3: turning
  // 0.7 m in front of office_w2's door, a person waiting there for the robot (which waited for
  // them to clear the door) held the demo robot at that door for good (demo-20261123-201201).
  w.people.push_back(make_person("walker_b", {{30.0, 12.6}, {11.0, 12.6}}, 0.7, false, 5.0));
  w.people.push_back(make_person("visitor", {{21.5, 4.5}, {24.5, 4.5}, {24.5, 1.0}, {21.5, 1.0}}, 0.6, true, 0.0));
  // walker_c keeps to the right of the 2 m hallways hall_c and hall_d, as people do: walking
  // their centre line back and forth, a person waiting for the robot left it no room to pass
  // (0.78 m either side for a robot that needs 2 x 0.36 m), and the demo stood there for good.
  w.people.push_back(make_person("walker_c",
                                 {{20.0, 24.6}, {35.6, 24.6}, {35.6, 15.0}, {36.4, 15.0}, {36.4, 25.4}, {20.0, 25.4}},
                                 0.8, true, 10.0));
  // Office people let the robot pass, as people in an office do (world.h): walking the
  // hallways back and forth without ever giving way, they locked the demo robot in front of
  // hall_c for minutes.
  // And, having waited 5 s for a robot that stays in their way, they step around it where the
  // hallway leaves room: with people who waited for good, a robot giving way along a 2 m
  // hallway was herded ahead of two walkers for up to 3 minutes (control_bench --tours).
  for (auto& p : w.people) {
    p.personal_space = 0.4;
    p.patience = 5.0;
  }

  using G = GatewayClass;
  Gateway crossing = make_gateway("crossing_ab", G::kXCrossing, {{19, 12}, {21, 12}, {21, 14}, {19, 14}}, "hall_b_south", "hall_b_north");
  crossing.regions.insert(crossing.regions.end(), {"hall_a_west", "hall_a_east"});
  w.gateways.push_back(crossing);
  w.gateways.push_back(make_gateway("junction_da", G::kTJunction, {{35, 14}, {37, 14}}, "hall_d", "hall_a_east", -M_PI / 2));
  w.gateways.push_back(make_gateway("turn_bc", G::kRTurn, {{21, 24}, {19, 26}}, "hall_b_north", "hall_c", M_PI / 2));
  w.gateways.push_back(make_gateway("turn_cd", G::kRTurn, {{35, 24}, {37, 26}}, "hall_c", "hall_d", 0.0));
  w.gateways.push_back(make_gateway("lobby_opening", G::kOpening, {{19, 6}, {21, 6}}, "lobby", "hall_b_south"));
  w.gateways.push_back(make_gateway("dead_end_a_west", G::kDeadEnd, {{1, 12}, {1, 14}}, "hall_a_west", "", M_PI));
  w.gateways.push_back(make_gateway("dead_end_a_east", G::kDeadEnd, {{39, 12}, {39, 14}}, "hall_a_east", "", 0.0));
  return w;
}

World hallway_world(double width, Clutter clutter)
{
  // Centre lines (dissertation fig. 4.1 style): a main hallway with an X-crossing, two
  // T-junctions (one branch up, one down), corners at both ends of a parallel hallway, and
  // dead ends. Classes are those seen when travelling in `heading`.
  struct Node { std::string name; Vec2 p; };
  const std::vector<Node> nodes = {
      {"w_end", {0, 0}},   {"x", {10, 0}},      {"t_up", {22, 0}},  {"t_down", {32, 0}}, {"corner_se", {40, 0}},
      {"s_end1", {10, -10}}, {"s_end2", {32, -10}}, {"corner_nw", {10, 10}}, {"t_top", {22, 10}}, {"corner_ne", {40, 10}}};
  const std::vector<std::pair<int, int>> edges = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {5, 1}, {1, 7}, {6, 3},
                                                  {2, 8}, {7, 8}, {8, 9}, {4, 9}};
  const double h = width / 2;
  std::map<int, int> degree;
  for (const auto& e : edges) { ++degree[e.first]; ++degree[e.second]; }

  World w;
  char name[64];
  const char* clutter_name = clutter == Clutter::kNone ? "uncluttered" : clutter == Clutter::kSlight ? "slightly_cluttered" : "strongly_cluttered";
  std::snprintf(name, sizeof name, "hallways_%gm_%s", width, clutter_name);
  w.name = name;
  w.start = {1.5, 0.0, 0.0};
  FreeSpace fs;
  auto square = [&](int i) { const Vec2 p = nodes[i].p; return Rect{p.x() - h, p.y() - h, p.x() + h, p.y() + h}; };
  for (size_t i = 0; i < nodes.size(); ++i) {
    fs.add(square(static_cast<int>(i)));
    if (degree[static_cast<int>(i)] >= 2)
      w.regions.push_back(make_region("j_" + nodes[i].name, RegionKind::kHallway, square(static_cast<int>(i))));
  }
  std::vector<std::pair<std::string, Rect>> halls;
  for (const auto& e : edges) {
    const Vec2 a = nodes[e.first].p, b = nodes[e.second].p;
    const Vec2 lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    const bool horizontal = std::fabs(a.y() - b.y()) < 1e-9;
    // The region between the junction squares; a dead end's square belongs to its hallway.
    const double cut_lo = degree[lo == a ? e.first : e.second] >= 2 ? h : -h;
    const double cut_hi = degree[hi == a ? e.first : e.second] >= 2 ? h : -h;
    const Rect r = horizontal ? Rect{lo.x() + cut_lo, lo.y() - h, hi.x() - cut_hi, hi.y() + h}
                              : Rect{lo.x() - h, lo.y() + cut_lo, hi.x() + h, hi.y() - cut_hi};
    fs.add(r);
    const std::string hall = "h_" + nodes[e.first].name + "_" + nodes[e.second].name;
    w.regions.push_back(make_region(hall, RegionKind::kHallway, r));
    halls.emplace_back(hall, r);
  }
  fs.build_walls(2.5, &w);

  using G = GatewayClass;
  auto corners = [&](int i) { return square(i).polygon(); };
  w.gateways.push_back(make_gateway("x", G::kXCrossing, corners(1), "j_x", ""));
  w.gateways.push_back(make_gateway("t_up", G::kLTJunction, corners(2), "j_t_up", "", 0.0));
  w.gateways.push_back(make_gateway("t_down", G::kRTJunction, corners(3), "j_t_down", "", 0.0));
  w.gateways.push_back(make_gateway("t_top", G::kTJunction, corners(8), "j_t_top", "", M_PI / 2));
  w.gateways.push_back(make_gateway("corner_se", G::kLTurn, corners(4), "j_corner_se", "", 0.0));
  w.gateways.push_back(make_gateway("corner_nw", G::kRTurn, corners(7), "j_corner_nw", "", M_PI / 2));
  w.gateways.push_back(make_gateway("corner_ne", G::kLTurn, corners(9), "j_corner_ne", "", M_PI / 2));
  auto dead_end = [&](int i, const std::string& hall, Vec2 a, Vec2 b, double heading) {
    w.gateways.push_back(make_gateway("dead_end_" + nodes[i].name, G::kDeadEnd, {a, b}, hall, "", heading));
  };
  dead_end(0, "h_w_end_x", {-h, -h}, {-h, h}, M_PI);
  dead_end(5, "h_s_end1_x", {10 - h, -10 - h}, {10 + h, -10 - h}, -M_PI / 2);
  dead_end(6, "h_s_end2_t_down", {32 - h, -10 - h}, {32 + h, -10 - h}, -M_PI / 2);

  if (clutter != Clutter::kNone) {
    // Objects stand against alternating walls, away from the junction squares so the
    // junction geometry stays what it is labelled as. A fixed seed keeps the file stable.
    Rng rng(clutter == Clutter::kSlight ? 41 : 42);
    const double spacing = clutter == Clutter::kSlight ? 5.0 : 2.2;
    const double max_depth = clutter == Clutter::kSlight ? 0.35 : std::min(0.6, width * 0.28);
    int k = 0;
    for (const auto& [hall, r] : halls) {
      const bool horizontal = (r.x1 - r.x0) > (r.y1 - r.y0);
      const double len = horizontal ? r.x1 - r.x0 : r.y1 - r.y0;
      for (double s = 1.5; s < len - 1.5; s += spacing) {
        const double along = std::round((0.4 + 0.6 * rng.uniform()) / kRes) * kRes;
        const double depth = std::round((0.25 + (max_depth - 0.25) * rng.uniform()) / kRes) * kRes;
        const bool side = (k++ % 2) == 0;
        const double pos = std::round((s + 0.5 * spacing * rng.uniform()) / kRes) * kRes;
        if (pos + along / 2 > len - 1.0) continue;
        Vec2 c;
        Vec2 size;
        if (horizontal) {
          c = {r.x0 + pos, side ? r.y1 - depth / 2 : r.y0 + depth / 2};
          size = {along, depth};
        } else {
          c = {side ? r.x1 - depth / 2 : r.x0 + depth / 2, r.y0 + pos};
          size = {depth, along};
        }
        const std::string obj = hall + ".obj" + std::to_string(k);
        if (clutter == Clutter::kStrong && k % 5 == 0) {
          w.tables.push_back(make_table(obj, c, size.cwiseMax(Vec2(0.5, 0.5))));
        } else {
          w.boxes.push_back(make_box(obj, c, size, 0.5 + std::round(rng.uniform() * 10) * 0.1));
        }
      }
    }
    if (clutter == Clutter::kStrong) {
      w.people.push_back(make_person("walker_1", {{3.0, 0.3}, {38.0, 0.3}}, 0.8, false, 0.0));
      w.people.push_back(make_person("walker_2", {{22.0, 8.0}, {22.0, 1.0}}, 0.6, false, 3.0));
    }
  }
  return w;
}

std::vector<std::pair<std::string, World>> builtin_worlds()
{
  std::vector<std::pair<std::string, World>> out;
  out.emplace_back("office", office_world());
  for (double width : {2.0, 2.5, 3.0})
    for (Clutter c : {Clutter::kNone, Clutter::kSlight, Clutter::kStrong}) {
      World w = hallway_world(width, c);
      out.emplace_back(w.name, std::move(w));
    }
  return out;
}

}  // namespace rgnav::sim
