#include "building_furniture.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include "building_reach.h"
#include "sim/rng.h"

namespace rgnav::buildings {

namespace {

constexpr uint8_t kFurniture = 200;   // drawn grey inside a black outline, as in the IPA maps

enum class ItemKind { kCabinet, kRound, kTable, kBox };

struct Item
{
  ItemKind kind;
  cv::Rect body;     // the piece itself (a table: its top)
  cv::Rect extent;   // with its chairs: what nothing else may overlap
  int chairs_near = 0, chairs_far = 0;   // along the long sides
};

void draw_chair(cv::Mat& m, cv::Point top_left)
{
  const int s = to_pixels(0.4) - 1;
  for (const cv::Point leg : {cv::Point(0, 0), cv::Point(s, 0), cv::Point(0, s), cv::Point(s, s)}) m.at<uint8_t>(top_left + leg) = 0;
}

void draw(const Item& it, cv::Mat& m)
{
  const cv::Rect& r = it.body;
  switch (it.kind) {
    case ItemKind::kCabinet:
    case ItemKind::kBox:
      cv::rectangle(m, r, cv::Scalar(kFurniture), cv::FILLED);
      cv::rectangle(m, r, cv::Scalar(0), 1);
      return;
    case ItemKind::kRound: {
      const cv::Point c(r.x + r.width / 2, r.y + r.height / 2);
      cv::circle(m, c, r.width / 2, cv::Scalar(kFurniture), cv::FILLED);
      cv::circle(m, c, r.width / 2, cv::Scalar(0), 1);
      return;
    }
    case ItemKind::kTable:
      break;
  }
  // Table legs (2 x 2 px, 5 cm in from the corners); chairs by their four legs.
  for (const cv::Point leg : {cv::Point(r.x + 1, r.y + 1), cv::Point(r.x + r.width - 3, r.y + 1), cv::Point(r.x + 1, r.y + r.height - 3),
                              cv::Point(r.x + r.width - 3, r.y + r.height - 3)})
    m(cv::Rect(leg.x, leg.y, 2, 2)).setTo(cv::Scalar(0));
  const bool along_x = r.width >= r.height;
  const int chair = to_pixels(0.4), pitch = to_pixels(0.6), gap = to_pixels(0.1);
  const int len = along_x ? r.width : r.height;
  for (int side = 0; side < 2; ++side) {
    const int n = side == 0 ? it.chairs_near : it.chairs_far;
    for (int k = 0; k < n; ++k) {
      const int u = (len - n * pitch) / 2 + k * pitch + (pitch - chair) / 2;
      const cv::Point p = along_x ? cv::Point(r.x + u, side == 0 ? r.y - gap - chair : r.y + r.height + gap)
                                  : cv::Point(side == 0 ? r.x - gap - chair : r.x + r.width + gap, r.y + u);
      draw_chair(m, p);
    }
  }
}

class Furnisher
{
 public:
  Furnisher(const Building& b, int space) : b_(b), space_(space), rng_(sim::Rng::derive(b.seed, 0xF0F0ull + static_cast<uint64_t>(space)))
  {
    // Nothing within a metre of a doorway, on either side.
    for (const auto& d : b.doorways) {
      if (d.a != space && d.b != space) continue;
      const int reach = to_pixels(1.0), side = 4;
      keep_out_.push_back(d.vertical ? cv::Rect(d.line - reach, d.from - side, 2 * reach, d.width_px() + 2 * side)
                                     : cv::Rect(d.from - side, d.line - reach, d.width_px() + 2 * side, 2 * reach));
    }
  }

  std::vector<Item> items()
  {
    const Space& s = b_.spaces[static_cast<size_t>(space_)];
    for (const auto& pr : s.rects) {
      // Inside the walls and their noise (walls reach at most 2 px into a space, bumps 1 more).
      const cv::Rect in(pr.x0 + 3, pr.y0 + 3, pr.width() - 6, pr.height() - 6);
      if (s.kind == SpaceKind::kHallway) {
        // Only in hallways wide enough to pass what stands along their walls.
        if (std::min(pr.width(), pr.height()) >= to_pixels(2.2))
          for (int k = between(0, 3); k > 0; --k) along_wall(in, chance(0.5) ? ItemKind::kRound : ItemKind::kCabinet, 0.3, 0.45);
        continue;
      }
      for (int k = between(0, 3); k > 0; --k) along_wall(in, ItemKind::kCabinet, 0.4, 0.6);
      if (chance(0.6)) in_corner(in);
      if (s.kind == SpaceKind::kHall) rows_of_tables(in);
      else if (std::min(in.width, in.height) >= to_pixels(3.0) && chance(0.8)) desk(in);
      for (int k = between(0, 3); k > 0; --k) along_wall(in, ItemKind::kBox, 0.3, 0.5);
    }
    return items_;
  }

 private:
  double uniform(double lo, double hi) { return lo + (hi - lo) * rng_.uniform(); }
  int between(int lo, int hi) { return lo + static_cast<int>(rng_.next_u64() % static_cast<uint64_t>(hi - lo + 1)); }
  bool chance(double p) { return rng_.uniform() < p; }

  bool place(const Item& it, const cv::Rect& in)
  {
    if ((it.extent & in) != it.extent) return false;
    for (const auto& k : keep_out_)
      if ((it.extent & k).area() > 0) return false;
    for (const auto& o : items_) {
      const cv::Rect grown(o.extent.x - 2, o.extent.y - 2, o.extent.width + 4, o.extent.height + 4);
      if ((it.extent & grown).area() > 0) return false;
    }
    items_.push_back(it);
    return true;
  }

  // A piece against one of the walls, depth lo..hi m, 0.3-2 m long.
  void along_wall(const cv::Rect& in, ItemKind kind, double lo, double hi)
  {
    const int depth = to_pixels(uniform(lo, hi));
    const int len = kind == ItemKind::kCabinet ? to_pixels(uniform(0.8, 2.0)) : to_pixels(uniform(lo, hi));
    const int side = between(0, 3);
    const bool horizontal = side < 2;
    const int span = horizontal ? in.width : in.height;
    if (span <= len) return;
    const int u = between(0, span - len);
    cv::Rect r = horizontal ? cv::Rect(in.x + u, side == 0 ? in.y : in.y + in.height - depth, len, depth)
                            : cv::Rect(side == 2 ? in.x : in.x + in.width - depth, in.y + u, depth, len);
    if (kind == ItemKind::kRound) r = cv::Rect(r.x, r.y, depth, depth);
    place({kind, r, r}, in);
  }

  void in_corner(const cv::Rect& in)
  {
    const int d = to_pixels(uniform(0.3, 0.5));
    const int corner = between(0, 3);
    const cv::Rect r((corner & 1) ? in.x + in.width - d : in.x, (corner & 2) ? in.y + in.height - d : in.y, d, d);
    place({ItemKind::kRound, r, r}, in);
  }

  Item table(cv::Point top_left, int len, int wid, bool along_x, int near, int far)
  {
    Item t{ItemKind::kTable, along_x ? cv::Rect(top_left.x, top_left.y, len, wid) : cv::Rect(top_left.x, top_left.y, wid, len), {}, near, far};
    const int reach = to_pixels(0.5);   // chair and its gap
    t.extent = along_x ? cv::Rect(t.body.x, t.body.y - (near ? reach : 0), t.body.width, t.body.height + (near ? reach : 0) + (far ? reach : 0))
                       : cv::Rect(t.body.x - (near ? reach : 0), t.body.y, t.body.width + (near ? reach : 0) + (far ? reach : 0), t.body.height);
    return t;
  }

  // An office desk with one or two chairs, somewhere in the room.
  void desk(const cv::Rect& in)
  {
    const int len = to_pixels(uniform(1.2, 1.8)), wid = to_pixels(uniform(0.7, 0.9));
    const bool along_x = chance(0.5);
    const int chairs = between(1, 2);
    for (int attempt = 0; attempt < 6; ++attempt) {
      const int w = along_x ? len : wid + to_pixels(0.5), h = along_x ? wid + to_pixels(0.5) : len;
      if (in.width <= w || in.height <= h) return;
      const cv::Point p(in.x + between(0, in.width - w) + (along_x ? 0 : to_pixels(0.5)), in.y + between(0, in.height - h) + (along_x ? to_pixels(0.5) : 0));
      if (place(table(p, len, wid, along_x, chairs, 0), in)) return;
    }
  }

  // Rows of tables with chairs on both sides (a canteen, a classroom), 1.2-1.6 m apart.
  void rows_of_tables(const cv::Rect& in)
  {
    const bool along_x = in.width >= in.height;
    const int len = to_pixels(uniform(1.4, 2.4)), wid = to_pixels(uniform(0.7, 1.0));
    const int aisle = to_pixels(uniform(1.2, 1.6)), reach = to_pixels(0.5);
    const int pitch_across = wid + 2 * reach + aisle, pitch_along = len + aisle;
    const int u_span = along_x ? in.width : in.height, v_span = along_x ? in.height : in.width;
    const int chairs = std::max(1, len / to_pixels(0.6));
    for (int v = aisle + reach; v + wid + reach + aisle <= v_span; v += pitch_across)
      for (int u = aisle; u + len + aisle <= u_span; u += pitch_along) {
        const cv::Point p = along_x ? cv::Point(in.x + u, in.y + v) : cv::Point(in.x + v, in.y + u);
        place(table(p, len, wid, along_x, chairs, chairs), in);
      }
  }

  const Building& b_;
  int space_;
  sim::Rng rng_;
  std::vector<cv::Rect> keep_out_;
  std::vector<Item> items_;
};

cv::Mat draw_all(const cv::Mat& map, const std::vector<std::vector<Item>>& items)
{
  cv::Mat out = map.clone();
  for (const auto& per_space : items)
    for (const auto& it : per_space) draw(it, out);
  return out;
}

}  // namespace

cv::Mat furnish(const Building& b, const cv::Mat& labels, const cv::Mat& map)
{
  const int n = static_cast<int>(b.spaces.size());
  std::vector<std::vector<Item>> items;
  for (int i = 0; i < n; ++i) items.push_back(Furnisher(b, i).items());
  const auto plain_out = spaces_out_of_reach(map, labels, n);
  const std::set<int> already(plain_out.begin(), plain_out.end());
  const auto graph = doorway_graph(b);
  // Furniture that shuts the robot out of a space goes, in the space and around its doorways.
  for (int round = 0; round < 6; ++round) {
    std::vector<int> lost;
    for (int s : spaces_out_of_reach(draw_all(map, items), labels, n))
      if (!already.count(s)) lost.push_back(s);
    if (lost.empty()) return draw_all(map, items);
    for (int s : lost) {
      items[static_cast<size_t>(s)].clear();
      if (round > 0)
        for (int t : graph[static_cast<size_t>(s)]) items[static_cast<size_t>(t)].clear();
    }
  }
  return map.clone();
}

}  // namespace rgnav::buildings
