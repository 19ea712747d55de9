#include "sim/world_yaml.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include "sim/image_world.h"

namespace rgnav::sim {

namespace fs = std::filesystem;

namespace {

constexpr double kCoordLimit = 1e5;  // [m] a building, not a continent

Vec2 read_point(const config::Config& c, const std::string& key)
{
  if (!c.has(key)) c.fail(key, "required point [x, y] missing");
  const auto v = c.numbers(key, {}, -kCoordLimit, kCoordLimit, 2, 2);
  return {v[0], v[1]};
}

// Points are written as a flat list of pairs: [x0, y0, x1, y1, ...].
std::vector<Vec2> read_points(const config::Config& c, const std::string& key, size_t min_points)
{
  if (!c.has(key)) {
    if (min_points == 0) return {};
    c.fail(key, "required list of points [x0, y0, x1, y1, ...] missing");
  }
  const auto v = c.numbers(key, {}, -kCoordLimit, kCoordLimit, 2 * min_points);
  if (v.size() % 2 != 0) c.fail(key, "expected pairs of numbers [x0, y0, x1, y1, ...], got an odd count");
  std::vector<Vec2> out;
  for (size_t i = 0; i < v.size(); i += 2) out.emplace_back(v[i], v[i + 1]);
  return out;
}

std::string unique_name(const config::Config& c, const std::string& fallback, std::set<std::string>* seen)
{
  const std::string name = c.string("name", fallback);
  if (name.empty()) c.fail("name", "must not be empty");
  if (!seen->insert(name).second) c.fail("name", "'" + name + "' is used twice");
  return name;
}

std::string resolve(const std::string& base_dir, const std::string& file)
{
  if (file.empty() || fs::path(file).is_absolute()) return file;
  return (fs::path(base_dir) / file).lexically_normal().string();
}

OccupancyImage read_image_section(const config::Config& c, const std::string& base_dir)
{
  OccupancyImage im;
  im.file = resolve(base_dir, c.required_string("file"));
  im.resolution = c.number("resolution", im.resolution, 1e-3, 10.0);
  const auto origin = c.numbers("origin", {0.0, 0.0}, -kCoordLimit, kCoordLimit, 2, 2);
  im.origin = {origin[0], origin[1]};
  im.negate = c.boolean("negate", im.negate);
  im.free_thresh = c.number("free_thresh", im.free_thresh, 0.0, 1.0);
  im.wall_height = c.number("wall_height", im.wall_height, 0.1, 20.0);
  im.gt_segmentation = resolve(base_dir, c.string("gt_segmentation", ""));
  im.min_room_area = c.number("min_room_area", im.min_room_area, 0.0, 1e4);
  return im;
}

World load_ros_map(const config::Config& cfg, const std::string& path)
{
  // map_server's format: image, resolution, origin [x, y, yaw], negate, occupied_thresh,
  // free_thresh (and optionally mode). A non-zero origin yaw is not supported.
  const std::string base_dir = fs::path(path).parent_path().string();
  OccupancyImage im;
  im.file = resolve(base_dir, cfg.required_string("image"));
  im.resolution = cfg.required_number("resolution", 1e-3, 10.0);
  const auto origin = cfg.numbers("origin", {0.0, 0.0, 0.0}, -kCoordLimit, kCoordLimit, 3, 3);
  if (std::fabs(origin[2]) > 1e-9) cfg.fail("origin", "a rotated map origin (yaw != 0) is not supported");
  im.origin = {origin[0], origin[1]};
  im.negate = cfg.integer("negate", 0, 0, 1) != 0;
  const double occupied = cfg.number("occupied_thresh", 0.65, 0.0, 1.0);
  im.free_thresh = cfg.number("free_thresh", 0.196, 0.0, 1.0);
  if (im.free_thresh > occupied) cfg.fail("free_thresh", "must not exceed occupied_thresh");
  cfg.choice("mode", "trinary", {"trinary", "scale", "raw"});
  cfg.finish();
  World world;
  world.name = fs::path(path).stem().string();
  world.source = path;
  world.start = add_occupancy_image(im, &world);
  return world;
}

World load_bare_image(const std::string& path)
{
  // IPA test maps: 0.05 m/pixel, white (> 250) is free. Rooms from <stem>_gt_segmentation.png.
  OccupancyImage im;
  im.file = path;
  std::string stem = fs::path(path).stem().string();
  const std::string furn = "_furnitures";
  if (stem.size() > furn.size() && stem.compare(stem.size() - furn.size(), furn.size(), furn) == 0)
    stem.resize(stem.size() - furn.size());
  const fs::path gt = fs::path(path).parent_path() / (stem + "_gt_segmentation.png");
  if (fs::exists(gt) && fs::path(path).filename() != gt.filename()) im.gt_segmentation = gt.string();
  World world;
  world.name = fs::path(path).stem().string();
  world.source = path;
  world.start = add_occupancy_image(im, &world);
  return world;
}

std::string num(double v)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  std::string s = buf;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

std::string point_text(const Vec2& p) { return "[" + num(p.x()) + ", " + num(p.y()) + "]"; }

std::string points_text(const std::vector<Vec2>& pts)
{
  std::string s = "[";
  for (size_t i = 0; i < pts.size(); ++i) s += (i ? ",  " : "") + num(pts[i].x()) + ", " + num(pts[i].y());
  return s + "]";
}

std::string quoted(const std::string& s) { return "\"" + s + "\""; }

}  // namespace

World parse_world_yaml(const config::Config& cfg, const std::string& base_dir)
{
  World world;
  world.source = cfg.origin();
  world.name = cfg.string("name", fs::path(cfg.origin()).stem().string());
  bool have_start = cfg.has("start");
  const auto start = cfg.numbers("start", {0.0, 0.0, 0.0}, -kCoordLimit, kCoordLimit, 3, 3);
  world.start = {start[0], start[1], normalize_angle(start[2])};

  for (const auto& c : cfg.list("walls")) {
    Wall w;
    w.a = read_point(c, "a");
    w.b = read_point(c, "b");
    if ((w.a - w.b).norm() < 1e-6) c.fail("b", "wall has zero length");
    w.z_min = c.number("z_min", 0.0, 0.0, 20.0);
    w.z_max = c.number("height", 2.5, 0.0, 20.0);
    if (w.z_max <= w.z_min) c.fail("height", "must exceed z_min");
    world.walls.push_back(w);
  }
  std::set<std::string> names;
  for (const auto& c : cfg.list("doors")) {
    Door d;
    d.name = unique_name(c, "door_" + std::to_string(world.doors.size()), &names);
    d.hinge = read_point(c, "hinge");
    d.latch = read_point(c, "latch");
    if (d.width() < 0.3 || d.width() > 5.0) c.fail("latch", "door width must be within [0.3, 5] m");
    d.height = c.number("height", d.height, 0.5, 10.0);
    d.open = c.boolean("open", d.open);
    for (const auto& e : c.list("schedule")) {
      DoorEvent ev;
      ev.t = e.required_number("t", 0.0, 1e7);
      if (!e.has("open")) e.fail("open", "required true/false missing");
      ev.open = e.boolean("open", true);
      if (!d.schedule.empty() && ev.t < d.schedule.back().t) e.fail("t", "schedule must be sorted by time");
      d.schedule.push_back(ev);
    }
    world.doors.push_back(d);
  }
  for (const auto& c : cfg.list("boxes")) {
    Box b;
    b.name = unique_name(c, "box_" + std::to_string(world.boxes.size()), &names);
    b.center = read_point(c, "center");
    const auto size = c.numbers("size", {}, 0.01, 100.0, 2, 2);
    if (size.empty()) c.fail("size", "required [sx, sy] missing");
    b.size = {size[0], size[1]};
    b.yaw = c.number("yaw", 0.0, -10.0, 10.0);
    b.z_min = c.number("z_min", 0.0, 0.0, 20.0);
    b.z_max = c.number("z_max", 1.0, 0.0, 20.0);
    if (b.z_max <= b.z_min) c.fail("z_max", "must exceed z_min");
    world.boxes.push_back(b);
  }
  for (const auto& c : cfg.list("tables")) {
    Table t;
    t.name = unique_name(c, "table_" + std::to_string(world.tables.size()), &names);
    t.center = read_point(c, "center");
    const auto size = c.numbers("size", {1.2, 0.8}, 0.2, 20.0, 2, 2);
    t.size = {size[0], size[1]};
    t.yaw = c.number("yaw", 0.0, -10.0, 10.0);
    t.height = c.number("height", t.height, 0.2, 3.0);
    t.top_thickness = c.number("top_thickness", t.top_thickness, 0.005, 0.5);
    t.leg_size = c.number("leg_size", t.leg_size, 0.01, 0.5);
    if (t.top_thickness >= t.height) c.fail("top_thickness", "must be less than height");
    if (2.0 * t.leg_size >= std::min(t.size.x(), t.size.y())) c.fail("leg_size", "legs do not fit under the top");
    world.tables.push_back(t);
  }
  for (const auto& c : cfg.list("people")) {
    Person p;
    p.name = unique_name(c, "person_" + std::to_string(world.people.size()), &names);
    p.path = read_points(c, "path", 1);
    p.speed = c.number("speed", p.speed, 0.0, 3.0);
    p.loop = c.boolean("loop", p.loop);
    p.once = c.boolean("once", p.once);
    p.radius = c.number("radius", p.radius, 0.05, 1.0);
    p.height = c.number("height", p.height, 0.5, 2.5);
    p.start_delay = c.number("start_delay", p.start_delay, 0.0, 1e7);
    p.personal_space = c.number("personal_space", p.personal_space, 0.0, 5.0);
    if (c.has("patience")) p.patience = c.required_number("patience", 0.0, 1e9);  // absent: waits for good
    // Doorway encounters (world.h): what they do when the robot is in their way, drawn per encounter.
    p.stand_aside_share = c.number("stand_aside_share", p.stand_aside_share, 0.0, 1.0);
    p.go_around_share = c.number("go_around_share", p.go_around_share, 0.0, 1.0);
    if (p.stand_aside_share + p.go_around_share > 1.0 + 1e-9)
      c.fail("go_around_share", "stand_aside_share + go_around_share must not exceed 1");
    p.patience_max = c.number("patience_max", p.patience_max, 0.0, 1e9);
    p.turn_back = c.boolean("turn_back", p.turn_back);
    world.people.push_back(p);
  }
  for (const auto& c : cfg.list("wall_objects")) {
    WallObject o;
    o.name = unique_name(c, "wall_object_" + std::to_string(world.wall_objects.size()), &names);
    o.kind = c.choice("kind", "poster", {"poster", "whiteboard"}) == "whiteboard" ? WallObject::Kind::kWhiteboard
                                                                                 : WallObject::Kind::kPoster;
    o.a = read_point(c, "a");
    o.b = read_point(c, "b");
    if ((o.a - o.b).norm() < 0.05) c.fail("b", "a wall object must be at least 5 cm wide");
    o.z_min = c.number("z_min", o.z_min, 0.0, 20.0);
    o.z_max = c.number("z_max", o.z_max, 0.0, 20.0);
    if (o.z_max < o.z_min + 0.05) c.fail("z_max", "must exceed z_min by at least 5 cm");
    world.wall_objects.push_back(o);
  }
  world.texture_seed = static_cast<uint64_t>(cfg.integer("texture_seed", 1, 0, INT64_MAX));
  std::set<std::string> region_names;
  for (const auto& c : cfg.list("regions")) {
    Region r;
    r.name = unique_name(c, "", &region_names);
    const auto kind = region_kind_from_string(c.choice("kind", "room", region_kind_names()));
    r.kind = *kind;
    r.polygon = read_points(c, "polygon", 3);
    if (polygon_area(r.polygon) < 1e-3) c.fail("polygon", "polygon has no area");
    world.regions.push_back(r);
  }
  std::set<std::string> gateway_names;
  for (const auto& c : cfg.list("gateways")) {
    Gateway g;
    g.name = unique_name(c, "", &gateway_names);
    g.cls = *gateway_class_from_string(c.choice("class", "door", gateway_class_names()));
    g.points = read_points(c, "points", 1);
    // from / to, and `joins` for a crossing between more than two regions (every pair adjacent).
    auto add_region = [&](const char* key, const std::string& r) {
      if (r.empty()) return;
      if (!region_names.count(r)) c.fail(key, "no region named '" + r + "'");
      if (std::find(g.regions.begin(), g.regions.end(), r) == g.regions.end()) g.regions.push_back(r);
    };
    for (const char* key : {"from", "to"}) add_region(key, c.string(key, ""));
    for (const auto& r : c.strings("joins", {})) add_region("joins", r);
    if (c.has("heading")) g.heading = c.number("heading", 0.0, -10.0, 10.0);
    world.gateways.push_back(g);
  }
  world.tour = read_points(cfg, "tour", 0);
  if (cfg.has("image")) {
    const auto section = cfg.section("image");
    const OccupancyImage image = read_image_section(section, base_dir);
    Pose2 widest;
    try {
      widest = add_occupancy_image(image, &world);
    } catch (const config::ConfigError& e) {
      section.fail("file", e.what());
    }
    if (!have_start) world.start = widest;
  }
  if (world.walls.empty()) cfg.fail("walls", "a world needs walls (or an image)");
  return world;
}

World load_world(const std::string& path)
{
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".png" || ext == ".pgm") {
    if (!fs::exists(path)) throw config::ConfigError(path + ": no such world image");
    return load_bare_image(path);
  }
  const auto cfg = config::Config::load(path);
  if (cfg.has("image") && cfg.has("resolution")) return load_ros_map(cfg, path);
  World world = parse_world_yaml(cfg, fs::path(path).parent_path().string());
  cfg.finish();
  return world;
}

std::string resolve_world_path(const std::string& name_or_path, const std::string& worlds_dir)
{
  if (fs::exists(name_or_path) && !fs::is_directory(name_or_path)) return name_or_path;
  const fs::path candidate = fs::path(worlds_dir) / (name_or_path + ".yaml");
  if (fs::exists(candidate)) return candidate.string();
  throw config::ConfigError(name_or_path + ": no such world file, and no " + candidate.string());
}

std::string world_to_yaml(const World& w)
{
  std::ostringstream o;
  o << "# rgnav world (format: config/worlds/README.md)\n";
  o << "name: " << quoted(w.name) << "\n";
  o << "start: [" << num(w.start.x) << ", " << num(w.start.y) << ", " << num(w.start.theta) << "]\n";
  o << "walls:\n";
  for (const auto& x : w.walls) {
    o << "  - {a: " << point_text(x.a) << ", b: " << point_text(x.b);
    if (x.z_min != 0.0) o << ", z_min: " << num(x.z_min);
    o << ", height: " << num(x.z_max) << "}\n";
  }
  if (!w.doors.empty()) o << "doors:\n";
  for (const auto& d : w.doors) {
    o << "  - {name: " << quoted(d.name) << ", hinge: " << point_text(d.hinge) << ", latch: " << point_text(d.latch)
      << ", height: " << num(d.height) << ", open: " << (d.open ? "true" : "false");
    if (!d.schedule.empty()) {
      o << ", schedule: [";
      for (size_t i = 0; i < d.schedule.size(); ++i)
        o << (i ? ", " : "") << "{t: " << num(d.schedule[i].t) << ", open: " << (d.schedule[i].open ? "true" : "false") << "}";
      o << "]";
    }
    o << "}\n";
  }
  if (!w.boxes.empty()) o << "boxes:\n";
  for (const auto& b : w.boxes)
    o << "  - {name: " << quoted(b.name) << ", center: " << point_text(b.center) << ", size: " << point_text(b.size)
      << ", yaw: " << num(b.yaw) << ", z_min: " << num(b.z_min) << ", z_max: " << num(b.z_max) << "}\n";
  if (!w.tables.empty()) o << "tables:\n";
  for (const auto& t : w.tables)
    o << "  - {name: " << quoted(t.name) << ", center: " << point_text(t.center) << ", size: " << point_text(t.size)
      << ", yaw: " << num(t.yaw) << ", height: " << num(t.height) << ", top_thickness: " << num(t.top_thickness)
      << ", leg_size: " << num(t.leg_size) << "}\n";
  if (!w.people.empty()) o << "people:\n";
  for (const auto& p : w.people)
    o << "  - {name: " << quoted(p.name) << ", path: " << points_text(p.path) << ", speed: " << num(p.speed)
      << ", loop: " << (p.loop ? "true" : "false") << ", radius: " << num(p.radius) << ", height: " << num(p.height)
      << ", start_delay: " << num(p.start_delay)
      << (p.personal_space > 0.0 ? ", personal_space: " + num(p.personal_space) : std::string())
      << (std::isfinite(p.patience) ? ", patience: " + num(p.patience) : std::string())
      << (p.stand_aside_share > 0.0 ? ", stand_aside_share: " + num(p.stand_aside_share) : std::string())
      << (p.go_around_share > 0.0 ? ", go_around_share: " + num(p.go_around_share) : std::string())
      << (p.patience_max > 0.0 ? ", patience_max: " + num(p.patience_max) : std::string())
      << (p.turn_back ? ", turn_back: true" : "") << (p.once ? ", once: true" : "") << "}\n";
  if (!w.wall_objects.empty()) o << "wall_objects:\n";
  for (const auto& x : w.wall_objects)
    o << "  - {name: " << quoted(x.name) << ", kind: " << (x.kind == WallObject::Kind::kWhiteboard ? "whiteboard" : "poster")
      << ", a: " << point_text(x.a) << ", b: " << point_text(x.b) << ", z_min: " << num(x.z_min)
      << ", z_max: " << num(x.z_max) << "}\n";
  if (w.texture_seed != 1) o << "texture_seed: " << w.texture_seed << "\n";
  if (!w.regions.empty()) o << "regions:\n";
  for (const auto& r : w.regions)
    o << "  - {name: " << quoted(r.name) << ", kind: " << to_string(r.kind) << ", polygon: " << points_text(r.polygon) << "}\n";
  if (!w.gateways.empty()) o << "gateways:\n";
  for (const auto& g : w.gateways) {
    o << "  - {name: " << quoted(g.name) << ", class: " << to_string(g.cls) << ", points: " << points_text(g.points);
    if (g.regions.size() > 2) {
      o << ", joins: [";
      for (size_t k = 0; k < g.regions.size(); ++k) o << (k ? ", " : "") << quoted(g.regions[k]);
      o << "]";
    } else {
      if (!g.regions.empty()) o << ", from: " << quoted(g.regions[0]);
      if (g.regions.size() > 1) o << ", to: " << quoted(g.regions[1]);
    }
    if (g.heading) o << ", heading: " << num(*g.heading);
    o << "}\n";
  }
  if (!w.tour.empty()) o << "tour: " << points_text(w.tour) << "\n";
  return o.str();
}

}  // namespace rgnav::sim
