#include "building_layout.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <queue>

#include "sim/rng.h"

namespace rgnav::buildings {

const char* to_string(SpaceKind kind)
{
  switch (kind) {
    case SpaceKind::kHallway: return "hallway";
    case SpaceKind::kHall: return "hall";
    case SpaceKind::kRoom: break;
  }
  return "room";
}

namespace {

// Smallest side of a room: a narrow office still lets the robot turn inside.
const int kMinRoomPx = to_pixels(2.5);
// Door jambs: an opening keeps this much wall at either end of the shared wall, more than the
// thickest perpendicular wall and its scan noise, so the opening never cuts into another wall.
const int kJambPx = to_pixels(0.3);
const int kShortJambPx = to_pixels(0.15);
const int kMarginPx = to_pixels(1.0);   // image border around the building

enum class Side { kNorth, kSouth, kWest, kEast };

// The wall two rectangles share: on which grid line and along which span.
struct SharedWall
{
  bool vertical = false;
  int line = 0, from = 0, to = 0;
  int length() const { return to - from; }
};

std::optional<SharedWall> shared_wall(const PixelRect& a, const PixelRect& b)
{
  SharedWall w;
  if (a.x1 == b.x0 || b.x1 == a.x0) {
    w.vertical = true;
    w.line = a.x1 == b.x0 ? a.x1 : a.x0;
    w.from = std::max(a.y0, b.y0);
    w.to = std::min(a.y1, b.y1);
  } else if (a.y1 == b.y0 || b.y1 == a.y0) {
    w.line = a.y1 == b.y0 ? a.y1 : a.y0;
    w.from = std::max(a.x0, b.x0);
    w.to = std::min(a.x1, b.x1);
  } else {
    return std::nullopt;
  }
  if (w.length() <= 0) return std::nullopt;
  return w;
}

// The building under construction with its random source.
class Planner
{
 public:
  explicit Planner(uint64_t seed) : rng_(sim::Rng::derive(seed, 0xB0117D1))
  {
    building_.seed = seed;
    max_spaces_ = between_int(18, 32);
  }

  Building plan()
  {
    lay_hallways();
    // Rooms along every arm (a ring's outer sides), then the ring's inner block, halls at open
    // hallway ends, and rooms behind rooms.
    const size_t arms = building_.spaces.size();
    if (building_.layout == "ring") fill_ring_block();
    for (size_t i = 0; i < arms; ++i)
      for (const PixelRect arm : std::vector<PixelRect>(building_.spaces[i].rects)) {
        const bool horizontal = arm.width() >= arm.height();
        for (const Side side : horizontal ? std::vector<Side>{Side::kNorth, Side::kSouth} : std::vector<Side>{Side::kWest, Side::kEast})
          strip_of_rooms(arm, side);
      }
    if (building_.layout != "ring")
      for (size_t i = 0; i < arms; ++i) hall_at_end(static_cast<int>(i));
    add_back_rooms();
    connect_rooms();
    add_second_doors();
    drop_unreachable();
    frame();
    return building_;
  }

 private:
  double uniform(double lo, double hi) { return lo + (hi - lo) * rng_.uniform(); }
  int between_int(int lo, int hi) { return lo + static_cast<int>(rng_.next_u64() % static_cast<uint64_t>(hi - lo + 1)); }
  int metres(double lo, double hi) { return to_pixels(uniform(lo, hi)); }
  bool chance(double p) { return rng_.uniform() < p; }

  bool is_free(const PixelRect& r) const
  {
    for (const auto& s : building_.spaces)
      for (const auto& o : s.rects)
        if (r.overlaps(o)) return false;
    return true;
  }

  int add_space(SpaceKind kind, const PixelRect& r, int parent = -1)
  {
    building_.spaces.push_back({kind, {r}});
    parent_.push_back(parent);
    return static_cast<int>(building_.spaces.size()) - 1;
  }

  bool full() const { return static_cast<int>(building_.spaces.size()) >= max_spaces_; }

  // A hallway arm as its own space (joined to the previous arm by a doorway) or part of it.
  void add_arm(int previous, const PixelRect& r)
  {
    if (previous >= 0 && chance(0.3)) {
      const int id = add_space(SpaceKind::kHallway, r);
      arm_links_.push_back({previous, id});
    } else if (previous >= 0) {
      building_.spaces[static_cast<size_t>(previous)].rects.push_back(r);
    } else {
      add_space(SpaceKind::kHallway, r);
    }
  }

  void lay_hallways()
  {
    const double u = rng_.uniform();
    const int w1 = metres(1.2, 3.5), w2 = chance(0.5) ? w1 : metres(1.2, 3.5);
    if (u < 0.25) {
      // A ring: a hallway around a block of rooms (inner block at least 4 m deep).
      building_.layout = "ring";
      const int w = w1;
      const int a = metres(14.0, 28.0), b = std::max(metres(10.0, 18.0), 2 * w + to_pixels(4.0));
      add_space(SpaceKind::kHallway, {0, 0, a, w});
      auto& ring = building_.spaces[0].rects;
      ring.push_back({0, b - w, a, b});
      ring.push_back({0, w, w, b - w});
      ring.push_back({a - w, w, a, b - w});
      return;
    }
    if (u < 0.40) {
      building_.layout = "straight";
      add_space(SpaceKind::kHallway, {0, 0, metres(15.0, 35.0), w1});
      return;
    }
    const int l1 = metres(14.0, 30.0), l2 = metres(8.0, 20.0);
    add_space(SpaceKind::kHallway, {0, 0, l1, w1});
    if (u < 0.60) {
      building_.layout = "L";
      add_arm(0, {l1 - w2, w1, l1, w1 + l2});
      return;
    }
    const int xj = static_cast<int>(uniform(0.25, 0.7) * l1);
    add_arm(0, {xj, w1, xj + w2, w1 + l2});
    if (u < 0.82) {
      building_.layout = "T";
      return;
    }
    building_.layout = "cross";
    add_arm(0, {xj, -metres(6.0, 14.0), xj + w2, 0});
  }

  // A room size: small offices most often, some medium rooms, a few open halls.
  struct RoomDraw
  {
    int width, depth;
  };
  RoomDraw draw_room()
  {
    const double u = rng_.uniform();
    if (u < 0.55) return {metres(2.5, 4.5), metres(3.0, 5.5)};
    if (u < 0.87) return {metres(4.5, 7.5), metres(4.0, 7.0)};
    return {metres(8.0, 14.0), metres(6.0, 10.0)};
  }

  // The rectangle of a strip room: u0..u1 along the arm, `depth` away from it on `side`.
  static PixelRect beside(const PixelRect& arm, Side side, int u0, int u1, int depth)
  {
    switch (side) {
      case Side::kNorth: return {u0, arm.y0 - depth, u1, arm.y0};
      case Side::kSouth: return {u0, arm.y1, u1, arm.y1 + depth};
      case Side::kWest: return {arm.x0 - depth, u0, arm.x0, u1};
      case Side::kEast: break;
    }
    return {arm.x1, u0, arm.x1 + depth, u1};
  }

  // The largest free room at u0 of at most width x depth (width shrunk first, then depth), if
  // one of at least the smallest room size fits.
  std::optional<PixelRect> fit(const PixelRect& arm, Side side, int u0, int width, int depth)
  {
    const int step = to_pixels(0.5);
    for (int d = depth; d >= kMinRoomPx; d -= step)
      for (int w = width; w >= kMinRoomPx; w -= step) {
        const PixelRect r = beside(arm, side, u0, u0 + w, d);
        if (is_free(r)) return r;
      }
    return std::nullopt;
  }

  void strip_of_rooms(const PixelRect& arm, Side side)
  {
    const bool horizontal = side == Side::kNorth || side == Side::kSouth;
    const int start = horizontal ? arm.x0 : arm.y0, end = horizontal ? arm.x1 : arm.y1;
    int u = start;
    if (chance(0.15)) u += metres(0.5, 4.0);   // a stretch of bare wall
    while (end - u >= kMinRoomPx && !full()) {
      const RoomDraw d = draw_room();
      int w = std::min(d.width, end - u);
      if (end - u - w < kMinRoomPx && end - u <= to_pixels(14.0)) w = end - u;   // no sliver left at the end
      const auto r = fit(arm, side, u, w, d.depth);
      if (!r) {
        u += to_pixels(0.5);
        continue;
      }
      const int got = horizontal ? r->width() : r->height();
      add_space(got >= to_pixels(8.0) && (horizontal ? r->height() : r->width()) >= to_pixels(6.0) ? SpaceKind::kHall : SpaceKind::kRoom, *r);
      u += got;
    }
  }

  // The block inside a ring: one or two rows of rooms, each touching the ring.
  void fill_ring_block()
  {
    const auto& ring = building_.spaces[0].rects;
    const PixelRect inner{ring[2].x1, ring[0].y1, ring[3].x0, ring[1].y0};
    std::vector<PixelRect> rows{inner};
    if (inner.height() >= to_pixels(8.0) && chance(0.6)) {
      const int split = inner.y0 + static_cast<int>(uniform(0.35, 0.65) * inner.height());
      rows = {{inner.x0, inner.y0, inner.x1, split}, {inner.x0, split, inner.x1, inner.y1}};
    }
    for (const PixelRect& row : rows) {
      if (inner.width() <= to_pixels(14.0) && chance(0.2)) {
        add_space(SpaceKind::kHall, row);
        continue;
      }
      int x = row.x0;
      while (x < row.x1) {
        int w = metres(3.0, 7.0);
        if (row.x1 - (x + w) < kMinRoomPx) w = row.x1 - x;
        const PixelRect r{x, row.y0, x + w, row.y1};
        add_space(w >= to_pixels(8.0) && row.height() >= to_pixels(6.0) ? SpaceKind::kHall : SpaceKind::kRoom, r);
        x += w;
      }
    }
  }

  // An open hall beyond the open end of a hallway arm (sometimes).
  void hall_at_end(int space)
  {
    for (const PixelRect arm : std::vector<PixelRect>(building_.spaces[static_cast<size_t>(space)].rects)) {
      if (full() || !chance(0.3)) continue;
      const bool horizontal = arm.width() >= arm.height();
      const int across = (horizontal ? arm.height() : arm.width()) + metres(2.0, 8.0);
      const int depth = metres(5.0, 10.0);
      const int centre = horizontal ? (arm.y0 + arm.y1) / 2 : (arm.x0 + arm.x1) / 2;
      const int lo = centre - across / 2 + between_int(-to_pixels(1.0), to_pixels(1.0));
      for (const bool far_end : {true, false}) {
        PixelRect r = horizontal ? (far_end ? PixelRect{arm.x1, lo, arm.x1 + depth, lo + across} : PixelRect{arm.x0 - depth, lo, arm.x0, lo + across})
                                 : (far_end ? PixelRect{lo, arm.y1, lo + across, arm.y1 + depth} : PixelRect{lo, arm.y0 - depth, lo + across, arm.y0});
        if (is_free(r)) {
          add_space(SpaceKind::kHall, r);
          break;
        }
      }
    }
  }

  // Rooms reached only through another room (an office behind a secretary's).
  void add_back_rooms()
  {
    const size_t n = building_.spaces.size();
    for (size_t i = 0; i < n && !full(); ++i) {
      const Space& s = building_.spaces[i];
      if (s.kind == SpaceKind::kHallway || parent_[i] >= 0 || !chance(0.25)) continue;
      const PixelRect f = s.rects[0];
      // Behind = on the side facing away from the hallway it touches.
      std::optional<Side> away;
      for (const auto& h : building_.spaces)
        if (h.kind == SpaceKind::kHallway)
          for (const auto& hr : h.rects)
            if (const auto w = shared_wall(f, hr))
              away = w->vertical ? (f.x0 == hr.x1 ? Side::kEast : Side::kWest) : (f.y0 == hr.y1 ? Side::kSouth : Side::kNorth);
      if (!away) continue;
      const bool horizontal = away == Side::kNorth || away == Side::kSouth;
      const int along = horizontal ? f.width() : f.height();
      const int w = std::max(kMinRoomPx, std::min(along, metres(2.5, 6.0)));
      const int u0 = (horizontal ? f.x0 : f.y0) + between_int(0, std::max(0, along - w));
      const auto r = fit(f, *away, u0, w, metres(2.5, 4.5));
      if (r) add_space(SpaceKind::kRoom, *r, static_cast<int>(i));
    }
  }

  // The longest wall spaces a and b share.
  std::optional<SharedWall> longest_wall(int a, int b) const
  {
    std::optional<SharedWall> best;
    for (const auto& ra : building_.spaces[static_cast<size_t>(a)].rects)
      for (const auto& rb : building_.spaces[static_cast<size_t>(b)].rects)
        if (const auto w = shared_wall(ra, rb); w && (!best || w->length() > best->length())) best = w;
    return best;
  }

  // A doorway in the wall between a and b: a door 0.8-1.6 m, sometimes (allow_wide) an opening
  // of 2-3 m; full_width: as wide as the jambs allow (hallway arms). False if none fits.
  bool add_doorway(int a, int b, bool allow_wide, bool full_width = false)
  {
    const auto wall = longest_wall(a, b);
    if (!wall) return false;
    // Between hallway arms the opening takes the whole width but for short jambs (still wider
    // than a perpendicular wall), so that even a 1.2 m hallway keeps a passable opening; so does
    // any wall too short for a door between long jambs (a hall at a narrow hallway's end).
    const int jamb = full_width || wall->length() - 2 * kJambPx < to_pixels(0.8) ? kShortJambPx : kJambPx;
    const int room = wall->length() - 2 * jamb;
    int w;
    bool wide = false;
    if (full_width) {
      w = room;
      wide = w >= to_pixels(2.0);
    } else if (allow_wide && chance(0.12) && room >= to_pixels(2.0)) {
      w = std::min(room, metres(2.0, 3.0));
      wide = true;
    } else {
      w = std::min(room, chance(0.8) ? metres(0.8, 1.2) : metres(1.2, 1.6));
    }
    if (w > room || w < to_pixels(0.8)) return false;
    for (int attempt = 0; attempt < 8; ++attempt) {
      const int from = wall->from + jamb + between_int(0, room - w);
      bool clash = false;
      for (const auto& d : building_.doorways)
        clash = clash || (d.vertical == wall->vertical && d.line == wall->line && from < d.to + jamb && d.from < from + w + jamb);
      if (clash) continue;
      building_.doorways.push_back({a, b, wall->vertical, wall->line, from, from + w, wide});
      return true;
    }
    return false;
  }

  // Every room a doorway to the hallway it touches (rooms behind rooms: to the room in front).
  void connect_rooms()
  {
    for (const auto& [a, b] : arm_links_) {
      if (chance(0.6)) add_doorway(a, b, false, true);
      else add_doorway(a, b, false);
    }
    for (size_t i = 0; i < building_.spaces.size(); ++i) {
      if (building_.spaces[i].kind == SpaceKind::kHallway) continue;
      const int me = static_cast<int>(i);
      if (parent_[i] >= 0) {
        add_doorway(parent_[i], me, true);
        continue;
      }
      int best = -1, best_len = 0;
      for (size_t h = 0; h < building_.spaces.size(); ++h)
        if (building_.spaces[h].kind == SpaceKind::kHallway)
          if (const auto w = longest_wall(static_cast<int>(h), me); w && w->length() > best_len) best = static_cast<int>(h), best_len = w->length();
      if (best >= 0) add_doorway(best, me, true);
    }
  }

  // Rooms with a second doorway: to a neighbouring room or hall.
  void add_second_doors()
  {
    const int n = static_cast<int>(building_.spaces.size());
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b) {
        if (building_.spaces[static_cast<size_t>(a)].kind == SpaceKind::kHallway || building_.spaces[static_cast<size_t>(b)].kind == SpaceKind::kHallway)
          continue;
        if (parent_[static_cast<size_t>(b)] == a || !longest_wall(a, b) || !chance(0.15)) continue;
        add_doorway(a, b, true);
      }
  }

  // Spaces the doorways do not reach from the first hallway: another doorway to a reached
  // neighbour if one fits, else the space is left out of the building.
  void drop_unreachable()
  {
    for (bool grew = true; grew;) {
      grew = false;
      const auto reached = reachable();
      for (size_t i = 0; i < reached.size() && !grew; ++i) {
        if (reached[i]) continue;
        for (size_t j = 0; j < reached.size() && !grew; ++j)
          if (reached[j] && add_doorway(static_cast<int>(j), static_cast<int>(i), false)) grew = true;
      }
    }
    const auto reached = reachable();
    std::vector<int> index(reached.size(), -1);
    Building kept = building_;
    kept.spaces.clear();
    for (size_t i = 0; i < reached.size(); ++i)
      if (reached[i]) {
        index[i] = static_cast<int>(kept.spaces.size());
        kept.spaces.push_back(building_.spaces[i]);
      }
    kept.doorways.clear();
    for (auto d : building_.doorways)
      if (index[static_cast<size_t>(d.a)] >= 0 && index[static_cast<size_t>(d.b)] >= 0) {
        d.a = index[static_cast<size_t>(d.a)];
        d.b = index[static_cast<size_t>(d.b)];
        kept.doorways.push_back(d);
      }
    building_ = std::move(kept);
  }

  std::vector<char> reachable() const { return reachable_through_doorways(building_); }

  // Shift the plan into the image with a margin around it.
  void frame()
  {
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -(1 << 30), y1 = -(1 << 30);
    for (const auto& s : building_.spaces)
      for (const auto& r : s.rects) x0 = std::min(x0, r.x0), y0 = std::min(y0, r.y0), x1 = std::max(x1, r.x1), y1 = std::max(y1, r.y1);
    const int dx = kMarginPx - x0, dy = kMarginPx - y0;
    for (auto& s : building_.spaces)
      for (auto& r : s.rects) r = {r.x0 + dx, r.y0 + dy, r.x1 + dx, r.y1 + dy};
    for (auto& d : building_.doorways) {
      d.line += d.vertical ? dx : dy;
      d.from += d.vertical ? dy : dx;
      d.to += d.vertical ? dy : dx;
    }
    building_.width = x1 - x0 + 2 * kMarginPx;
    building_.height = y1 - y0 + 2 * kMarginPx;
  }

  sim::Rng rng_;
  Building building_;
  std::vector<int> parent_;   // per space: the room it is reached through (-1: none)
  std::vector<std::pair<int, int>> arm_links_;
  int max_spaces_ = 0;
};

}  // namespace

Building generate_building(uint64_t seed) { return Planner(seed).plan(); }

int wall_thickness_px(const Building& building, int a, int b)
{
  const int lo = std::min(a, b), hi = std::max(a, b);
  sim::Rng r = sim::Rng::derive(building.seed, 0x3A11ull * 1000003ull + static_cast<uint64_t>(lo + 2) * 65599ull + static_cast<uint64_t>(hi + 2));
  const uint64_t u = r.next_u64();
  return lo < 0 ? 2 + static_cast<int>(u % 3) : 1 + static_cast<int>(u % 4);
}

std::vector<char> reachable_through_doorways(const Building& building)
{
  std::vector<char> seen(building.spaces.size(), 0);
  if (seen.empty()) return seen;
  const auto graph = doorway_graph(building);
  std::queue<int> q;
  q.push(0);
  seen[0] = 1;
  while (!q.empty()) {
    const int s = q.front();
    q.pop();
    for (int t : graph[static_cast<size_t>(s)])
      if (!seen[static_cast<size_t>(t)]) seen[static_cast<size_t>(t)] = 1, q.push(t);
  }
  return seen;
}

std::vector<std::vector<int>> doorway_graph(const Building& building)
{
  std::vector<std::vector<int>> g(building.spaces.size());
  for (const auto& d : building.doorways) {
    g[static_cast<size_t>(d.a)].push_back(d.b);
    g[static_cast<size_t>(d.b)].push_back(d.a);
  }
  return g;
}

}  // namespace rgnav::buildings
