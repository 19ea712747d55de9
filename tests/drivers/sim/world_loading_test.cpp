#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "bad_files.h"
#include "config/config.h"
#include "sim/world_generator.h"
#include "sim/world_yaml.h"

namespace rgnav::sim {
namespace {

namespace fs = std::filesystem;
const std::string kWorlds = std::string(RGNAV_SOURCE_DIR) + "/config/worlds";
const std::string kIpa = std::string(RGNAV_SOURCE_DIR) + "/../shared/data/maps/ipa";

std::string temp_dir()
{
  const fs::path dir = fs::temp_directory_path() / ("rgnav_sim_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir.string();
}

std::string write_file(const std::string& name, const std::string& text)
{
  const std::string path = temp_dir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string read_file(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(WorldLoading, CheckedInWorldsAreWhatTheGeneratorWrites)
{
  for (const auto& [name, world] : builtin_worlds()) {
    const std::string path = kWorlds + "/" + name + ".yaml";
    ASSERT_TRUE(fs::exists(path)) << path << " missing: run sim_worldgen config/worlds";
    EXPECT_EQ(read_file(path), world_to_yaml(world)) << path << " is stale: run sim_worldgen config/worlds";
  }
}

TEST(WorldLoading, OfficeWorldHasWhatTheIssueAsksFor)
{
  const World w = load_world(kWorlds + "/office.yaml");
  int rooms = 0, doors_to_rooms = 0;
  std::set<GatewayClass> classes;
  for (const auto& r : w.regions) rooms += r.kind == RegionKind::kRoom;
  for (const auto& g : w.gateways) {
    classes.insert(g.cls);
    doors_to_rooms += g.cls == GatewayClass::kDoor;
  }
  EXPECT_GE(rooms, 10);
  EXPECT_GE(doors_to_rooms, 10);
  EXPECT_EQ(w.doors.size(), static_cast<size_t>(doors_to_rooms));
  EXPECT_TRUE(classes.count(GatewayClass::kXCrossing));
  EXPECT_TRUE(classes.count(GatewayClass::kTJunction));
  // The X-crossing joins the four hallways around it (written and read back as `joins`).
  for (const auto& g : w.gateways)
    if (g.cls == GatewayClass::kXCrossing) {
      EXPECT_EQ(g.regions, (std::vector<std::string>{"hall_b_south", "hall_b_north", "hall_a_west", "hall_a_east"}));
    }
  EXPECT_TRUE(classes.count(GatewayClass::kRTurn));
  EXPECT_FALSE(w.tables.empty());
  EXPECT_FALSE(w.people.empty());
  bool scheduled = false;
  for (const auto& d : w.doors) scheduled |= !d.schedule.empty();
  EXPECT_TRUE(scheduled);
  // Round trip: what is written reads back to the same text.
  const std::string again = world_to_yaml(load_world(write_file("office_copy.yaml", world_to_yaml(w))));
  EXPECT_EQ(again, world_to_yaml(w));
}

TEST(WorldLoading, HallwayWorldsCoverEveryCrossingClassAndClutterLevel)
{
  std::map<std::string, size_t> obstacles;
  for (double width : {2.0, 2.5, 3.0}) {
    for (Clutter c : {Clutter::kNone, Clutter::kSlight, Clutter::kStrong}) {
      const World w = hallway_world(width, c);
      std::set<GatewayClass> classes;
      for (const auto& g : w.gateways) classes.insert(g.cls);
      for (auto cls : {GatewayClass::kXCrossing, GatewayClass::kTJunction, GatewayClass::kLTJunction,
                       GatewayClass::kRTJunction, GatewayClass::kLTurn, GatewayClass::kRTurn, GatewayClass::kDeadEnd})
        EXPECT_TRUE(classes.count(cls)) << w.name << " lacks " << to_string(cls);
      const size_t n = w.boxes.size() + w.tables.size();
      if (c == Clutter::kNone) {
        EXPECT_EQ(n, 0u);
      }
      if (c == Clutter::kSlight) {
        EXPECT_GT(n, 0u);
      }
      obstacles[w.name] = n;
    }
    char s[64], m[64];
    std::snprintf(s, sizeof s, "hallways_%gm_slightly_cluttered", width);
    std::snprintf(m, sizeof m, "hallways_%gm_strongly_cluttered", width);
    EXPECT_GT(obstacles[m], obstacles[s]);
  }
}

TEST(WorldLoading, IpaMapAndItsGroundTruthSegmentation)
{
  const std::string png = kIpa + "/lab_ipa.png";
  if (!fs::exists(png)) GTEST_SKIP() << png << " not available";
  const World w = load_world(png);
  EXPECT_GT(w.walls.size(), 100u);
  // Counted by eye in lab_ipa_gt_segmentation.png: 10 rooms and corridors.
  EXPECT_EQ(w.regions.size(), 10u);
  // The start pose is free and inside one of the rooms.
  bool inside = false;
  for (const auto& r : w.regions) inside |= point_in_polygon({w.start.x, w.start.y}, r.polygon);
  EXPECT_TRUE(inside);
  // Image size 864 x 768 at 0.05 m: all walls within 43.2 x 38.4 m.
  for (const auto& wall : w.walls) {
    EXPECT_GE(wall.a.x(), 0.0);
    EXPECT_LE(wall.a.x(), 43.2 + 1e-9);
    EXPECT_LE(wall.a.y(), 38.4 + 1e-9);
  }
}

TEST(WorldLoading, RosMapServerMap)
{
  // 20 x 10 pixels, free inside a 1-pixel black border, one occupied pixel at column 5, row 4.
  cv::Mat img(10, 20, CV_8U, cv::Scalar(254));
  img.row(0).setTo(0);
  img.row(9).setTo(0);
  img.col(0).setTo(0);
  img.col(19).setTo(0);
  img.at<uint8_t>(4, 5) = 0;
  cv::imwrite(temp_dir() + "/tiny.pgm", img);
  const std::string yaml = write_file("tiny.yaml",
                                      "image: tiny.pgm\nresolution: 0.1\norigin: [-1.0, 2.0, 0.0]\nnegate: 0\n"
                                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const World w = load_world(yaml);
  // Free area: columns 1..18, rows 1..8 -> x in [-0.9, 0.9], y in [2.1, 2.9].
  double x_min = 1e9, x_max = -1e9, y_min = 1e9, y_max = -1e9;
  for (const auto& wall : w.walls)
    for (const Vec2& p : {wall.a, wall.b}) {
      x_min = std::min(x_min, p.x()); x_max = std::max(x_max, p.x());
      y_min = std::min(y_min, p.y()); y_max = std::max(y_max, p.y());
    }
  EXPECT_NEAR(x_min, -0.9, 1e-9);
  EXPECT_NEAR(x_max, 0.9, 1e-9);
  EXPECT_NEAR(y_min, 2.1, 1e-9);
  EXPECT_NEAR(y_max, 2.9, 1e-9);
  // Outer boundary (4 walls) + the single occupied pixel (4 walls).
  EXPECT_EQ(w.walls.size(), 8u);
}

TEST(WorldLoading, StartIsInTheLargestDrivableAreaNotInAWalledOffPocket)
{
  // 0.1 m pixels. A closed 3 x 3 m square (clearance 1.5 m: the widest spot of the map) beside
  // a 1.2 x 20 m hallway (clearance 0.6 m) no robot can leave for the square, as furniture
  // walls off such pockets in lab_ipa_furnitures.png. The hallway is where a tour can go.
  cv::Mat img(60, 240, CV_8U, cv::Scalar(0));
  img(cv::Rect(2, 2, 30, 30)).setTo(254);    // the square: x in [0.2, 3.2]
  img(cv::Rect(36, 20, 200, 12)).setTo(254); // the hallway: x in [3.6, 23.6]
  cv::imwrite(temp_dir() + "/pocket.pgm", img);
  const std::string yaml = write_file("pocket.yaml",
                                      "image: pocket.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const World w = load_world(yaml);
  EXPECT_GT(w.start.x, 3.6);
  EXPECT_LT(w.start.x, 23.6);
}

void expect_refused(const std::string& name, const std::string& text, const std::string& key)
{
  const std::string path = write_file(name, text);
  try {
    load_world(path);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const config::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(key), std::string::npos) << "expected key '" << key << "' in: " << what;
  }
}

TEST(WorldLoading, MalformedWorldsAreRefusedWithFileAndKey)
{
  const std::string wall = "walls:\n  - {a: [0, 0], b: [5, 0]}\n";
  expect_refused("bad1.yaml", "walls:\n  - {a: [0, 0, 1], b: [5, 0]}\n", "walls[0].a");
  expect_refused("bad2.yaml", "walls:\n  - {a: [0, 0], b: [5, x]}\n", "walls[0].b");
  expect_refused("bad3.yaml", wall + "doors:\n  - {name: d, hinge: [0, 0], latch: [0.1, 0]}\n", "doors[0].latch");
  expect_refused("bad4.yaml", wall + "regions:\n  - {name: r, kind: attic, polygon: [0, 0, 1, 0, 1, 1]}\n", "regions[0].kind");
  expect_refused("bad5.yaml", wall + "regions:\n  - {name: r, polygon: [0, 0, 1, 0, 1]}\n", "regions[0].polygon");
  expect_refused("bad6.yaml", wall + "gateways:\n  - {name: g, class: door, points: [0, 0], from: nowhere}\n", "gateways[0].from");
  expect_refused("bad6b.yaml", wall + "regions:\n  - {name: r, polygon: [0, 0, 1, 0, 1, 1]}\ngateways:\n  - {name: g, class: x_crossing, points: [0, 0], joins: [r, nowhere]}\n",
                 "gateways[0].joins");
  expect_refused("bad7.yaml", wall + "wals: []\n", "wals");
  expect_refused("bad8.yaml", wall + "tables:\n  - {center: [1, 1], size: [0.2, 0.2], leg_size: 0.1}\n", "tables[0].leg_size");
  expect_refused("bad9.yaml", wall + "people:\n  - {name: p, path: [1, 1], speed: -1}\n", "people[0].speed");
  expect_refused("bad10.yaml", wall + "doors:\n  - {name: d, hinge: [0, 0], latch: [1, 0], schedule: [{t: 5, open: false}, {t: 2, open: true}]}\n",
                 "doors[0].schedule[1].t");
  expect_refused("bad11.yaml", "name: empty\n", "walls");
  expect_refused("bad12.yaml", wall + "image: {file: does_not_exist.png}\n", "does_not_exist.png");
  expect_refused("bad13.yaml", "walls: [\n", "not valid YAML");
}

void expect_bad_world_refused(const testing::BadFile& f)
{
  SCOPED_TRACE(f.kind + " " + f.path);
  try {
    load_world(f.path);
    ADD_FAILURE() << f.path << " was loaded as a world";
  } catch (const config::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(f.path + ": ", 0), 0u) << e.what();
  }
}

// Issue 35: random bytes, an empty file and one cut off mid-content are refused naming the file,
// for each kind of world: rgnav YAML, a bare PGM and a bare PNG (a decoder alone fills the
// missing rows of a cut-off PGM with zeros: walls where the file ended).
TEST(WorldLoading, RandomBytesEmptyAndCutOffWorldFilesAreRefusedNamingThem)
{
  testing::TempDir dir("bad_worlds");
  const std::string office = read_file(kWorlds + "/office.yaml");
  const size_t mid_line = office.find("{", office.size() / 2) + 5;   // inside a flow mapping
  for (const auto& f : testing::write_bad_files(dir.path(), "world.yaml", office, mid_line)) expect_bad_world_refused(f);
  cv::Mat img(40, 60, CV_8U, cv::Scalar(254));
  img.row(0).setTo(0);
  img.row(39).setTo(0);
  for (const char* ext : {".pgm", ".png"}) {
    const std::string valid = dir.file(std::string("valid") + ext);
    cv::imwrite(valid, img);
    ASSERT_FALSE(load_world(valid).walls.empty());
    const std::string bytes = testing::read_file(valid);
    for (const auto& f : testing::write_bad_files(dir.path(), std::string("map") + ext, bytes, bytes.size() * 2 / 3))
      expect_bad_world_refused(f);
  }
  // A config cut off inside its header comment is only comments: no world, not an empty one.
  testing::write_bytes(dir.file("comment.yaml"), "# rgnav world (format: config/worlds/README.md)\n# cut he");
  expect_bad_world_refused({"only comments", dir.file("comment.yaml")});
}

TEST(WorldLoading, ResolvesWorldNames)
{
  EXPECT_EQ(resolve_world_path("office", kWorlds), kWorlds + "/office.yaml");
  EXPECT_THROW(resolve_world_path("no_such_world", kWorlds), config::ConfigError);
}

}  // namespace
}  // namespace rgnav::sim
