#include "render/rgmap_picture.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <limits>

#include "geometry/farthest_pair.h"

namespace rgnav::render {

using Eigen::Vector2d;
using rgmap::Region;

namespace {

Color region_color(int64_t id)
{
  static const Color palette[] = {{141, 211, 199}, {255, 255, 179}, {190, 186, 218}, {251, 128, 114},
                                  {128, 177, 211}, {253, 180, 98},  {179, 222, 105}, {252, 205, 229},
                                  {217, 217, 217}, {188, 128, 189}, {204, 235, 197}, {255, 237, 111}};
  return palette[static_cast<size_t>(id) % (sizeof palette / sizeof palette[0])];
}

Color gateway_color(rgmap::GatewayClass c)
{
  switch (c) {
    case rgmap::GatewayClass::kDoor: return {200, 30, 30};
    case rgmap::GatewayClass::kNarrowPassage: return {230, 120, 0};
    case rgmap::GatewayClass::kXCrossing: return {30, 30, 200};
    case rgmap::GatewayClass::kTCrossing:
    case rgmap::GatewayClass::kLTCrossing:
    case rgmap::GatewayClass::kRTCrossing: return {0, 140, 200};
    case rgmap::GatewayClass::kLTurn:
    case rgmap::GatewayClass::kRTurn: return {120, 0, 160};
    default: return {90, 90, 90};
  }
}

bool live(const Region& r) { return r.state != Region::State::kMerged; }

}  // namespace

std::map<int64_t, geometry::Pose2> compose_region_frames(const rgmap::RgMap& map)
{
  std::map<int64_t, geometry::Pose2> frames;
  for (const auto& [id, r] : map.regions()) {
    if (!live(r) || frames.count(id)) continue;
    // A new component: anchor it at its own map pose, then walk its gateways.
    frames[id] = r.map_from_region;
    std::deque<int64_t> open{id};
    while (!open.empty()) {
      const int64_t a = open.front();
      open.pop_front();
      for (const auto& [gid, g] : map.gateways()) {
        if (g.region_b == 0 || g.neutralized) continue;
        const int64_t ga = map.resolve(g.region_a), gb = map.resolve(g.region_b);
        if (ga == a && !frames.count(gb)) {
          frames[gb] = frames[a] * g.region_a_from_region_b;
          open.push_back(gb);
        } else if (gb == a && !frames.count(ga)) {
          frames[ga] = frames[a] * g.region_a_from_region_b.inverse();
          open.push_back(ga);
        }
      }
    }
  }
  return frames;
}

Bounds map_bounds(const rgmap::RgMap& map, const std::map<int64_t, geometry::Pose2>& frames)
{
  Bounds b;
  b.min = Vector2d::Constant(std::numeric_limits<double>::max());
  b.max = -b.min;
  auto grow = [&](const Vector2d& p) {
    b.min = b.min.cwiseMin(p);
    b.max = b.max.cwiseMax(p);
  };
  for (const auto& [id, f] : frames) {
    const Region& r = *map.region(id);
    for (const auto& s : r.segments) {
      grow(f * s.a);
      grow(f * s.b);
    }
    grow(f * r.bbox_min);
    grow(f * r.bbox_max);
  }
  if (b.min.x() > b.max.x()) return Bounds{};
  return b;
}

void draw_rgmap(const rgmap::RgMap& map, const rgmap::RgGraph& graph, Canvas* c)
{
  const auto frames = compose_region_frames(map);
  // Regions: freespace cells in the region's colour.
  for (const auto& [id, f] : frames) {
    const Region& r = *map.region(id);
    const auto& fs = r.freespace;
    const double res = fs.resolution();
    for (int y = 0; y < fs.height(); ++y) {
      for (int x = 0; x < fs.width(); ++x) {
        if (!fs.free(x, y)) continue;
        const geometry::Pose2 world_from_grid = f * fs.region_from_grid();
        c->polygon({world_from_grid * Vector2d(x * res, y * res), world_from_grid * Vector2d((x + 1) * res, y * res),
                    world_from_grid * Vector2d((x + 1) * res, (y + 1) * res), world_from_grid * Vector2d(x * res, (y + 1) * res)},
                   region_color(id), 0.55);
      }
    }
  }
  // Line maps and objects.
  for (const auto& [id, f] : frames) {
    const Region& r = *map.region(id);
    for (const auto& s : r.segments) c->line(f * s.a, f * s.b, {20, 20, 20}, 1.5, false);
    for (const auto& o : r.objects) {
      const geometry::Pose2 p = f * o.center;
      if (o.shape == rgmap::Object2d::Shape::kCircle) {
        // Circles (pillars) as polygons: drawn in metres like everything else in the map.
        std::vector<Vector2d> ring;
        for (int k = 0; k < 24; ++k)
          ring.push_back(p.translation() + 0.5 * o.length * Vector2d(std::cos(k * M_PI / 12), std::sin(k * M_PI / 12)));
        c->polygon(ring, {40, 80, 120}, 0.7);
        continue;
      }
      const Vector2d hx = p.rotation() * Vector2d(o.length / 2, 0), hy = p.rotation() * Vector2d(0, o.width / 2);
      c->polygon({p.translation() - hx - hy, p.translation() + hx - hy, p.translation() + hx + hy, p.translation() - hx + hy},
                 {120, 80, 40}, 0.7);
    }
    // 3D objects (the vision's rectangles) seen from above: upright ones (doors, whiteboards) as
    // their footprint, a thick line along the floor; flat ones (table tops) as their outline.
    for (const auto& o : r.objects3d) {
      const Color col = o.kind == 1 ? Color{230, 120, 0} : Color{150, 60, 160};
      std::vector<Vector2d> outline;
      for (int k = 0; k < 4; ++k) outline.push_back(f * Vector2d(o.corners(k, 0), o.corners(k, 1)));
      if (std::fabs(o.normal.z()) > 0.7) {
        c->polygon(outline, col, 0.5);
      } else {
        const auto [a, b] = geometry::farthest_pair(outline);
        c->line(a, b, col, 3.0, false);
      }
    }
    const Vector2d label = f * (0.5 * (r.bbox_min + r.bbox_max));
    c->text(label, "R" + std::to_string(id) + (r.name.empty() ? "" : " " + r.name), {0, 0, 0}, 14);
  }
  // RG graph: edges dashed, nodes (crossing points) as dots.
  std::map<int64_t, Vector2d> node_at;
  for (const auto& n : graph.nodes)
    if (frames.count(n.region_id)) node_at[n.id] = frames.at(n.region_id) * n.point;
  for (const auto& e : graph.edges)
    if (node_at.count(e.from) && node_at.count(e.to))
      c->line(node_at[e.from], node_at[e.to], e.kind == rgmap::GraphEdge::Kind::kGateway ? Color{200, 0, 0} : Color{0, 90, 0},
              1.2, true);
  for (const auto& [id, p] : node_at) c->circle(p, 3.5, {0, 90, 0});
  // Gateways with their class.
  for (const auto& [gid, g] : map.gateways()) {
    const int64_t a = map.resolve(g.region_a);
    if (!frames.count(a)) continue;
    const auto& f = frames.at(a);
    const Color col = g.neutralized ? Color{160, 160, 160} : gateway_color(g.cls);
    for (size_t k = 0; k + 1 < g.gateway_points.size(); k += 2) c->line(f * g.gateway_points[k], f * g.gateway_points[k + 1], col, 4, false);
    if (!g.crossing_points.empty())
      c->text(f * g.crossing_points.front() + Vector2d(0.15, 0.15),
              std::string(rgmap::to_string(g.cls)) + (g.neutralized ? " (neutralized)" : ""), col, 11);
  }
}

void render_rgmap(const rgmap::RgMap& map, const std::string& path, double ppm)
{
  const auto canvas = make_canvas_for(path, map_bounds(map, compose_region_frames(map)), ppm);
  draw_rgmap(map, rgmap::build_graph(map), canvas.get());
  canvas->save(path);
}

GlobalGrid compose_global_grid(const rgmap::RgMap& map, double resolution)
{
  const auto frames = compose_region_frames(map);
  const Bounds b = map_bounds(map, frames);
  GlobalGrid g;
  g.resolution = resolution;
  g.origin = b.min - Vector2d(0.5, 0.5);
  const int w = static_cast<int>(std::ceil((b.max.x() - b.min.x() + 1.0) / resolution)) + 1;
  const int h = static_cast<int>(std::ceil((b.max.y() - b.min.y() + 1.0) / resolution)) + 1;
  g.cells = cv::Mat(h, w, CV_8U, cv::Scalar(205));
  // Row 0 of the PGM is the top of the map (largest y).
  auto cell = [&](const Vector2d& p) {
    return cv::Point(static_cast<int>((p.x() - g.origin.x()) / resolution), h - 1 - static_cast<int>((p.y() - g.origin.y()) / resolution));
  };
  // Inverse mapping: every output cell asks its region's bitmap whether its centre is free,
  // so rotated regions leave no holes (a forward mapping of rotated cells aliases).
  for (const auto& [id, f] : frames) {
    const auto& fs = map.region(id)->freespace;
    if (fs.width() == 0 || fs.height() == 0) continue;
    const geometry::Pose2 world_from_grid = f * fs.region_from_grid();
    const double gw = fs.width() * fs.resolution(), gh = fs.height() * fs.resolution();
    Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::max()), hi = -lo;
    for (const Vector2d& c : {Vector2d(0, 0), Vector2d(gw, 0), Vector2d(0, gh), Vector2d(gw, gh)}) {
      lo = lo.cwiseMin(world_from_grid * c);
      hi = hi.cwiseMax(world_from_grid * c);
    }
    const geometry::Pose2 region_from_world = f.inverse();
    const cv::Point a = cell(lo), b = cell(hi);  // rows grow downward: a is bottom-left
    for (int row = std::max(0, b.y); row <= std::min(h - 1, a.y); ++row) {
      for (int col = std::max(0, a.x); col <= std::min(w - 1, b.x); ++col) {
        const Vector2d centre(g.origin.x() + (col + 0.5) * resolution, g.origin.y() + (h - 1 - row + 0.5) * resolution);
        if (fs.is_free(region_from_world * centre)) g.cells.at<uint8_t>(row, col) = 254;
      }
    }
  }
  for (const auto& [id, f] : frames)
    for (const auto& s : map.region(id)->segments) cv::line(g.cells, cell(f * s.a), cell(f * s.b), cv::Scalar(0), 1, cv::LINE_8);
  return g;
}

void write_map_server(const GlobalGrid& grid, const std::string& base_path)
{
  const std::string pgm = base_path + ".pgm";
  if (!cv::imwrite(pgm, grid.cells)) throw std::runtime_error("cannot write " + pgm);
  std::ofstream y(base_path + ".yaml");
  y << "image: " << std::filesystem::path(pgm).filename().string() << "\n"
    << "resolution: " << grid.resolution << "\n"
    << "origin: [" << grid.origin.x() << ", " << grid.origin.y() << ", 0.0]\n"
    << "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  if (!y) throw std::runtime_error("cannot write " + base_path + ".yaml");
}

}  // namespace rgnav::render
