// End to end: a short simulated drive through the office world (lobby, hallway, through a door
// into an office) is written as an LCM log (LASER_FRONT + ODOMETRY, a few hundred scans), and
// rgnav_rgmap_offline maps it twice: rgmap.json must exist, parse, hold a region, and be
// byte-identical between the runs (deterministic on message time); every file written opens in
// the standard tool for its format.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "importers/lcm_log_io.h"
#include "rgmap/saved_map.h"
#include "rgmap/rgmap_json.h"
#include "sim/simulator.h"
#include "sim/step_order.h"
#include "sim/waypoint_follower.h"
#include "sim/world_yaml.h"

namespace rgnav {
namespace {

namespace fs = std::filesystem;

constexpr int kEveryNthScan = 8;   // ~9 Hz: a few hundred scans for ~45 s of driving

importers::ImportedLog simulated_log()
{
  sim::World world = sim::load_world(std::string(RGNAV_CONFIG_DIR) + "/worlds/office.yaml");
  world.people.clear();   // a walker in the way would stop this fixed route
  sim::SimulatorOptions options;   // seed 1: deterministic
  sim::Simulator simulator(world, options);
  sim::WaypointFollower follower({{20, 2}, {20, 13}, {13, 13}, {13, 10}}, [&simulator] { return simulator.truth(); });
  simulator.set_command_source(&follower);
  importers::ImportedLog log;
  log.format = "lcm";
  int64_t n = 0;
  while (!follower.done() && simulator.time_s() < 90.0) {
    const auto out = simulator.step(std::chrono::microseconds(13333));
    sim::in_time_order(
        out,
        [&](const sim::OdometrySample& o) {
          log.add_odometry({o.utime, o.seq, o.odom_from_base.x, o.odom_from_base.y, o.odom_from_base.theta});
        },
        [&](const sensors::LaserScan& s) {
          if (n++ % kEveryNthScan == 0) log.add_scan(sensors::with_message_precision(s));
        });
  }
  EXPECT_TRUE(follower.done()) << "the drive did not finish in 90 s of simulated time; at " << simulator.truth().x << ", "
                               << simulator.truth().y << " heading for waypoint " << follower.next_index()
                               << ", collisions " << simulator.collisions();
  return log;
}

std::string slurp(const fs::path& p)
{
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(RgMapOffline, ShortSimulatedLogGivesTheSameRgMapTwice)
{
  const fs::path dir = fs::temp_directory_path() / ("rgmap_e2e_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto log = simulated_log();
  ASSERT_GE(log.scans.size(), 200u);
  ASSERT_LE(log.scans.size(), 1000u);
  importers::write_lcm_log(log, (dir / "drive.lcmlog").string());

  for (const char* run : {"a", "b"}) {
    const std::string cmd = std::string(RGMAP_OFFLINE_BIN) + " " + (dir / "drive.lcmlog").string() + " --out " +
                            (dir / run).string() + " --config " RGNAV_CONFIG_DIR "/scan_mapper.yaml > " +
                            (dir / run).string() + ".out 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir / (std::string(run) + ".out"));
  }
  const fs::path a = dir / "a" / "rgmap.json";
  ASSERT_TRUE(fs::exists(a));
  const rgmap::RgMap map = rgmap::load_saved_map(a.string());
  int live = 0;
  for (const auto& [id, r] : map.regions()) live += r.state != rgmap::Region::State::kMerged;
  EXPECT_GE(live, 1);
  EXPECT_GT(map.last_scan_id, 0);
  EXPECT_TRUE(map.consistency_problems().empty());
  for (const char* f : {"trajectory.txt", "aligned_scans.lcmlog", "map.png", "rgmap.svg", "rgmap.png",
                        "rgmap_global.pgm", "rgmap_global.yaml", "summary.json"})
    EXPECT_TRUE(fs::exists(dir / "a" / f)) << f;
  // Each export opens in the standard tool for its format, as it is (issue 36: rgmap.json once
  // had a header line before its JSON).
  const std::vector<std::pair<std::string, std::string>> readers = {
      {"rgmap.json", "python3 -m json.tool"},
      {"summary.json", "python3 -m json.tool"},
      {"rgmap.svg", "xmllint --noout"},
      {"map.png", "identify"},
      {"rgmap.png", "identify"},
      {"rgmap_global.pgm", "identify"},
      {"rgmap_global.yaml", "python3 -c 'import sys, yaml; assert isinstance(yaml.safe_load(open(sys.argv[1])), dict)'"}};
  for (const auto& [file, reader] : readers) {
    const std::string cmd = reader + " " + (dir / "a" / file).string() + " > " + (dir / "reader.out").string() + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << file << " refused by `" << reader << "`: " << slurp(dir / "reader.out");
  }
  EXPECT_EQ(slurp(a), slurp(dir / "b" / "rgmap.json"));
  EXPECT_EQ(slurp(dir / "a" / "trajectory.txt"), slurp(dir / "b" / "trajectory.txt"));

  // The same log with its odometry taken as given poses (the corrected-log mode of the benchmark).
  const std::string cmd = std::string(RGMAP_OFFLINE_BIN) + " " + (dir / "drive.lcmlog").string() + " --poses-as-given --no-pictures --out " +
                          (dir / "given").string() + " > " + (dir / "given.out").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir / "given.out");
  EXPECT_GE(rgmap::load_saved_map((dir / "given" / "rgmap.json").string()).regions().size(), 1u);
  EXPECT_FALSE(fs::exists(dir / "given" / "rgmap.svg"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rgnav
